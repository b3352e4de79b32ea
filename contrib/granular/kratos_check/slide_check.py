#!/usr/bin/env python3
"""Sanity check of Kratos' frictional slip floor: an elastic block
(0.05 x 0.02 m, rho 2650, E 0.84 MPa) launched at v0 = 1 m/s along the floor
with Coulomb friction mu. Exact rigid-block answer: deceleration mu*g, stop at
t* = v0/(mu g) after s* = v0^2/(2 mu g).
Usage: slide_check.py RUNDIR  (after make_case.py RUNDIR ... --v0 1 and run_case.py --dump 0.02)
"""
import csv
import glob
import os
import sys

d = sys.argv[1]
mu = float(sys.argv[2]) if len(sys.argv) > 2 else 0.36
g = 9.81
v0 = 1.0
ts, xs, vs = [], [], []
for f in sorted(glob.glob(os.path.join(d, "mp_t*.csv"))):
    t = float(os.path.basename(f)[4:-4])
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(f))]
    m = sum(r["mass"] for r in rows)
    ts.append(t)
    xs.append(sum(r["mass"] * r["x"] for r in rows) / m)
    vs.append(sum(r["mass"] * r["vx"] for r in rows) / m)
tstar = v0 / (mu * g) if mu > 0 else 1e9
print(f"mu = {mu}: exact stop t* = {tstar:.4f} s, slide s* = {(v0**2/(2*mu*g) if mu > 0 else float('inf')):.4f} m")
print("t      x_c-x_c0   exact      v_c      exact")
for t, x, v in zip(ts, xs, vs):
    te = min(t, tstar)
    se = v0 * te - 0.5 * mu * g * te**2
    ve = max(0.0, v0 - mu * g * t)
    print(f"{t:.3f}  {x - xs[0]:.4f}    {se:.4f}    {v:+.4f}  {ve:.4f}")
