#!/usr/bin/env python3
"""Global error of the step chosen by the truncation error against its
tolerance (doc/verification.md "Time steps chosen by the error").

usage: tolerance_study.py TALUS INPUT WORKDIR REFERENCE_STEP TOLERANCES
                          MIN_SLOPE MAX_SLOPE [--set ENTRY=VALUE ...]
                          [--max-steps N]

INPUT is a .prm with lines `set time step`, `set error tolerance` (and
optionally `set maximum time step`) in subsection Time. The script runs it
once with the fixed step REFERENCE_STEP (error tolerance 0, the reference:
the same grid and points, only the time integration differs) and once per
tolerance of the comma-separated TOLERANCES, each run writing its final
material points (TALUS_DEBUG_DUMP_POINTS). The global time-integration
error of a run is the RMS over the points of |x - x_ref| at the end time
(points matched by id; one rank). Also for 'problem = coupled': the
points of the MPM, and in an extra column the RMS over the structure's
dofs of |u - u_ref| at the end (TALUS_DEBUG_DUMP_STRUCTURE). --set
replaces the value of an entry the input sets (all runs, also the
reference). --max-steps: fail if the run at the smallest tolerance takes
more than N steps. Prints the table tolerance / error /
steps / rejected steps / smallest and largest step, and the least-squares
slopes of log(error) and log(steps) against log(tolerance); exits 1 unless
the error slope lies in [MIN_SLOPE, MAX_SLOPE] and the error falls with
the tolerance at every level.
"""
import math
import os
import re
import subprocess
import sys


def substitute(text, entry, value):
    pattern = re.compile(r"^(\s*set " + re.escape(entry) + r"\s*=).*$",
                         re.MULTILINE)
    if not pattern.search(text):
        sys.exit("FAIL: the input has no line 'set %s'" % entry)
    return pattern.sub(lambda m: m.group(1) + " " + value, text)


def run(talus, text, directory):
    os.makedirs(directory, exist_ok=True)
    text = substitute(text, "output directory", "output")
    with open(os.path.join(directory, "case.prm"), "w") as f:
        f.write(text)
    env = dict(os.environ, TALUS_DEBUG_DUMP_POINTS="points.txt",
               TALUS_DEBUG_DUMP_STRUCTURE="structure.txt")
    p = subprocess.run([talus, "case.prm"], cwd=directory, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=600)
    with open(os.path.join(directory, "log.txt"), "w") as f:
        f.write(p.stdout)
    if p.returncode not in (0, 3):  # 3: a verification check missed
        print(p.stdout)
        sys.exit("FAIL: talus exited with %d in %s" % (p.returncode,
                                                       directory))
    # 'problem = mpm': "... after N steps"; coupled: "Done: N coupled steps"
    m = re.search(r"after (\d+) steps|Done: (\d+) coupled steps", p.stdout)
    steps = int(m.group(1) or m.group(2))
    m = re.search(r"steps chosen by the error: \d+ steps, (\d+) rejected "
                  r"for their error, dt (\S+) \.\. (\S+) s", p.stdout)
    rejected, smallest, largest = (int(m.group(1)), float(m.group(2)),
                                   float(m.group(3))) if m else (0, 0., 0.)
    points = {}
    with open(os.path.join(directory, "points.txt")) as f:
        for line in f:
            v = line.split()
            points[v[0]] = [float(x) for x in v[1:4]]
    structure = None
    if os.path.exists(os.path.join(directory, "structure.txt")):
        with open(os.path.join(directory, "structure.txt")) as f:
            structure = [float(x) for x in f]
    return steps, rejected, smallest, largest, points, structure


def slope(x, y):
    lx = [math.log(a) for a in x]
    ly = [math.log(b) for b in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return (sum((a - mx) * (b - my) for a, b in zip(lx, ly)) /
            sum((a - mx) ** 2 for a in lx))


def main():
    talus, input_file, work = sys.argv[1:4]
    reference_step = sys.argv[4]
    tolerances = [float(t) for t in sys.argv[5].split(",")]
    min_slope, max_slope = float(sys.argv[6]), float(sys.argv[7])
    dim = int(re.search(r"^set dimension\s*=\s*(\d)",
                        open(input_file).read(), re.MULTILINE).group(1))
    text = open(input_file).read()
    options = sys.argv[8:]
    max_steps = None
    while options:
        if options[0] == "--max-steps" and len(options) >= 2:
            max_steps = int(options[1])
        elif options[0] == "--set" and len(options) >= 2 and \
                "=" in options[1]:
            entry, value = options[1].split("=", 1)
            text = substitute(text, entry.strip(), value.strip())
        else:
            sys.exit("usage: ... [--set ENTRY=VALUE ...] [--max-steps N]")
        options = options[2:]

    ref_text = substitute(substitute(text, "error tolerance", "0"),
                          "time step", reference_step)
    ref_text = re.sub(r"^\s*set maximum time step\s*=.*$", "", ref_text,
                      flags=re.MULTILINE)
    ref_steps, _, _, _, ref, ref_structure = run(talus, ref_text,
                                  os.path.join(work, "reference"))
    print("reference: fixed step %s s, %d steps" % (reference_step,
                                                     ref_steps))
    rows = []
    for tol in tolerances:
        steps, rejected, smallest, largest, points, structure = run(
            talus, substitute(text, "error tolerance", "%g" % tol),
            os.path.join(work, "tol_%g" % tol))
        if set(points) != set(ref):
            sys.exit("FAIL: the points differ from the reference's")
        sum2, worst = 0., 0.
        for key, x in points.items():
            d2 = sum((x[d] - ref[key][d]) ** 2 for d in range(dim))
            sum2 += d2
            worst = max(worst, math.sqrt(d2))
        structure_error = None
        if structure is not None and ref_structure is not None:
            structure_error = math.sqrt(
                sum((a - b) ** 2 for a, b in zip(structure, ref_structure)) /
                len(structure))
        rows.append((tol, math.sqrt(sum2 / len(points)), worst, steps,
                     rejected, smallest, largest, structure_error))

    with_structure = ref_structure is not None
    print("| tolerance | RMS error [m] | largest error [m] | steps | "
          "rejected (error) | smallest dt [s] | largest dt [s] |" +
          (" structure RMS error [m] |" if with_structure else ""))
    print("|---|---|---|---|---|---|---|" + ("---|" if with_structure
                                             else ""))
    for r in rows:
        print("| %.0e | %.3e | %.3e | %d | %d | %.3g | %.3g |" % r[:7] +
              (" %.3e |" % r[7] if with_structure else ""))
    tol = [r[0] for r in rows]
    s_error = slope(tol, [r[1] for r in rows])
    s_steps = slope(tol, [r[3] for r in rows])
    print("slope of log(error) against log(tolerance): %.2f" % s_error)
    print("slope of log(steps) against log(tolerance): %.2f" % s_steps)
    ok = min_slope <= s_error <= max_slope
    by_tolerance = sorted(rows)
    for a, b in zip(by_tolerance, by_tolerance[1:]):
        if not a[1] < b[1]:
            print("FAIL: the error does not fall from tolerance %g to %g"
                  % (b[0], a[0]))
            ok = False
    if max_steps is not None and by_tolerance[0][3] > max_steps:
        print("FAIL: %d steps at tolerance %g, more than %d"
              % (by_tolerance[0][3], by_tolerance[0][0], max_steps))
        ok = False
    if not ok:
        sys.exit("FAIL: error slope %.2f outside [%g, %g]"
                 % (s_error, min_slope, max_slope))
    print("PASS")


if __name__ == "__main__":
    main()
