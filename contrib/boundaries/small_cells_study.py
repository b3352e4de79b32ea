#!/usr/bin/env python3
"""Does a block stay at rest on a non-conforming incline whatever the cut of
its cells? (issue 38, "Small and nearly empty cells by default";
doc/verification.md, "Rotated incline (section 2.3)")

The stick case of make_rotated_incline.py (30 degree incline, mu = 0.7 >
tan 30, 0.05 m cells, 2 x 2 points per cell, penalty boundary particles)
is shifted along y by a fraction of a cell, so that the incline and the
block cut the cells differently, for each rotation of the problem against
the grid. Every run uses the code's defaults (no Newmark damping, no ghost
penalty) unless options are given. A run passes if the final speed after
1 s is below 1e-4 m/s, the displacement within 1 % of h and the
penetration within 1e-3 h (the stick tests' checks).

    usage: small_cells_study.py TALUS [--offsets N] [--rotations 0 15 30 45]
                                [--damping] [--solver-lines "..."]
                                [--method-lines "..."] [--work DIR]
Prints one row per run and the number that pass.
"""
import argparse
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_rotated_incline as incline  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("talus")
    ap.add_argument("--offsets", type=int, default=10,
                    help="shifts k h / N, k = 0 .. N-1")
    ap.add_argument("--rotations", type=float, nargs="+",
                    default=[0, 15, 30, 45])
    ap.add_argument("--damping", action="store_true",
                    help="Newmark gamma = 0.6 as the tests")
    ap.add_argument("--solver-lines", default="",
                    help="extra lines of subsection Solver")
    ap.add_argument("--method-lines", default="",
                    help="extra lines of the boundary's subsection")
    ap.add_argument("--work", default="small_cells_study")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    solver = "".join("  " + l.strip() + "\n"
                     for l in args.solver_lines.split(";") if l.strip())
    method = "".join("    " + l.strip() + "\n"
                     for l in args.method_lines.split(";") if l.strip())
    print("| rotation | shift / h | final speed [m/s] | displacement error [m] "
          "| penetration [m] | rejected steps | pass |")
    print("|---|---|---|---|---|---|---|")
    passed = total = 0
    for rho in args.rotations:
        for k in range(args.offsets):
            shift = k / args.offsets
            name = f"stick_{rho:g}_{k}"
            prm = os.path.join(args.work, name + ".prm")
            incline.write(prm, rho, 0.7, "friction", offset=shift * incline.H,
                          damping=args.damping, solver_lines=solver,
                          method_lines=method,
                          output_directory=os.path.join(args.work,
                                                        "out_" + name))
            run = subprocess.run([args.talus, prm], capture_output=True,
                                 text=True)
            out = run.stdout + run.stderr

            def last(pattern):
                m = re.findall(pattern, out)
                return m[-1] if m else "-"
            speed = last(r"check final speed: (\S+)")
            error = last(r"check displacement error: (\S+)")
            pen = last(r"check penetration: (\S+)")
            rejected = len(re.findall(r"rejected", out))
            ok = run.returncode == 0 and "FAILED" not in out \
                and " ok" in out and not re.search(r"check .*failed", out)
            passed += ok
            total += 1
            print(f"| {rho:g}° | {shift:.2f} | {speed} | {error} | {pen} "
                  f"| {rejected} | {'yes' if ok else 'no (exit %d)' % run.returncode} |",
                  flush=True)
    print(f"\n{passed} of {total} runs pass")


if __name__ == "__main__":
    main()
