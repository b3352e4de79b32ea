#!/usr/bin/python3
"""Plot the time series CSV written by talus (one PNG, four panels).

usage: plot_time_series.py file.csv [-o out.png] [--title T]

Panels: energies, momentum components, time step and Newton iterations
(twin axes), relative mass change.  Columns are picked by header name, extra
columns are ignored.  Needs Debian's python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import math
import sys

REQUIRED = ["time", "dt", "newton_iterations", "mass",
            "kinetic_energy", "strain_energy", "gravitational_energy",
            "total_energy"]
MOMENTUM = ["momentum_x", "momentum_y", "momentum_z"]


def fail(message):
    sys.exit("plot_time_series.py: " + message)


def read_columns(path):
    """Return {header name: list of floats} for every column of the CSV."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    if not rows:
        fail(f"{path} is empty")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in REQUIRED if c not in header]
    if missing:
        fail(f"{path} lacks the column(s) {', '.join(missing)}; "
             f"header is: {','.join(header)}")
    columns = {h: [] for h in header}
    for line, row in enumerate(rows[1:], start=2):
        if not row or all(not x.strip() for x in row):
            continue                       # blank line
        if len(row) < len(header):
            fail(f"{path}:{line}: {len(row)} fields, header has {len(header)}")
        for h, x in zip(header, row):
            try:
                columns[h].append(float(x))
            except ValueError:
                fail(f"{path}:{line}: column {h}: '{x}' is not a number")
    if not columns["time"]:
        fail(f"{path} has a header but no data rows")
    return columns


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", help="time_series.csv written by talus")
    parser.add_argument("-o", "--output",
                        help="PNG to write (default: the CSV name with .png)")
    parser.add_argument("--title", help="figure title (default: CSV path)")
    args = parser.parse_args()

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("matplotlib not found: apt-get install python3-matplotlib and "
             "run with /usr/bin/python3")

    c = read_columns(args.csv)
    out = args.output or (args.csv[:-4] if args.csv.endswith(".csv")
                          else args.csv) + ".png"
    t = c["time"]

    fig, ax = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    fig.suptitle(args.title or args.csv)

    # Energies [J]
    a = ax[0][0]
    for name, style in [("kinetic_energy", "-"), ("strain_energy", "-"),
                        ("gravitational_energy", "-"), ("total_energy", "k--")]:
        a.plot(t, c[name], style, label=name.replace("_energy", ""))
    a.set_ylabel("energy [J]")
    a.set_title("Energies")
    a.legend(fontsize="small")

    # Momentum components [kg m/s]; z only when present and not all zero
    a = ax[0][1]
    for name in MOMENTUM:
        if name in c and (name != "momentum_z" or any(c[name])):
            a.plot(t, c[name], label=name.replace("momentum_", ""))
    a.set_ylabel("momentum [kg m/s]")
    a.set_title("Momentum")
    a.legend(fontsize="small")

    # Time step and Newton iterations on twin axes
    a = ax[1][0]
    a.plot(t, c["dt"], "C0-", label="dt")
    a.set_ylabel("dt [s]", color="C0")
    a.tick_params(axis="y", labelcolor="C0")
    b = a.twinx()
    b.step(t, c["newton_iterations"], "C1-", where="post")
    b.set_ylabel("Newton iterations", color="C1")
    b.tick_params(axis="y", labelcolor="C1")
    b.set_ylim(0, max(c["newton_iterations"]) + 1)
    b.yaxis.get_major_locator().set_params(integer=True)
    a.set_zorder(b.get_zorder() + 1)    # dt drawn over the iteration steps
    a.patch.set_visible(False)
    a.set_title("Time step and Newton iterations")
    a.set_xlabel("time [s]")

    # Relative mass change (m - m0)/m0
    a = ax[1][1]
    m0 = c["mass"][0]
    if m0 == 0 or not math.isfinite(m0):
        fail(f"initial mass is {m0}: cannot form the relative change")
    a.plot(t, [(m - m0) / m0 for m in c["mass"]], "C2-", label="mass")
    if "lost_mass" in c and any(c["lost_mass"]):
        a.plot(t, [-m / m0 for m in c["lost_mass"]], "k--",
               label="- lost_mass / m0")
        a.legend(fontsize="small")
    a.set_ylabel("(m - m0) / m0")
    a.set_title(f"Mass (m0 = {m0:.6g} kg)")
    a.set_xlabel("time [s]")

    for a in ax.flat:
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=100)
    except OSError as e:
        fail(f"cannot write {out}: {e.strerror}")
    print(f"plot_time_series.py: wrote {out}")


if __name__ == "__main__":
    main()
