#!/usr/bin/env python3
"""Distribution of the point volume ratio J = V/V0 at the end of a Talus run
(last particles_*.0.vtu, J = det F, plane strain) or a Kratos run (last mp_t*.csv,
J = MP_VOLUME / initial volume). Usage: jdist.py DIR [DIR ...]"""
import csv, glob, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # talus_vtu_to_csv.py next to this file
from talus_vtu_to_csv import arrays  # noqa

def pct(v, q):
    v = sorted(v); return v[min(len(v) - 1, int(q * len(v)))]

for d in sys.argv[1:]:
    vt = sorted(glob.glob(os.path.join(d, "particles_*.0.vtu")))
    if vt:
        a = arrays(open(vt[-1]).read())
        J = [f00[0] * f11[0] - f01[0] * f10[0] for f00, f01, f10, f11 in zip(a["F_00"], a["F_01"], a["F_10"], a["F_11"])]
        y = [p[1] for p in a["Points"]]
        src = os.path.basename(vt[-1])
    else:
        fs = sorted(glob.glob(os.path.join(d, "mp_t*.csv")))
        r0 = list(csv.DictReader(open(fs[0]))); r = list(csv.DictReader(open(fs[-1])))
        J = [float(b["volume"]) / float(a_["volume"]) for a_, b in zip(r0, r)]
        y = [float(b["y"]) for b in r]
        src = os.path.basename(fs[-1])
    n = len(J)
    print(f"{d} ({src}): N={n} mean J={sum(J)/n:.4f}  min {min(J):.3f}  p10 {pct(J,.1):.3f}  p50 {pct(J,.5):.3f}  p90 {pct(J,.9):.3f}  max {max(J):.3f}"
          f"  frac J>1.1: {sum(j > 1.1 for j in J)/n:.2f}  J>1.5: {sum(j > 1.5 for j in J)/n:.3f}  J<0.98: {sum(j < 0.98 for j in J)/n:.2f}")
