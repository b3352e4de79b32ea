#!/usr/bin/env python3
"""Every imposition method on every rotated incline (issue 4, VERIFICATION.md
2.3): the block on the 30 degree incline rotated by 0, 15, 30 and 45 degrees
against the grid, frictionless (mu = 0), with friction (mu = 0.1) and stuck
(mu = 0.7), for each method, with the checks of the test inputs
(contrib/boundaries/make_rotated_incline.py): displacement error at 0.5 s and
1 s within 1 % of s(0.5 s) (sliding) or 1 % of h (stick), largest penetration
below 1e-3 h, final speed of the stuck block below 1e-4 m/s. Prints a
Markdown table and the number of cases that pass; h = 0.05 m, dt = 0.01 s,
1 s. About 2 to 5 s a run, 60 runs.

    usage: method_matrix.py <talus executable> [methods]

methods: comma-separated names of METHODS below (default: all).
"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rotated_incline as incline  # noqa: E402

# name: (lines of subsection Boundary 1, lines of subsection Solver)
METHODS = {
    "penalty": ("", ""),
    "augmented Lagrangian": ("    set method = augmented Lagrangian\n"
                             "    set constraint = per cell\n", ""),
    "Nitsche": ("    set method = Nitsche\n", ""),
    "Nitsche symmetric": ("    set method = Nitsche\n"
                          "    set Nitsche symmetry = 1\n"
                          "    set penalty factor = 10\n",
                          "  set ghost penalty factor = 1\n"),
    "Lagrange multiplier": ("    set method = Lagrange multiplier\n", ""),
}
CASES = (("mu = 0", 0.0, "contact"), ("mu = 0.1", 0.1, "friction"),
         ("stick", 0.7, "friction"))


def run(talus, rho, mu, condition, method, workdir):
    path = os.path.join(workdir, "incline.prm")
    lines, solver = METHODS[method]
    incline.write(path, rho, mu, condition, method_lines=lines,
                  solver_lines=solver)
    text = open(path).read().replace("set test mode = true",
                                     "set test mode = false")
    open(path, "w").write(text)
    out = subprocess.run([talus, path], cwd=workdir, capture_output=True,
                         text=True)
    log = out.stdout + out.stderr
    errors = [float(x) for x in
              re.findall(r"error at t = [\d.]+: displacement (\S+)", log)]
    tolerance = re.findall(r"check displacement error: \S+ <= (\S+)", log)
    penetration = re.findall(r"check penetration: (\S+)", log)
    speed = re.findall(r"check final speed: (\S+)", log)
    rejected = re.findall(r"\((\d+) rejected\)", log)
    checks = re.findall(r"^\s*check .*$", log, re.M)
    passed = (out.returncode == 0 and len(errors) == 2 and checks and
              all(c.rstrip().endswith("ok") for c in checks))
    return dict(errors=errors,
                tolerance=float(tolerance[0]) if tolerance else None,
                penetration=float(penetration[0]) if penetration else None,
                speed=float(speed[0]) if speed else None,
                rejected=int(rejected[0]) if rejected else None,
                passed=passed)


def main():
    talus = os.path.abspath(sys.argv[1])
    methods = sys.argv[2].split(",") if len(sys.argv) > 2 else list(METHODS)
    h = incline.H
    print("| method | rotation | case | error at 0.5 s / 1 s [m] | tolerance "
          "[m] | penetration / h | final speed [m/s] | rejected steps | "
          "pass |")
    print("|---|---|---|---|---|---|---|---|---|")
    n_pass = n_all = 0
    with tempfile.TemporaryDirectory() as workdir:
        for method in methods:
            for rho in (0, 15, 30, 45):
                for case, mu, condition in CASES:
                    r = run(talus, rho, mu, condition, method, workdir)
                    n_all += 1
                    n_pass += r["passed"]
                    e = " / ".join("%.2e" % x for x in r["errors"]) or "-"
                    fmt = lambda x, f: f % x if x is not None else "-"
                    print("| %s | %d° | %s | %s | %s | %s | %s | %s | %s |" %
                          (method, rho, case, e,
                           fmt(r["tolerance"], "%.2e"),
                           fmt(None if r["penetration"] is None else
                               r["penetration"] / h, "%.1e"),
                           fmt(r["speed"], "%.1e"),
                           fmt(r["rejected"], "%d"),
                           "yes" if r["passed"] else "**no**"))
                    sys.stdout.flush()
    print()
    print("%d of %d cases pass" % (n_pass, n_all))


if __name__ == "__main__":
    main()
