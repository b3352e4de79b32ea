#!/usr/bin/env python3
"""Rolling cylinder on a 60 degree incline (VERIFICATION.md 2.4) with
'contact side = material points': the centre-of-mass distance and speed at
0.2 s and 0.4 s against rolling without slip, a = (2/3) g sin 60, for the
disk's points (background-cell lattice in a 64-gon, or O-grid Gmsh disks),
the penalty factor and the contact damping. Prints a Markdown table.

    usage: rolling_study.py <talus executable> [work dir] [--quick | --refine]

--refine: the grid and the disk refined together (h = 0.05, 0.025,
0.0125 m with O-grid disks of 8, 16, 32 cells per side, 4 x 4 points per
cell), penalty factors 100 and 1, no damping.

The inputs come from make_rolling_cylinder.py (same directory); each run
takes a few seconds on one core.
"""
import csv
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rolling_cylinder as cyl  # noqa: E402

G, THETA, RHO = 9.81, math.radians(60.), math.radians(20.)
A_ROLL = 2. / 3. * G * math.sin(THETA)
T_DIR = (math.cos(RHO), math.sin(RHO))


def run(talus, work, name, ogrid, ppc, factor, damping, cell):
    path = os.path.join(work, name + ".prm")
    cyl.write(path, 0.7, "friction", 2. / 3., points_contact=True,
              ogrid=ogrid, cell=cell, ppc=ppc)
    text = open(path).read().replace(
        "set contact side = material points",
        "set contact side = material points\n"
        f"    set penalty factor = {factor}\n"
        f"    set contact damping = {damping}")
    open(path, "w").write(text)
    out = subprocess.run([talus, name + ".prm"], cwd=work, capture_output=True, text=True)
    log = out.stdout + out.stderr
    errors = [float(e) for e in re.findall(r"error at t = [0-9.]+: displacement ([0-9.e+-]+)", log)]
    rejected = log.count("rejected")
    rows = list(csv.DictReader(open(os.path.join(work, "output-" + name, "time_series.csv"))))
    m = float(rows[0]["mass"])
    speed = {}
    for r in rows:
        t = float(r["time"])
        speed[round(t, 6)] = (float(r["momentum_x"]) * T_DIR[0] + float(r["momentum_y"]) * T_DIR[1]) / m
    v4 = speed.get(0.4, float("nan"))
    n_points = re.search(r"material points: (\d+)", log).group(1)
    return errors, v4, rejected, n_points


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    talus = os.path.abspath(args[0])
    work = os.path.abspath(args[1] if len(args) > 1 else "rolling_study")
    os.makedirs(work, exist_ok=True)
    bodies = [("lattice", 0, 2), ("O-grid 8, 2x2", 8, 2), ("O-grid 8, 4x4", 8, 4),
              ("O-grid 16, 2x2", 16, 2)]
    factors = [100, 1, 0.1]
    dampings = [0, 5]
    cells = [0.05]
    if "--quick" in sys.argv:
        bodies, factors = bodies[1:3], [100, 0.1]
    runs = [(cell, body, f, d) for cell in cells for body in bodies for f in factors for d in dampings]
    if "--refine" in sys.argv:
        runs = [(h, (f"O-grid {m}, 4x4", m, 4), f, 0)
                for f in [100, 1] for h, m in [(0.05, 8), (0.025, 16), (0.0125, 32)]]
    s2, s4 = 0.5 * A_ROLL * 0.2 ** 2, 0.5 * A_ROLL * 0.4 ** 2
    print("| h [m] | disk points | penalty factor | contact damping | points | "
          "error s(0.2 s) | error s(0.4 s) | v(0.4 s) error | rejected steps |")
    print("|---|---|---|---|---|---|---|---|---|")
    for cell, (label, ogrid, ppc), factor, damping in runs:
        name = f"roll_h{cell}_o{ogrid}p{ppc}_f{factor}_d{damping}"
        errors, v4, rejected, n = run(talus, work, name, ogrid, ppc, factor, damping, cell)
        e2 = "%.2f %%" % (100 * errors[0] / s2) if errors else "failed"
        e4 = "%.2f %%" % (100 * errors[1] / s4) if len(errors) > 1 else "failed"
        print(f"| {cell} | {label} | {factor} | {damping} | {n} | {e2} | {e4} | "
              f"{100 * (v4 / (A_ROLL * 0.4) - 1):+.2f} % | {rejected} |", flush=True)


if __name__ == "__main__":
    main()
