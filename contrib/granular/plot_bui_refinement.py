#!/usr/bin/python3
"""Plot the Bui et al. 2008 collapse under grid refinement for several models.

usage: plot_bui_refinement.py [-o doc/figures/collapse_bui2008_refinement.png]
           [--earlier FILE.csv] [--surface LABEL] [--data data]
           LABEL:CELL_MM:OUTPUT_DIR [LABEL:CELL_MM:OUTPUT_DIR ...]

Each LABEL:CELL_MM:OUTPUT_DIR names one run: its model label, its cell size
[mm] and the output directory holding its deposit_summary.csv and
deposit_profile.csv (subsection "Deposit profile"). --earlier adds runouts
measured in earlier sessions, rows "label,cell_mm,runout,source" (the
source column says where the number is documented). Left: runout L
against the cell size for every label, with the experiment's toe (0.43 m)
and its 10 % band. Right: the final surfaces h(x) of the runs of
--surface LABEL against the experimental points
(data/bui2008_final_surface.csv) with the 1 cm band. Needs Debian's
python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f
                                   if not line.startswith("#")))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("-o", "--output",
                        default="doc/figures/collapse_bui2008_refinement.png")
    parser.add_argument("--earlier", help="CSV label,cell_mm,runout,source")
    parser.add_argument("--surface", help="label whose surfaces are drawn")
    parser.add_argument("--data", default="data")
    args = parser.parse_args()

    runout = {}   # label -> {cell: L}
    surfaces = []  # (cell, x, h) of the --surface label
    for run in args.runs:
        label, cell, directory = run.split(":", 2)
        cell = float(cell)
        summary = read_rows(os.path.join(directory, "deposit_summary.csv"))
        runout.setdefault(label, {})[cell] = float(summary[0]["runout"])
        if label == args.surface:
            profile = read_rows(os.path.join(directory, "deposit_profile.csv"))
            surfaces.append((cell, [float(r["x"]) for r in profile],
                             [float(r["h"]) for r in profile]))
    if args.earlier:
        for r in read_rows(args.earlier):
            runout.setdefault(r["label"], {}).setdefault(
                float(r["cell_mm"]), float(r["runout"]))

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.axhspan(0.43 * 0.9, 0.43 * 1.1, color="0.9", label="experiment ±10 %")
    left.axhline(0.43, color="k", lw=0.8)
    for label, values in runout.items():
        cells = sorted(values)
        left.plot(cells, [values[c] for c in cells], "o-", label=label)
    left.set_xscale("log")
    ticks = sorted({c for values in runout.values() for c in values})
    left.set_xticks(ticks)
    left.set_xticklabels(["%g" % c for c in ticks])
    left.minorticks_off()
    left.invert_xaxis()
    left.set_xlabel("cell size [mm]")
    left.set_ylabel("runout L [m]")
    left.set_title("Bui et al. 2008: runout under refinement")
    left.legend(fontsize=8)

    exp = read_rows(os.path.join(args.data, "bui2008_final_surface.csv"))
    x_exp = [float(r[list(r)[0]]) for r in exp]
    h_exp = [float(r[list(r)[1]]) for r in exp]
    right.fill_between(x_exp, [h - 0.01 for h in h_exp],
                       [h + 0.01 for h in h_exp], color="0.9",
                       label="experiment ±1 cm")
    right.plot(x_exp, h_exp, "ks", ms=4, label="experiment")
    for cell, x, h in sorted(surfaces, reverse=True):
        right.step(x, h, where="mid", label="%g mm" % cell)
    right.set_xlim(0, 0.55)
    right.set_ylim(0, 0.11)
    right.set_xlabel("x [m]")
    right.set_ylabel("h [m]")
    right.set_title("final surface, %s" % (args.surface or "-"))
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
