#!/usr/bin/env python3
"""Table of the time-step runs of run_dt.sh (output/dt_check/NAME) or of any
collapse output directories (e.g. output/granular/bui2008_10mm).

usage (repository top): collect_dt.py DIR [DIR ...]

Per run: largest step (from the input), steps, mean step, Newton iterations
per step, runout L, (L - L0)/L0, H/L0 (maximum height), the largest
|h - h_ref| of the reference profile (talus' table, if any), V/V0 (sum of
V0 det F), kinetic energy at the end, talus' exit code and wall time (last
line of talus.log). Runs of the same input (name up to '_dt') are listed
from the largest step down, and for each the change against the run with
the next larger step: dL = relative change of L, dL* = of (L - L0)/L0, dH = relative
change of H, dh = largest change of the surface h(x) over the stations at
least two bin widths behind both fronts and not empty (h > 0) in either
run, in % of H0.
"""
import csv, glob, os, re, sys


def run(d):
    r = list(csv.DictReader(open(os.path.join(d, "time_series.csv"))))
    s = list(csv.DictReader(open(os.path.join(d, "deposit_summary.csv"))))[0]
    prm = glob.glob(os.path.join(d, "*.prm"))
    log = open(os.path.join(d, "talus.log")).read()
    dtmax = None
    src = prm[0] if prm else None
    if src is None:  # a benchmark run of run_collapse_series.sh: its input
        name = os.path.basename(d.rstrip("/"))
        found = glob.glob("benchmarks/**/%s.prm" % name, recursive=True)
        src = found[0] if found else None
    m = re.search(r"^\s*set time step\s*=\s*(\S+)", open(src).read(), re.M) if src else None
    if m:
        dtmax = float(m.group(1))
    dts = [float(x["dt"]) for x in r[1:]]
    newton = sum(float(x["newton_iterations"]) for x in r[1:]) / max(1, len(dts))
    hmax = None
    for line in log.splitlines():
        mm = re.match(r"\s*h\(.*?\)\s.*?\s(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(ok|FAILED)\s*$", line)
        if mm:
            e = abs(float(mm.group(3)))
            hmax = e if hmax is None else max(hmax, e)
    w = re.findall(r"rc=(\d+) wall=(\d+)", log)
    prof = {}
    with open(os.path.join(d, "deposit_profile.csv")) as f:
        for row in csv.reader(f):
            try:
                prof[round(float(row[0]), 6)] = float(row[1])
            except (ValueError, IndexError):
                pass
    mb = re.search(r"bin width ([0-9.e-]+) m", log)
    return dict(dir=d, bin=float(mb.group(1)) if mb else 0., dtmax=dtmax, steps=len(dts), dtmean=sum(dts) / max(1, len(dts)),
                newton=newton, L=float(s["runout"]), Ln=float(s["runout_normalised"]),
                Hn=float(s["height_normalised"]), H=float(s["max_height"]),
                H0=float(s["H0"]), a=float(s["a"]), lr=s.get("lube_runout"), lh=s.get("lube_height"),
                hmax=hmax, V=float(r[-1]["volume"]) / float(r[0]["volume"]),
                KE=float(r[-1]["kinetic_energy"]), rc=w[-1][0] if w else "",
                wall=w[-1][1] if w else "", prof=prof)


def main():
    runs = [run(d.rstrip("/")) for d in sys.argv[1:]]
    groups = {}
    for x in runs:
        key = re.sub(r"_dt[0-9.e-]+$", "", os.path.basename(x["dir"]))
        groups.setdefault(key, []).append(x)
    print("| run | Δt max [s] | steps | mean Δt [s] | Newton/step | L [m] | (L−L0)/L0 | H/L0 | max abs(h−h_exp) [m] "
          "| dL | dL* | dH | dh [% H0] | V/V0 | KE end [J] | rc | wall [s] |")
    print("|" + "---|" * 17)
    for key, xs in groups.items():
        xs.sort(key=lambda x: -(x["dtmax"] or 0))
        prev = None
        for x in xs:
            dl = dl0 = dh = dprof = ""
            if prev:
                dl0 = "%+.1f %%" % (100 * (x["L"] / prev["L"] - 1))
                dl = "%+.1f %%" % (100 * (x["Ln"] / prev["Ln"] - 1))
                dh = "%+.1f %%" % (100 * (x["H"] / prev["H"] - 1))
                # stations behind both fronts (not the toe bins)
                front = min(x["L"], prev["L"]) - 2 * x["bin"]
                common = [k for k in set(x["prof"]) & set(prev["prof"])
                          if k <= front and x["prof"][k] > 0 and prev["prof"][k] > 0]
                if common:
                    dprof = "%.1f" % (100 * max(abs(x["prof"][k] - prev["prof"][k]) for k in common) / x["H0"])
            print("| %s | %g | %d | %.2g | %.1f | %.4f | %.3f | %.3f | %s | %s | %s | %s | %s | %.3f | %.3f | %s | %s |" % (
                os.path.basename(x["dir"]), x["dtmax"] or 0, x["steps"], x["dtmean"], x["newton"], x["L"],
                x["Ln"], x["Hn"], "%.4f" % x["hmax"] if x["hmax"] is not None else "", dl0, dl, dh, dprof,
                x["V"], x["KE"], x["rc"], x["wall"]))
            prev = x


main()
