#!/usr/bin/python3
"""Plot granular column collapse results against Bui et al. 2008 and Lube et al. 2005.

usage: plot_collapse.py results.csv [-o doc/figures] [--data data] [--bui-only]

results.csv is written by contrib/granular/run_collapse_series.sh (one row
per run: input, exit_code, L0, H0, a, runout, max_height, ..., profile).
Writes three PNGs to the output directory:
  collapse_bui2008_surface.png  final surface h(x) of the runs whose input
      name contains 'bui' (their deposit_profile.csv) against the
      experimental points (data/bui2008_final_surface.csv, +-3 mm), the toe
      range 0.42-0.44 m and the failure line, with the measured failure
      lines (failure_line.csv, dashed) of the runs that compared one;
  collapse_lube2005_runout.png  (L - L0)/L0 against a = H0/L0 with the Lube
      2D law (1.2 a for a < 1.8, 1.9 a^(2/3) for a > 2.8) and a +-15 % band;
  collapse_lube2005_height.png  H/L0 against a with a (a < 1.15) and
      a^(2/5) above, +-15 %.
Runs without numbers (failed) are skipped with a note. Needs Debian's
python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_xy(path):
    """'x, h' pairs of a CSV with '#' comments and an optional header."""
    xs, ys = [], []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = [p.strip() for p in line.split(",")]
            try:
                x, y = float(parts[0]), float(parts[1])
            except (ValueError, IndexError):
                continue  # header
            xs.append(x)
            ys.append(y)
    return xs, ys


def lube_runout(a):
    return 1.2 * a if a < 1.8 else (1.9 * a ** (2. / 3.) if a > 2.8 else None)


def lube_height(a):
    return a if a < 1.15 else a ** 0.4


def linspace(a, b, n=100):
    return [a + (b - a) * i / (n - 1) for i in range(n)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("-o", "--output", default="doc/figures")
    parser.add_argument("--data", default="data",
                        help="directory of bui2008_*.csv (default data)")
    parser.add_argument("--bui-only", action="store_true",
                        help="draw collapse_bui2008_surface.png only")
    parser.add_argument("--tolerance", type=float, default=0.15,
                        help="band around the Lube laws (default 0.15)")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)

    rows = []
    with open(args.results) as f:
        for row in csv.DictReader(f):
            try:
                for key in ("a", "runout_normalised", "height_normalised"):
                    row[key] = float(row[key])
            except (KeyError, ValueError):
                print("skipping %s (no result, exit code %s)"
                      % (row.get("input"), row.get("exit_code")), file=sys.stderr)
                continue
            rows.append(row)

    # (i) Bui et al. 2008: final surfaces.
    fig, ax = plt.subplots(figsize=(8, 3.5))
    xe, he = read_xy(os.path.join(args.data, "bui2008_final_surface.csv"))
    ax.errorbar(xe, he, xerr=0.003, yerr=0.003, fmt="ko", ms=4,
                label="experiment (Bui et al. 2008, ±3 mm)")
    ax.axvspan(0.42, 0.44, color="0.85", label="experimental toe 0.42-0.44 m")
    xf, hf = read_xy(os.path.join(args.data, "bui2008_failure_line.csv"))
    ax.plot(xf, hf, "k--", lw=1, label="experimental failure line")
    ax.plot([0, 0.2, 0.2], [0.1, 0.1, 0], color="0.5", lw=1, ls=":",
            label="initial column")
    for row in rows:
        if "bui" not in os.path.basename(row["input"]).lower():
            continue
        try:
            x, h = read_xy(row["profile"])
        except OSError:
            print("no profile %s" % row["profile"], file=sys.stderr)
            continue
        line = ax.step(x, h, where="mid",
                       label="%s (exit %s)" % (os.path.basename(row["input"]),
                                               row["exit_code"]))[0]
        # The measured failure line (edge of the unmoved material, initial
        # positions), if the input compared one.
        failure = os.path.join(os.path.dirname(row["profile"]),
                               "failure_line.csv")
        if os.path.exists(failure):
            v, s_f = [], []
            with open(failure) as f:
                for r in csv.DictReader(l for l in f if not l.startswith("#")):
                    v.append(float(r["v"]))
                    s_f.append(float(r["s_f"]))
            ax.plot(s_f, v, ls="--", lw=1, color=line.get_color())
    ax.set_xlabel("distance from the wall x [m]")
    ax.set_ylabel("height h [m]")
    ax.set_xlim(0, 0.5)
    ax.set_ylim(0, 0.12)
    ax.set_title("Granular column collapse, final surface (Bui et al. 2008)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "collapse_bui2008_surface.png"), dpi=150)
    plt.close(fig)

    if args.bui_only:
        print("wrote collapse_bui2008_surface.png in %s" % args.output)
        return

    # (ii), (iii) Lube et al. 2005.
    tol = args.tolerance
    for key, law, name, label, ranges in (
            ("runout_normalised", lube_runout, "collapse_lube2005_runout.png",
             "(L - L0)/L0", [(0.05, 1.8), (2.8, 10.)]),
            ("height_normalised", lube_height, "collapse_lube2005_height.png",
             "H/L0", [(0.05, 1.15), (1.15, 10.)])):
        fig, ax = plt.subplots(figsize=(5.5, 4))
        for i, (lo, hi) in enumerate(ranges):
            a = linspace(lo + 1e-9, hi - 1e-9)
            y = [law(v) for v in a]
            ax.plot(a, y, "k-", label="Lube et al. 2005 (2D)" if i == 0 else None)
            ax.fill_between(a, [v * (1 - tol) for v in y],
                            [v * (1 + tol) for v in y], color="0.85",
                            label="±%g %%" % (100 * tol) if i == 0 else None)
        if key == "runout_normalised":
            ax.axvspan(1.8, 2.8, color="w", hatch="//", ec="0.7",
                       label="no fit (1.8 < a < 2.8)")
        # Lube's law is for sand-like columns: the Bui runs (aluminium
        # rods, another material) are not plotted against it.
        pts = [(r["a"], r[key]) for r in rows
               if "bui" not in os.path.basename(r["input"]).lower()]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "ro",
                    label="Talus")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("aspect ratio a = H0/L0")
        ax.set_ylabel(label)
        ax.set_title("Column collapse: %s" % label)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(args.output, name), dpi=150)
        plt.close(fig)
    print("wrote collapse_bui2008_surface.png, collapse_lube2005_runout.png, "
          "collapse_lube2005_height.png in %s" % args.output)


if __name__ == "__main__":
    main()
