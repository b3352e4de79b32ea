#!/usr/bin/env python3
"""Run a Talus input twice, as given (an iterative 'linear solver') and with
'linear solver = direct', and compare every number of the two summaries
(test mode output) to a relative tolerance.

Usage: compare_solvers.py TALUS INPUT.prm WORKDIR RTOL [ATOL]

Passes (exit 0) iff both runs succeed and every number of the iterative
run's output is within RTOL * max(|a|, |b|) + ATOL of the direct run's.
"""
import os
import re
import subprocess
import sys

talus, prm, workdir, rtol = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
atol = float(sys.argv[5]) if len(sys.argv) > 5 else 1e-8
os.makedirs(workdir, exist_ok=True)
text = open(prm).read()
if not re.search(r"set linear solver\s*=\s*(GMRES|CG)", text):
    sys.exit("the input does not use an iterative linear solver")
direct = re.sub(r"set linear solver\s*=\s*\w+", "set linear solver = direct", text)
number = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def run(name, content):
    path = os.path.join(workdir, name + ".prm")
    with open(path, "w") as f:
        f.write(content)
    result = subprocess.run([talus, path], cwd=workdir, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{name} run failed:\n{result.stdout}\n{result.stderr}")
    lines = [l for l in result.stdout.splitlines() if not l.startswith("Talus:")]
    return lines


iterative = run("iterative", text)
reference = run("direct", direct)
if len(iterative) != len(reference):
    sys.exit(f"the outputs differ in length:\n" + "\n".join(iterative) + "\n---\n" + "\n".join(reference))
largest = 0.0
for a_line, b_line in zip(iterative, reference):
    a, b = number.findall(a_line), number.findall(b_line)
    if len(a) != len(b) or number.sub("#", a_line) != number.sub("#", b_line):
        sys.exit(f"the outputs differ:\n  {a_line}\n  {b_line}")
    for x, y in zip(map(float, a), map(float, b)):
        error = abs(x - y)
        if error > rtol * max(abs(x), abs(y)) + atol:
            sys.exit(f"{x} (iterative) != {y} (direct) within {rtol}:\n  {a_line}\n  {b_line}")
        if max(abs(x), abs(y)) > atol:
            largest = max(largest, error / max(abs(x), abs(y)))
print("\n".join(iterative))
print(f"the iterative and the direct solver agree: largest relative difference {largest:.1e} <= {rtol}")
