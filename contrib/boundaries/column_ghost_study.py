#!/usr/bin/env python3
"""Ghost-penalty study on the column under self weight between walls rotated
by 30 degrees (contrib/boundaries/make_rotated_column.py): for each cell size
and ghost penalty factor, run talus and print the displacement error, the
error of the axial point stress a.sigma.a against -rho g (l - Y) relative to
the base stress rho g l (largest; largest over the points with more than 10 %
of a full point's volume; volume-weighted RMS), with and without clipping,
and the mean number of CG iterations per Newton iteration (AMG, the same
system solved with the direct solver gives the stresses).

    usage: column_ghost_study.py <talus> [h ...] [-- factor ...]
Needs numpy. The point stresses come from the debug dump TALUS_DEBUG_STRESS.
"""
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rotated_column as mrc  # noqa: E402

ROT = 30


def run(talus, h, factor, clip, solver, workdir):
    mrc.H = h
    prm = os.path.join(workdir, f"column_rotated_{ROT}.prm")
    mrc.write(prm, ROT, clip=clip, ghost=factor)
    text = open(prm).read()
    text = text.replace("set linear solver = direct",
                        f"set linear solver = {solver}")
    text = text.replace("set test mode = true", "set test mode = false")
    open(prm, "w").write(text)
    env = dict(os.environ, TALUS_DEBUG_STRESS="1")
    out = subprocess.run([talus, os.path.basename(prm)], cwd=workdir,
                         env=env, capture_output=True, text=True).stdout
    return out


def analyse(out):
    r = math.radians(ROT)
    a = np.array([-math.sin(r), math.cos(r)])
    o = np.array([1.0 + mrc.L * math.sin(r) + 0.013, 0.5 + 0.017])
    rows = [list(map(float, re.split(r"\s+", ln.strip())[1:12]))
            for ln in out.splitlines() if ln.startswith("DBGSTRESS")]
    d = np.array(rows)
    X = d[:, 0:2]
    sxx, exx, syy, eyy, sxy, exy = d[:, 4:10].T
    V = d[:, 10]

    def axial(xx, yy, xy):
        return a[0] * a[0] * xx + a[1] * a[1] * yy + 2 * a[0] * a[1] * xy

    err = np.abs(axial(sxx, syy, sxy) - axial(exx, eyy, exy)) / (
        mrc.RHO * mrc.G * mrc.L)
    Y = (X - o) @ a
    large = V > 0.1 * V.max()
    m = re.search(r"displacement ([0-9.e+-]+), stress", out)
    return (float(m.group(1)), err.max(), err[large].max(),
            math.sqrt((V * err ** 2).sum() / V.sum()))


def cg_iterations(out):
    its = [(int(m.group(1)), int(m.group(2))) for m in re.finditer(
        r"Newton\s+(\d+)\s+linear\s+(\d+)", out)]
    return sum(l for _, l in its) / max(1, sum(n for n, _ in its))


def main():
    talus = os.path.abspath(sys.argv[1])
    args = sys.argv[2:]
    if "--" in args:
        i = args.index("--")
        hs, factors = args[:i], args[i + 1:]
    else:
        hs, factors = args, []
    hs = [float(h) for h in hs] or [0.25, 0.125, 0.0625]
    factors = [float(f) for f in factors] or [0, 0.1, 1, 10]
    print("| h [m] | points clipped | ghost penalty factor | displacement "
          "error [m] | axial stress error: largest | largest, points with "
          "> 10 % of a full volume | volume-weighted RMS | CG iterations per "
          "Newton iteration |")
    print("|---|---|---|---|---|---|---|---|")
    for h in hs:
        for clip in (False, True):
            for f in factors:
                with tempfile.TemporaryDirectory() as w:
                    e = analyse(run(talus, h, f, clip, "direct", w))
                    cg = cg_iterations(run(talus, h, f, clip, "CG", w))
                print(f"| {h:g} | {'yes' if clip else 'no'} | {f:g} "
                      f"| {e[0]:.2e} | {e[1]:.3f} | {e[2]:.3f} | {e[3]:.4f} "
                      f"| {cg:.0f} |", flush=True)


if __name__ == "__main__":
    main()
