#!/usr/bin/python3
"""Plot several Lube et al. 2005 collapse series against the 2D laws.

usage: plot_lube_study.py [contrib/granular/lube_study/results.csv]
                          [-o doc/figures/collapse_lube2005_study.png]

results.csv holds one row per run (study, a, cell, phi, note, exit_code,
runout, max_height, runout_normalised, height_normalised, ...); the runs
with the same friction angle, cell size and note form one labelled marker
series (the columns with another material, phi < 25 deg, and the series of
a single column, which plot_lube_convergence.py shows, are left out). Left panel:
(L - L0)/L0 against a = H0/L0 with the Lube law (1.2 a for a < 1.8,
1.9 a^(2/3) for a > 2.8) and its +-15 % band; right panel: H/L0 with a
(a < 1.15) and a^(2/5) above, and, dashed, the final height of true-2D
collapses of aluminium rods (h0/h = 1.42 a^(2/3) for a > 0.65, H/L0 = a
below; abstract of arXiv:1512.05180, "Failure mechanism of true 2D
granular flows"). Used for the friction-angle, grid and wall
sensitivity study of doc/verification.md ("Lube series at 10 mm, and what the
grid dependence is not"). Needs
Debian's python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_collapse import lube_height, lube_runout, linspace  # noqa: E402

MARKERS = "osD^v<>"


def true2d_height(a):
    """H/L0 of true-2D rod collapses: h0/h = 1.42 a^(2/3) above a = 0.65."""
    return a if a < 0.65 else a / (1.42 * a ** (2. / 3.))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", nargs="?",
                        default="contrib/granular/lube_study/results.csv")
    parser.add_argument("-o", "--output",
                        default="doc/figures/collapse_lube2005_study.png")
    parser.add_argument("--tolerance", type=float, default=0.15)
    args = parser.parse_args()

    fig, axes = plt.subplots(1, 2, figsize=(10, 5.2))
    tol = args.tolerance
    for ax, law, ranges, label in (
            (axes[0], lube_runout, [(0.3, 1.8), (2.8, 10.)], "(L - L0)/L0"),
            (axes[1], lube_height, [(0.3, 1.15), (1.15, 10.)], "H/L0")):
        for i, (lo, hi) in enumerate(ranges):
            a = linspace(lo + 1e-9, hi - 1e-9)
            y = [law(v) for v in a]
            ax.plot(a, y, "k-",
                    label="Lube et al. 2005 (2D)" if i == 0 else None)
            ax.fill_between(a, [v * (1 - tol) for v in y],
                            [v * (1 + tol) for v in y], color="0.85",
                            label="±%g %%" % (100 * tol) if i == 0 else None)
        if law is lube_height:
            a = linspace(0.3, 10.)
            ax.plot(a, [true2d_height(v) for v in a], "k--", lw=1,
                    label="true 2D, aluminium rods (arXiv:1512.05180)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("aspect ratio a = H0/L0")
        ax.set_ylabel(label)

    groups = {}
    with open(args.results) as f:
        for row in csv.DictReader(f):
            try:
                phi, cell = float(row["phi"]), float(row["cell"])
                point = (float(row["a"]), float(row["runout_normalised"]),
                         float(row["height_normalised"]))
            except (KeyError, ValueError):
                print("skipping %s" % row, file=sys.stderr)
                continue
            if phi < 25.:
                continue
            key = (phi, -cell, row.get("note", ""))
            groups.setdefault(key, []).append(point)
    for k, key in enumerate(sorted(groups)):
        phi, cell, note = key[0], -key[1], key[2]
        rows = sorted(groups[key])
        if len(rows) < 2:
            continue  # one column only: plot_lube_convergence.py shows it
        name = "phi = %g deg" % phi
        if cell > 0.:  # cell 0: runs of several cell sizes, see the note
            name += ", %g mm" % (1000. * cell)
        if note and not note.startswith("from doc"):
            name += ", " + note
        marker = MARKERS[k % len(MARKERS)]
        for ax, col in ((axes[0], 1), (axes[1], 2)):
            ax.plot([r[0] for r in rows], [r[col] for r in rows],
                    marker=marker, ls=":", lw=0.8, ms=5, label=name)
    axes[0].set_title("Runout")
    axes[1].set_title("Final height")
    handles, labels = axes[0].get_legend_handles_labels()
    h1, l1 = axes[1].get_legend_handles_labels()
    handles += [h for h, l in zip(h1, l1) if l.startswith("true 2D")]
    labels += [l for l in l1 if l.startswith("true 2D")]
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=[0, 0.2, 1, 1])
    fig.savefig(args.output, dpi=150)
    print("wrote %s" % args.output)


if __name__ == "__main__":
    main()
