#!/usr/bin/python3
"""Compare the deposits of the 3D block on a slope computed on several grids.

usage: compare_block_3d_grids.py FINAL.pvtu [FINAL2.pvtu ...]

For each particle output (the last one of a run of
benchmarks/granular_3d/block_on_slope*.prm): total mass, the mass-weighted
mean travel along the slope (x - x0), the 1 %, 50 % and 99 % mass quantiles
of x (rear, middle and front of the deposit without the few outermost
points), the mass-weighted mean and the 99 % quantile of the height z, and the
spread of the deposit across the slope (1 % to 99 % of y). Used for
doc/verification.md, "3D granular block on a slope".
Needs numpy (/usr/bin/python3 with Debian's python3-numpy).
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                ".."))
from plot_particles import read_particles  # noqa: E402


def quantile(values, weights, q):
    """Weighted quantile: the value below which the fraction q of weight lies."""
    order = np.argsort(values)
    cumulative = np.cumsum(weights[order])
    return values[order][np.searchsorted(cumulative, q * cumulative[-1])]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("%-50s %7s %7s %7s %7s %7s %7s %7s %13s" % (
        "output", "mass", "travel", "x 1%", "x 50%", "x 99%", "z mean",
        "z 99%", "y 1%..99%"))
    for path in sys.argv[1:]:
        points, fields = read_particles(path)
        m = fields["mass"].ravel()
        x0 = fields["initial_position"][:, 0]
        x, y, z = points[:, 0], points[:, 1], points[:, 2]
        print("%-50s %7.3f %7.3f %7.3f %7.3f %7.3f %7.4f %7.4f %6.3f..%6.3f"
              % (path[-50:], m.sum(), np.average(x - x0, weights=m),
                 quantile(x, m, 0.01), quantile(x, m, 0.5),
                 quantile(x, m, 0.99), np.average(z, weights=m),
                 quantile(z, m, 0.99), quantile(y, m, 0.01),
                 quantile(y, m, 0.99)))


if __name__ == "__main__":
    main()
