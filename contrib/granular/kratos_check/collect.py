#!/usr/bin/env python3
"""Collect all runs/*/ into results.md (markdown table) and results.csv.
For each run: settings (case.json), steps, non-converged steps, wall time,
crash time, runout/height measures at the last dump (measure.py), and the
runout at t = 0.5 s for the time history."""
import csv
import glob
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
rows = []
for d in sorted(glob.glob(os.path.join(HERE, "runs", "*"))):
    name = os.path.basename(d)
    if name.startswith("slide") or not os.path.exists(os.path.join(d, "mp_t0.000.csv")):
        continue
    case = json.load(open(os.path.join(d, "case.json")))
    summ = {}
    if os.path.exists(os.path.join(d, "run_summary.json")):
        summ = json.load(open(os.path.join(d, "run_summary.json")))
    binw = 0.01
    out = subprocess.run([sys.executable, os.path.join(HERE, "measure.py"), d, "--bin", str(binw), "--json"],
                         capture_output=True, text=True)
    m = json.loads(out.stdout)
    L05 = ""
    if os.path.exists(os.path.join(d, "mp_t0.500.csv")):
        o5 = subprocess.run([sys.executable, os.path.join(HERE, "measure.py"), d, "--t", "0.5", "--json"],
                            capture_output=True, text=True)
        L05 = f"{json.loads(o5.stdout)['runout']:.4f}"
    floor = case["floor"]
    if floor == "friction":
        floor = f"Coulomb mu={case['mu']} (penalty {case['pen']:.0e})"
    settings = (f"{case['elem']} {case.get('mp') or (4 if case['elem']=='quad' else 3)} MP/element, "
                f"floor {floor}, wall {case['wall']}, dt {case['dt']:g}, {case['scheme']}")
    crashed = summ.get("crashed")
    if not summ and os.path.exists(os.path.join(d, "run.out")) and "INVERTED" in open(os.path.join(d, "run.out")).read():
        crashed = {"time": float(m["file"][4:-4]), "note": "after"}
    rows.append({
        "run": name, "cell_mm": case["h"] * 1e3, "settings": settings,
        "steps": summ.get("steps", ""), "not_conv": summ.get("not_converged_steps", ""),
        "mean_newton": f"{summ['mean_newton']:.1f}" if summ else "",
        "wall_s": f"{summ['wall_s']:.0f}" if summ else "",
        "t_end": m["file"][4:-4],
        "crash": (f"element inverted between t={crashed['time']:.1f} and {crashed['time']+0.1:.1f} s" if crashed.get("note") else f"element inverted at t={crashed['time']:.3f}") if crashed else "",
        "runout": f"{m['runout']:.4f}", "err_pct": f"{m['runout_err_pct']:+.1f}",
        "max_dh": f"{abs(m['max_abs_dh_exp_stations']['dh']):.4f} (x={m['max_abs_dh_exp_stations']['x']:.2f})",
        "H": f"{m['H']:.4f}", "runout_t0.5": L05,
        "h_0.05": " ".join(f"{v:.4f}" for v in m["h_at_0.05"].values()),
        "max_speed": f"{m['max_speed']:.2f}",
    })

keys = ["run", "cell_mm", "settings", "steps", "not_conv", "mean_newton", "wall_s", "t_end", "crash",
        "runout", "err_pct", "max_dh", "H", "runout_t0.5", "max_speed", "h_0.05"]
with open(os.path.join(HERE, "results.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys)
    w.writeheader()
    w.writerows(rows)
with open(os.path.join(HERE, "results.md"), "w") as f:
    f.write("| " + " | ".join(keys) + " |\n|" + "---|" * len(keys) + "\n")
    for r in rows:
        f.write("| " + " | ".join(str(r[k]) for k in keys) + " |\n")
print(open(os.path.join(HERE, "results.md")).read())
