#!/usr/bin/python3
"""Plot the runout of the a = 0.5 Lube collapses against the grid resolution.

usage: plot_lube_convergence.py [contrib/granular/lube_study/results.csv]
                                [-o doc/figures/collapse_lube2005_convergence.png]
                                [-a 0.5]

results.csv is the table of contrib/granular/lube_study/run.sh (study, a,
cell, phi, note, exit_code, runout, max_height, runout_normalised, ...).
The runs of one aspect ratio a (default 0.5) with the same friction angle
and note form one line of (L - L0)/L0 against the number of cells over the
column height, H0/h (L0 = 0.1 m, so H0 = 0.05 m at a = 0.5), with Lube et
al.'s law and its +-15 % band. Used for the grid-convergence study of
doc/verification.md ("Lube series, resolved, μ(I)"). Needs Debian's
python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_collapse import lube_runout  # noqa: E402

MARKERS = "osD^v<>ph*"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", nargs="?",
                        default="contrib/granular/lube_study/results.csv")
    parser.add_argument("-o", "--output",
                        default="doc/figures/collapse_lube2005_convergence.png")
    parser.add_argument("-a", "--aspect-ratio", type=float, default=0.5)
    parser.add_argument("--length", type=float, default=0.1,
                        help="L0 of the runs [m] (default 0.1)")
    parser.add_argument("--tolerance", type=float, default=0.15)
    args = parser.parse_args()

    groups = {}
    with open(args.results) as f:
        for row in csv.DictReader(f):
            try:
                a, cell = float(row["a"]), float(row["cell"])
                value = float(row["runout_normalised"])
                phi = float(row["phi"])
            except (KeyError, ValueError):
                continue
            if abs(a - args.aspect_ratio) > 1e-9:
                continue
            note = row.get("note", "")
            if note.startswith("from doc") or note.startswith("front at"):
                note = ""
            groups.setdefault((phi, note), {})[cell] = value
    if not groups:
        sys.exit("plot_lube_convergence.py: no run with a = %g in %s"
                 % (args.aspect_ratio, args.results))

    fig, ax = plt.subplots(figsize=(10, 5.2))
    H0 = args.aspect_ratio * args.length
    law = lube_runout(args.aspect_ratio)
    ax.axhline(law, color="k", label="Lube et al. 2005 (2D)")
    ax.axhspan(law * (1 - args.tolerance), law * (1 + args.tolerance),
               color="0.85", label="±%g %%" % (100 * args.tolerance))
    for k, key in enumerate(sorted(groups)):
        cells = sorted(groups[key], reverse=True)
        if len(cells) < 2:
            continue
        phi, note = key
        name = "phi = %g deg" % phi + (", " + note if note else "")
        ax.plot([H0 / c for c in cells], [groups[key][c] for c in cells],
                marker=MARKERS[k % len(MARKERS)], ls="-" if k < 10 else "--",
                lw=0.8, ms=5, color=plt.get_cmap("tab10")(k % 10), label=name)
    ax.set_xscale("log", base=2)
    ax.set_xlabel("cells over the column height H0/h")
    ax.set_ylabel("(L - L0)/L0")
    ax.set_title("a = %g: runout under grid refinement" % args.aspect_ratio)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.))
    fig.tight_layout()
    fig.savefig(args.output, dpi=150)
    print("wrote %s" % args.output)


if __name__ == "__main__":
    main()
