#!/usr/bin/env python3
"""Deposit measures of a Kratos MPM material point dump, the same definitions
as Talus' IO::DepositProfile (doc/verification.md §2.2):
  d_p = sqrt(initial MP volume) (each point a square of its initial area)
  runout L: points sorted by x from the far end, mass accumulated; the front is
     the first point where the accumulated mass exceeds 0.1 % of the total and
     more than 1 point has been passed; L = x_front + d_p/2
  h(x) = max(y + d_p/2) over the points with |x_p - x| <= bin/2 (0 if empty)
Usage: measure.py CASEDIR [--t 1.000] [--bin 0.01] [--json]
"""
import argparse
import csv
import glob
import json
import math
import os

EXP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "data", "bui2008_final_surface.csv")


def read_mps(path):
    with open(path) as f:
        r = csv.DictReader(f)
        return [{k: float(v) for k, v in row.items()} for row in r]


def read_exp():
    xs, hs = [], []
    with open(EXP) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#") or line.startswith("x"):
                continue
            x, h = line.split(",")
            xs.append(float(x))
            hs.append(float(h))
    return xs, hs


def interp(xs, ys, x):
    if x <= xs[0]:
        return ys[0]
    for i in range(1, len(xs)):
        if x <= xs[i]:
            w = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] * (1 - w) + ys[i] * w
    return None  # beyond the data


def measure(mps, dp, bin_w, frac=1e-3, ignored=1):
    mtot = sum(p["mass"] for p in mps)
    srt = sorted(mps, key=lambda p: -p["x"])
    acc = 0.0
    front = srt[-1]["x"]
    for k, p in enumerate(srt):
        acc += p["mass"]
        if acc > frac * mtot and k + 1 > ignored:
            front = p["x"]
            break
    L = front + dp / 2

    def h(x):
        ys = [p["y"] for p in mps if abs(p["x"] - x) <= bin_w / 2 + 1e-12]
        return max(ys) + dp / 2 if ys else 0.0
    H = max(p["y"] for p in mps) + dp / 2
    return L, H, h


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("casedir")
    ap.add_argument("--t", default=None, help="time of the dump (default: the last)")
    ap.add_argument("--bin", type=float, default=0.01)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    files = sorted(glob.glob(os.path.join(a.casedir, "mp_t*.csv")))
    f0 = os.path.join(a.casedir, "mp_t0.000.csv")
    fe = os.path.join(a.casedir, f"mp_t{float(a.t):.3f}.csv") if a.t else files[-1]
    mps0 = read_mps(f0)
    mps = read_mps(fe)
    dp = math.sqrt(sum(p["volume"] for p in mps0) / len(mps0))
    L0, H0, _ = measure(mps0, dp, a.bin)
    L, H, h = measure(mps, dp, a.bin)
    xe, he = read_exp()
    stations = [round(0.05 * i, 2) for i in range(9)]
    prof = {x: h(x) for x in stations}
    # error against the experiment at its own stations (x = 0, 0.04, ..., 0.40)
    errs = [(x, h(x) - he_) for x, he_ in zip(xe, he)]
    worst = max(errs, key=lambda e: abs(e[1]))
    # and at the 0.05 stations, experiment interpolated linearly
    errs5 = [(x, prof[x] - interp(xe, he, x)) for x in stations]
    worst5 = max(errs5, key=lambda e: abs(e[1]))
    vmax = max(math.hypot(p["vx"], p["vy"]) for p in mps)
    res = {"file": os.path.basename(fe), "n_points": len(mps), "d_p": dp,
           "L0": L0, "H0": H0, "runout": L, "runout_err_pct": 100 * (L - 0.43) / 0.43,
           "H": H, "h_at_0.05": prof,
           "max_abs_dh_exp_stations": {"x": worst[0], "dh": worst[1]},
           "max_abs_dh_0.05_stations": {"x": worst5[0], "dh": worst5[1]},
           "dh_exp_stations": {f"{x:.2f}": round(d, 4) for x, d in errs},
           "max_speed": vmax, "bin": a.bin}
    if a.json:
        print(json.dumps(res, indent=1))
    else:
        print(f"{fe}: N={len(mps)} d_p={dp*1e3:.2f} mm  L0={L0:.4f} H0={H0:.4f}")
        print(f"  runout L = {L:.4f} m  ({res['runout_err_pct']:+.1f} % vs 0.43)  H = {H:.4f}  max |v| = {vmax:.3g} m/s")
        print("  h(x): " + "  ".join(f"{x:.2f}:{prof[x]:.4f}" for x in stations))
        print("  h - h_exp at exp stations: " + "  ".join(f"{x:.2f}:{d:+.4f}" for x, d in errs))
        print(f"  largest |h-h_exp| = {abs(worst[1]):.4f} at x = {worst[0]:.2f}"
              f"  (0.05-stations, interpolated exp: {abs(worst5[1]):.4f} at {worst5[0]:.2f})")
    with open(os.path.join(a.casedir, f"measure_{os.path.basename(fe)[:-4]}.json"), "w") as f:
        json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
