#!/usr/bin/env python3
"""Error of the rotated incline against the penalty factor and the cell size.

Runs the block on the 30 degree incline rotated by rho against the grid
(contrib/boundaries/make_rotated_incline.py) for penalty factors
(beta = factor * M / h), background cell sizes h and imposition methods
(penalty, augmented Lagrangian), and prints a Markdown table of the RMS
displacement error at t = 1 s against s = a t^2 / 2, the largest
penetration, the Newton iterations and multiplier updates per step
(doc/verification.md, "Boundary particles", penalty study). A run takes
1 to 30 s.

    usage: penalty_study.py <talus executable> [rho] [mu] [methods]
                            [factors] [cell sizes] [ghost penalty factor]

methods: comma-separated, "penalty,augmented Lagrangian,Nitsche" by
default; "Nitsche theta=1" is Nitsche's method with 'Nitsche symmetry' = 1
(symmetric; plain "Nitsche" is the default theta = -1); factors and cell
sizes comma-separated (defaults below); the ghost penalty factor (subsection
Solver, default 0) applies to every run.
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rotated_incline as incline  # noqa: E402

FACTORS = (1., 10., 100., 1000., 1e4)
CELL_SIZES = (0.1, 0.05, 0.025)


def run(talus, rho, mu, factor, h, method, workdir, ghost=0.):
    incline.H = h
    condition = "friction" if mu > 0. else "contact"
    path = os.path.join(workdir, "incline.prm")
    name, _, theta = method.partition(" theta=")
    lines = "    set penalty factor = %g\n    set method = %s\n" % (factor, name)
    if theta:
        lines += "    set Nitsche symmetry = %s\n" % theta
    incline.write(path, rho, mu, condition, method_lines=lines)
    text = open(path).read()
    text = text.replace("subsection Solver\n",
                        "subsection Solver\n  set ghost penalty factor = %g\n"
                        % ghost, 1)
    # no pass/fail here: the table shows the numbers
    text = re.sub(r"set displacement error tolerance = .*",
                  "set displacement error tolerance = 1e9", text)
    text = re.sub(r"set maximum penetration = .*",
                  "set maximum penetration = 1e9", text)
    text = text.replace("set test mode = true", "set test mode = false")
    # Uzawa converges linearly, slowly for small factors: allow many updates
    text = text.replace("subsection Boundary particles\n",
                        "subsection Boundary particles\n"
                        "  set maximum multiplier updates = 200\n", 1)
    open(path, "w").write(text)
    out = subprocess.run([talus, path], cwd=workdir, capture_output=True,
                         text=True)
    log = out.stdout + out.stderr
    error = re.findall(r"error at t = 1: displacement (\S+)", log)
    pen = re.findall(r"check penetration: (\S+)", log)
    newton = re.findall(r"([\d.]+) Newton iterations per step", log)
    rejected = re.findall(r"\((\d+) rejected\)", log)
    updates = (re.findall(r"multiplier updates: (\d+) in (\d+) steps", log)
               or re.findall(r"(\d+) multiplier updates in (\d+) steps", log))
    if out.returncode != 0 or not error:
        return None
    return (float(error[0]), float(pen[0]) if pen else float("nan"),
            float(newton[0]) if newton else float("nan"),
            int(rejected[0]) if rejected else 0,
            int(updates[0][0]) / int(updates[0][1]) if updates else 0.)


def main():
    talus = os.path.abspath(sys.argv[1])
    rho = float(sys.argv[2]) if len(sys.argv) > 2 else 30.
    mu = float(sys.argv[3]) if len(sys.argv) > 3 else 0.1
    methods = (sys.argv[4] if len(sys.argv) > 4 else
               "penalty,augmented Lagrangian,Nitsche").split(",")
    factors = (tuple(float(x) for x in sys.argv[5].split(","))
               if len(sys.argv) > 5 else FACTORS)
    cell_sizes = (tuple(float(x) for x in sys.argv[6].split(","))
                  if len(sys.argv) > 6 else CELL_SIZES)
    ghost = float(sys.argv[7]) if len(sys.argv) > 7 else 0.
    g, theta = incline.G, incline.THETA
    import math
    a = g * (math.sin(theta) - mu * math.cos(theta))
    print("Rotated incline rho = %g deg, mu = %g: s(1 s) = %.4f m, ghost "
          "penalty factor %g" % (rho, mu, a / 2, ghost))
    print()
    print("| method | factor | h [m] | error at 1 s [m] | error / s | "
          "penetration [m] | penetration / h | Newton its/step | "
          "multiplier updates/step | rejected |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as workdir:
        for method in methods:
            for factor in factors:
                for h in cell_sizes:
                    r = run(talus, rho, mu, factor, h, method, workdir,
                            ghost)
                    if r is None:
                        print("| %s | %g | %g | failed | | | | | | |" %
                              (method, factor, h))
                        continue
                    e, p, n, rej, upd = r
                    print("| %s | %g | %g | %.2e | %.1e | %.2e | %.1e | %.1f "
                          "| %.2f | %d |" % (method, factor, h, e, e / (a / 2),
                                              p, p / h, n, upd, rej))
                    sys.stdout.flush()


if __name__ == "__main__":
    main()
