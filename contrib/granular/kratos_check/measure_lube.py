#!/usr/bin/env python3
"""Lube et al. 2005 deposit measures of a Kratos material point dump (mp_t*.csv
written by run_case.py), with the definitions of Talus' IO::DepositProfile
(measure.py): L, H, (L - L0)/L0 and H/L0 with the nominal L0 (default 0.1 m),
the Lube 2D laws, and the material volume and mass over time.
Usage: measure_lube.py CASEDIR --a 1.5 [--L0 0.1] [--t T]
"""
import argparse
import glob
import math
import os

from measure import read_mps, measure


def lube(a):
    run = 1.2 * a if a < 1.8 else 1.9 * a ** (2. / 3.)
    h = a if a < 1.15 else a ** 0.4
    return run, h


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("casedir")
    ap.add_argument("--a", type=float, required=True)
    ap.add_argument("--L0", type=float, default=0.1)
    ap.add_argument("--t", default=None)
    a = ap.parse_args()
    files = sorted(glob.glob(os.path.join(a.casedir, "mp_t*.csv")))
    mps0 = read_mps(os.path.join(a.casedir, "mp_t0.000.csv"))
    dp = math.sqrt(sum(p["volume"] for p in mps0) / len(mps0))
    V0 = sum(p["volume"] for p in mps0)
    M0 = sum(p["mass"] for p in mps0)
    L0m, H0m, _ = measure(mps0, dp, 0.01)
    print(f"{a.casedir}: N={len(mps0)} d_p={dp*1e3:.2f} mm  measured L0={L0m:.4f} H0={H0m:.4f}  V0={V0:.6e} M0={M0:.4f}")
    print(" t      L [m]   (L-L0)/L0  H [m]   H/L0   V/V0     M/M0    max|v|")
    rl, rh = lube(a.a)
    for f in files:
        mps = read_mps(f)
        L, H, _ = measure(mps, dp, 0.01)
        V = sum(p["volume"] for p in mps)
        M = sum(p["mass"] for p in mps)
        vmax = max(math.hypot(p["vx"], p["vy"]) for p in mps)
        t = os.path.basename(f)[4:-4]
        print(f" {t}  {L:.4f}  {(L-a.L0)/a.L0:7.3f}  {H:.4f}  {H/a.L0:6.3f}  {V/V0:.4f}  {M/M0:.5f}  {vmax:.3f}")
    print(f"Lube: (L-L0)/L0 = {rl:.3f}, H/L0 = {rh:.3f};  last: runout err {100*((L-a.L0)/a.L0/rl-1):+.1f} %, "
          f"height err {100*(H/a.L0/rh-1):+.1f} %")


if __name__ == "__main__":
    main()
