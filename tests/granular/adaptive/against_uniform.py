#!/usr/bin/env python3
"""Run an input with an adaptive background grid (subsection Adaptive grid
enabled, test mode) on 1 and on NPROC ranks, and the same input on the
uniform grid of its finest cells (the adaptive grid disabled, the given
subdivisions), and compare what the runs' summaries say about the body.

usage: against_uniform.py TALUS INPUT WORKDIR FINE_SUBDIVISIONS RTOL
                          [NPROC]

FINE_SUBDIVISIONS: the 'subdivisions' of the uniform grid ("20, 8, 4").
Passes (exit 0) iff every run succeeds, loses no mass, meets its own
checks (energy balance), and the extremes of the points' displacement
('displacement min/max') and the kinetic energy of each adaptive run lie
within RTOL of the uniform run's (relative to the largest displacement
component and to the kinetic energy). Plastic Newton paths branch
differently on another grid or number of ranks (other steps rejected),
so the runs are compared by their result, not line by line. Prints the
table of the compared quantities.
"""
import os
import re
import subprocess
import sys


def summary(text):
    def numbers(label):
        m = re.search(r"^  " + re.escape(label) + r": (.*)$", text,
                      re.MULTILINE)
        if not m:
            sys.exit("FAIL: no '%s' in the summary" % label)
        return [float(x) for x in m.group(1).split()[:3]]

    mass = re.search(r"^  mass: (\S+) kg \(initial (\S+)\)", text,
                     re.MULTILINE)
    steps = re.search(r"^Summary at t = \S+ s after (\d+) steps", text,
                      re.MULTILINE)
    return {"mass": (float(mass.group(1)), float(mass.group(2))),
            "displacement min": numbers("displacement min"),
            "displacement max": numbers("displacement max"),
            "kinetic energy": numbers("kinetic energy")[0],
            "steps": int(steps.group(1)),
            "rejected": len(re.findall(r"^  step \d+ at t = .* rejected",
                                       text, re.MULTILINE))}


def run(talus, text, work, name, nproc):
    os.makedirs(work, exist_ok=True)
    text = re.sub(r"(set output directory\s*=).*",
                  r"\1 output-" + name, text)
    path = os.path.join(work, name + ".prm")
    with open(path, "w") as f:
        f.write(text)
    command = [talus, path]
    if nproc > 1:
        command = ["mpirun", "-np", str(nproc)] + command
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    p = subprocess.run(command, cwd=work, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True,
                       timeout=900)
    with open(os.path.join(work, name + ".log"), "w") as f:
        f.write(p.stdout)
    if p.returncode != 0:
        print(p.stdout)
        sys.exit("FAIL: the %s run exited with %d" % (name, p.returncode))
    if re.search(r"  FAILED$", p.stdout, re.MULTILINE):
        print(p.stdout)
        sys.exit("FAIL: a check of the %s run failed" % name)
    return summary(p.stdout)


def main():
    talus, input_file, work, fine, rtol = sys.argv[1:6]
    rtol = float(rtol)
    nproc = int(sys.argv[6]) if len(sys.argv) > 6 else 1
    text = open(input_file).read()
    if not re.search(r"^\s*set enable\s*=\s*true", text, re.MULTILINE):
        sys.exit("FAIL: the input does not enable the adaptive grid")
    uniform = re.sub(r"^(\s*set enable\s*=\s*)true", r"\1false", text,
                     flags=re.MULTILINE)
    uniform = re.sub(r"^(\s*set subdivisions\s*=).*$", r"\1 " + fine,
                     uniform, count=1, flags=re.MULTILINE)
    runs = [("uniform", run(talus, uniform, work, "uniform", 1)),
            ("adaptive", run(talus, text, work, "adaptive", 1))]
    if nproc > 1:
        runs.append(("adaptive, %d ranks" % nproc,
                     run(talus, text, work, "adaptive_np%d" % nproc,
                         nproc)))
    ref = runs[0][1]
    scale = max(abs(x) for x in ref["displacement min"] +
                ref["displacement max"])
    print("| run | steps (rejected) | displacement min [m] | "
          "displacement max [m] | kinetic energy [J] | mass [kg] |")
    print("|---|---|---|---|---|---|")
    ok = True
    for name, s in runs:
        print("| %s | %d (%d) | %s | %s | %.6g | %.6g |"
              % (name, s["steps"], s["rejected"],
                 " ".join("%.6g" % x for x in s["displacement min"]),
                 " ".join("%.6g" % x for x in s["displacement max"]),
                 s["kinetic energy"], s["mass"][0]))
        if s["mass"][0] != s["mass"][1]:
            print("FAIL: %s: mass %g of %g" % ((name,) + s["mass"]))
            ok = False
        for key in ("displacement min", "displacement max"):
            d = max(abs(a - b) for a, b in zip(s[key], ref[key])) / scale
            if d > rtol:
                print("FAIL: %s: %s differs by %.2e of the largest "
                      "displacement" % (name, key, d))
                ok = False
        d = abs(s["kinetic energy"] - ref["kinetic energy"]) / \
            ref["kinetic energy"]
        if d > rtol:
            print("FAIL: %s: kinetic energy differs by %.2e" % (name, d))
            ok = False
    if not ok:
        sys.exit("FAIL")
    print("PASS: the adaptive runs agree with the uniform run within %g"
          % rtol)


if __name__ == "__main__":
    main()
