#!/usr/bin/env python3
"""Force of a granular collapse on a rigid wall: linear shape functions
against uGIMP, under grid refinement.

The Bui et al. (2008) column collapse of
tests/granular/bui_collapse_20mm_boundary_particles_ugimp.prm.in (floor
and back wall as boundary particles, Mohr-Coulomb, F-bar, 3 x 3 points
per cell, steps of 5 ms) run twice per grid and shape function:

  open     no obstacle: the runout against the experiment's 0.43 m
  barrier  a smooth rigid wall (boundary particles, 'contact') across the
           runout path at x = 0.32 m; its normal force is recorded

and one table row per grid and shape function:

  runout   runout of the open run [m] and its error against 0.43 m [%]
  t_imp    first instant with a force on the barrier wall [s]
  F_peak   largest force [N/m] (the front's impact, one or two steps)
  F_end    mean force over the last 0.2 s (material at rest) [N/m]
  ring     high-frequency content after the impact: RMS of the force
           minus its 50 ms centred moving average (a low-pass at about
           20 Hz), from t_imp + 50 ms on, resampled every 5 ms, in % of
           F_end; cell crossings make the force ring
  TV       total variation of the force over the same window / F_end
  steps, rej, Newton iterations per step, wall [s] of the barrier run

doc/verification.md, "Force on a rigid wall: uGIMP against linear".

usage: contrib/bui_wall_force_study.py [--talus PATH] [--work DIR]
       [--sizes 0.02 0.01 ...] [--shapes linear uGIMP ...] [--reuse]
       [--plot PNG]
"""

import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from flexible_barrier_2d_study import (moving_average, read_csv,  # noqa: E402
                                       resample, run_in)

BASE = os.path.join(ROOT, "tests", "granular",
                    "bui_collapse_20mm_boundary_particles_ugimp.prm.in")
WALL_X = 0.32
SAMPLE = 0.005
WINDOW = 0.05


def prm_text(h, shape, barrier, out):
    """The test input with the grid, the shape functions, the barrier wall
    and the output set anew (appended: the last value set wins)."""
    with open(BASE) as f:
        text = f.read().replace("@TALUS_DATA_DIR@",
                                os.path.join(ROOT, "data"))
    text += """
subsection Background grid
  set subdivisions = %d, %d
end
subsection Solver
  set shape functions = %s
end
subsection Time
  set time step = %g
end
subsection Output
  set output directory = %s
  set test mode = false
end
subsection Deposit profile
  set measure deposit = %s
  # report, do not check (the table compares)
  set runout tolerance = 10
  set height tolerance = 10
end
""" % (round(0.64 / h), round(0.14 / h), shape, SAMPLE, out,
       "false" if barrier else "true")
    if barrier:
        text += """subsection Boundary particles
  subsection Boundary 3
    set geometry = line
    set name = barrier
    set vertices = %g, 0.005; %g, 0.135
    set condition = contact
  end
end
""" % (WALL_X, WALL_X)
    return text


def run(talus, work, h, shape, barrier, reuse):
    """Run one case; return its directory, log text and wall time."""
    tag = "%s_%s_%gmm" % ("barrier" if barrier else "open", shape,
                          h * 1e3)
    out = os.path.join(work, tag)
    os.makedirs(out, exist_ok=True)
    rc, wall, _, log = run_in(talus, out, prm_text(h, shape, barrier, out),
                              reuse)
    if rc != 0:
        sys.exit("%s failed (exit %d): %s" % (tag, rc,
                                              log.strip().splitlines()[-1]))
    return out, log, wall


def wall_force(t, f):
    """Impact time, peak, final force, ring and total variation."""
    t_imp = next(ti for ti, fi in zip(t, f) if fi > 1.)
    values = resample(t, f, SAMPLE)
    half = int(round(WINDOW / SAMPLE / 2))
    first = int(round((t_imp + WINDOW) / SAMPLE))
    mean = moving_average(values, half)
    window = range(max(first, half), len(values) - half)
    ring = (sum((values[i] - mean[i - half]) ** 2 for i in window) /
            len(window)) ** 0.5
    tv = sum(abs(values[i + 1] - values[i]) for i in window[:-1])
    last = [fi for ti, fi in zip(t, f) if ti > t[-1] - 0.2]
    f_end = sum(last) / len(last)
    return dict(t_imp=t_imp, F_peak=max(f), F_end=f_end,
                ring=100 * ring / f_end, TV=tv / f_end)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--talus", default=os.path.join(ROOT, "build",
                                                         "talus"))
    parser.add_argument("--work", default="bui_wall_force_study")
    parser.add_argument("--sizes", nargs="*", type=float,
                        default=[0.02, 0.01])
    parser.add_argument("--shapes", nargs="*", default=["linear", "uGIMP"],
                        help="shape functions to compare (linear, uGIMP, "
                        "cpGIMP, CPDI)")
    parser.add_argument("--reuse", action="store_true",
                        help="report the runs already in the work "
                        "directory instead of running them again")
    parser.add_argument("--plot", metavar="PNG",
                        help="draw the wall force of every run")
    args = parser.parse_args()
    talus, work = os.path.abspath(args.talus), os.path.abspath(args.work)
    header = ("%6s %7s %7s %6s %6s %7s %7s %6s %6s %5s %4s %6s %6s" %
              ("h[mm]", "shape", "runout", "err%", "t_imp", "F_peak",
               "F_end", "ring%", "TV", "steps", "rej", "Newton", "wall"))
    print(header)
    histories = []
    for h in args.sizes:
        for shape in args.shapes:
            out, log, _ = run(talus, work, h, shape, False, args.reuse)
            runout = float(re.search(r"runout L = ([0-9.eE+-]+) m",
                                     log).group(1))
            out, log, wall = run(talus, work, h, shape, True, args.reuse)
            s = read_csv(os.path.join(out, "time_series.csv"))
            r = wall_force(s["time"], s["barrier_normal_force"])
            m = re.search(r"Done: (\d+) steps \((\d+) rejected\), "
                          r"([0-9.]+) Newton", log)
            print("%6.0f %7s %7.4f %6.1f %6.3f %7.1f %7.1f %6.1f %6.1f "
                  "%5s %4s %6s %6.0f" %
                  (h * 1e3, shape, runout, 100 * (runout / 0.43 - 1),
                   r["t_imp"], r["F_peak"], r["F_end"], r["ring"], r["TV"],
                   m.group(1), m.group(2), m.group(3), wall))
            histories.append((h, shape, s["time"],
                              s["barrier_normal_force"]))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, len(args.sizes), sharey=True,
                                 figsize=(4.2 * len(args.sizes), 3.4),
                                 squeeze=False)
        for ax, h in zip(axes[0], args.sizes):
            for hh, shape, t, f in histories:
                if hh == h:
                    ax.plot(t, f, lw=1, label=shape)
            ax.set_title("cells %g mm" % (h * 1e3), fontsize=10)
            ax.set_xlabel("t [s]")
            ax.set_xlim(0.1, 1.0)
            ax.legend(fontsize=8)
        axes[0][0].set_ylabel("force on the wall [N/m]")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=90)
        print("wrote %s" % args.plot, file=sys.stderr)


if __name__ == "__main__":
    main()
