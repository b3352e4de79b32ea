#!/usr/bin/env python3
"""Table of the Talus Lube runs of talus_variant.sh (output/lube_check/NAME):
steps, mean/max dt, (L-L0)/L0 and H/L0 with their errors against the Lube laws,
V/V0 (sum of V0 det F), final kinetic energy, wall time (from the log).
Usage (repository root): talus_lube_collect.py NAME ... [--logdir /tmp]"""
import csv, os, re, sys

args = sys.argv[1:]
logdir = "/tmp"
if "--logdir" in args:
    i = args.index("--logdir"); logdir = args[i + 1]; del args[i:i + 2]
print("| run | a | steps | mean dt [s] | (L-L0)/L0 | err | H/L0 | err | V/V0 | KE end [J] | wall [s] |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for n in args:
    d = os.path.join("output/lube_check", n)
    r = list(csv.DictReader(open(d + "/time_series.csv")))
    s = list(csv.DictReader(open(d + "/deposit_summary.csv")))[0]
    dts = [float(x["dt"]) for x in r[1:]]
    wall = ""
    for lg in (os.path.join(logdir, "lube_check_" + n + ".log"), os.path.join(logdir, n + ".log")):
        if os.path.exists(lg):
            m = re.findall(r"wall=(\d+)", open(lg).read())
            wall = m[-1] if m else ""
            break
    a = float(s["a"]); rn = float(s["runout_normalised"]); hn = float(s["height_normalised"])
    lr = float(s["lube_runout"]); lh = float(s["lube_height"])
    print(f"| {n} | {a:g} | {len(r) - 1} | {sum(dts) / len(dts):.4f} | {rn:.3f} | {100 * (rn / lr - 1):+.1f} % | {hn:.3f} | "
          f"{100 * (hn / lh - 1):+.1f} % | {float(r[-1]['volume']) / float(r[0]['volume']):.3f} | {float(r[-1]['kinetic_energy']):.3f} | {wall} |")
