#!/usr/bin/env python3
"""The contact onset event on a free-fall impact (doc/verification.md "Time
steps chosen by the error", contact onset).

usage: contact_onset_study.py TALUS INPUT WORKDIR REFERENCE_STEP

INPUT (tests/mpm/drop_contact_onset.prm or drop_contact_onset_points.prm)
is a block falling onto a floor of boundary particles named 'floor', with
lines `set time step` and `set contact onset time step` in subsection
Time. Runs: the reference (fixed REFERENCE_STEP, no onset event), the
fixed step of INPUT without the onset event, with it but without its
forecast ('contact onset forecast = false'), and with both, and the step
chosen by the error (tolerance 1e-2, largest step that of INPUT) without
and with the event. For each: steps, steps shortened ahead of a forecast
onset, onset rejections, smallest step, the first time the floor carries a
normal force, the step that contains it, the largest normal force, and the
RMS over the points of |x - x_ref| at the end time (points matched by id;
one rank).
"""
import csv
import math
import os
import re
import subprocess
import sys


def substitute(text, entry, value):
    pattern = re.compile(r"^(\s*set " + re.escape(entry) + r"\s*=).*$",
                         re.MULTILINE)
    if pattern.search(text):
        return pattern.sub(lambda m: m.group(1) + " " + value, text)
    return text.replace("subsection Time\n",
                        "subsection Time\n  set %s = %s\n" % (entry, value))


def run(talus, text, directory):
    os.makedirs(directory, exist_ok=True)
    text = re.sub(r"^(\s*set output directory\s*=).*$", r"\1 output", text,
                  flags=re.MULTILINE)
    with open(os.path.join(directory, "case.prm"), "w") as f:
        f.write(text)
    env = dict(os.environ, TALUS_DEBUG_DUMP_POINTS="points.txt")
    p = subprocess.run([talus, "case.prm"], cwd=directory, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=1200)
    with open(os.path.join(directory, "log.txt"), "w") as f:
        f.write(p.stdout)
    if p.returncode != 0:
        print(p.stdout)
        sys.exit("FAIL: talus exited with %d in %s" % (p.returncode,
                                                       directory))
    steps = int(re.search(r"after (\d+) steps", p.stdout).group(1))
    m = re.search(r"contact onset: (\d+) steps shortened ahead of a "
                  r"forecast onset, (\d+) steps rejected", p.stdout)
    shortened, onset = (int(m.group(1)), int(m.group(2))) if m else (0, 0)
    rows = list(csv.DictReader(open(os.path.join(directory, "output",
                                                 "time_series.csv"))))
    first, first_dt, peak, smallest = None, None, 0., 1e300
    for r in rows:
        f = abs(float(r["floor_normal_force"]))
        if float(r["dt"]) > 0.:
            smallest = min(smallest, float(r["dt"]))
        if f > 0. and first is None:
            first, first_dt = float(r["time"]), float(r["dt"])
        peak = max(peak, f)
    points = {}
    with open(os.path.join(directory, "points.txt")) as f:
        for line in f:
            v = line.split()
            points[v[0]] = [float(x) for x in v[1:3]]
    return steps, shortened, onset, smallest, first, first_dt, peak, points


def main():
    talus, input_file, work, reference_step = sys.argv[1:5]
    text = open(input_file).read()
    step = re.search(r"set time step\s*=\s*(\S+)", text).group(1)
    plain = substitute(text, "contact onset time step", "0")
    cases = [
        ("reference: fixed %s s" % reference_step,
         substitute(plain, "time step", reference_step)),
        ("fixed %s s" % step, plain),
        ("fixed %s s + onset, no forecast" % step,
         substitute(text, "contact onset forecast", "false")),
        ("fixed %s s + onset" % step, text),
        ("error 1e-2", substitute(plain, "error tolerance", "1e-2")),
        ("error 1e-2 + onset", substitute(text, "error tolerance", "1e-2")),
    ]
    results = []
    for i, (name, t) in enumerate(cases):
        results.append((name, run(talus, t, os.path.join(work, "case%d" % i))))
    ref = results[0][1][7]
    print("| run | steps | shortened ahead | onset rejections | smallest dt "
          "[s] | first floor force at t [s] | its step [s] | largest floor "
          "force [N] | RMS error at the end [m] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, (steps, shortened, onset, smallest, first, first_dt, peak,
               pts) in results:
        err = math.sqrt(sum((pts[k][0] - ref[k][0]) ** 2 +
                            (pts[k][1] - ref[k][1]) ** 2 for k in ref) /
                        len(ref))
        print("| %s | %d | %d | %d | %.3g | %.6g | %.3g | %.4g | %.3e |" %
              (name, steps, shortened, onset, smallest, first, first_dt, peak,
               err))


if __name__ == "__main__":
    main()
