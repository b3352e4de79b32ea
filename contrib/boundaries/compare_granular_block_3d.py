#!/usr/bin/python3
"""Compare the 3D granular block on a grid-aligned slope with tilted gravity
(benchmarks/granular_3d/block_on_slope.prm, basal friction on the grid's
bottom face) and on a 15 degree slope of boundary particles with vertical
gravity (block_on_rotated_plane.prm, written by make_granular_block_3d.py).

Both are expressed in the slope frame (s down the slope, h along the slope
normal): for every output time the script prints the mean and largest s of
the points (travel and front), the largest h (height of the deposit) and
the kinetic energy from the time series, as a Markdown table.

    usage: compare_granular_block_3d.py <output dir of block_on_slope>
                                        <output dir of block_on_rotated_plane>
"""
import csv
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(
    __file__))))
from plot_particles import read_particles  # noqa: E402
from make_granular_block_3d import T, N, ORIGIN  # noqa: E402


def frames(directory):
    """(time, path) of the particle outputs listed in particles.pvd."""
    root = ET.parse(os.path.join(directory, "particles.pvd")).getroot()
    return [(float(d.get("timestep")), os.path.join(directory, d.get("file")))
            for d in root.iter("DataSet")]


def kinetic_energy(directory):
    with open(os.path.join(directory, "time_series.csv")) as f:
        rows = list(csv.DictReader(f))
    return {float(r["time"]): float(r["kinetic_energy"]) for r in rows}


def slope_coordinates(points, rotated):
    if not rotated:  # the grid is the slope frame
        return points[:, 0], points[:, 2]
    d = points - np.array(ORIGIN)
    return d @ np.array(T), d @ np.array(N)


def nearest(table, t):
    key = min(table, key=lambda k: abs(k - t))
    return table[key]


def main():
    dirs = sys.argv[1:3]
    if len(dirs) != 2:
        sys.exit(__doc__)
    results = []
    for rotated, directory in enumerate(dirs):
        ke = kinetic_energy(directory)
        rows = {}
        for t, path in frames(directory):
            points, _ = read_particles(path)
            s, h = slope_coordinates(points, rotated)
            rows[round(t, 6)] = (len(points), s.mean(), s.max(), s.min(),
                                 h.max(), nearest(ke, t) if t > 0 else
                                 float("nan"))
        results.append(rows)
    s0 = {k: results[k][min(results[k])][1] for k in (0, 1)}
    print("| t [s] | points | mean travel [m] (grid / particles) | front s [m] "
          "| rear s [m] | top h [m] | kinetic energy [J] |")
    print("|---|---|---|---|---|---|---|")
    # output times differ by a fraction of an (adaptive) step: pair each
    # output of the first run with the nearest one of the second
    for t in sorted(results[0]):
        t1 = min(results[1], key=lambda k: abs(k - t))
        if abs(t1 - t) > 0.02:
            continue
        a, b = results[0][t], results[1][t1]
        print("| %.2f | %d / %d | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | "
              "%.3f / %.3f | %.2f / %.2f |" %
              (t, a[0], b[0], a[1] - s0[0], b[1] - s0[1], a[2], b[2],
               a[3], b[3], a[4], b[4], a[5], b[5]))


if __name__ == "__main__":
    main()
