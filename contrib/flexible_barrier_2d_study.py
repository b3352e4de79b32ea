#!/usr/bin/env python3
"""Convergence and sensitivity study of the 2D flagship analogue.

Runs prm/flexible_barrier_2d.prm (a granular slide into the plane barrier)
once per variant, each variant the base file with a few parameters set
anew (appended subsections: the last value set wins), and prints one table
row per variant with what a barrier engineer reads off a run:

  F_peak   largest interface force on the net [kN/m] and its time [s]
  F_avg    largest 0.11 s moving average of that force [kN/m] (the impact
           peak lasts a step or two and depends on the front's last cells)
  F_end    the force at the end (material at rest) [kN/m]
  rope     largest force in the retaining rope [kN/m]
  stroke   the brake's stroke at the end [m]
  defl     largest and final displacement of the net [m]
  E_bar    energy taken by the barrier: elastic + kinetic change + brakes
           and damping, in % of the released gravitational energy
  fric, plast   friction and plastic dissipation [% released]
  bal      the energy balance error at the end [% released]
  ring     high-frequency content of the net force: RMS of the force minus
           its 0.1 s moving average from 0.2 s after the impact peak on, in
           % of F_end (cell crossings make the force ring)
  its      coupling iterations per step; rej: rejected steps; wall [s]

Studies (doc/verification.md, "Flexible barrier (2D): convergence and
sensitivity"): MPM cell size (three levels), net mesh, time step, coupling
tolerance; net stiffness, brake activation force, basal friction and
material model; a boulder at the front of the flow (two bodies).

usage: contrib/flexible_barrier_2d_study.py [--talus PATH] [--only NAME...]
       [--work DIR] [--jobs N] [--reuse] [--plot PNG]
"""

import argparse
import concurrent.futures
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def sub(section, entries):
    """A prm subsection setting the given entries (nested: 'A/B')."""
    names = section.split("/")
    text = "".join("subsection %s\n" % n for n in names)
    for key, value in entries.items():
        text += "  set %s = %s\n" % (key, value)
    return text + "end\n" * len(names)


NEWTON_1E6 = {"residual tolerance": "1e-6", "increment tolerance": "1e-6",
              "increment test": "estimated error"}

# the variants of the slope and the material, shared with the 3D study
SLOPE_AND_MATERIAL = [
    # basal friction (0.4 in the base)
    ("basal friction", "mu=0.3",
     sub("Boundary particles/Boundary 1", {"friction coefficient": "0.3"})),
    ("basal friction", "mu=0.5",
     sub("Boundary particles/Boundary 1", {"friction coefficient": "0.5"})),
    # material model (Mohr-Coulomb, phi 35 deg, in the base)
    ("material", "phi=30",
     sub("Material/Mohr-Coulomb", {"friction angle": "30"})),
    # mu(I) rheology (Jop et al. 2006) on top of phi = 35 deg, the
    # recoverable variant of the Bui collapse; limiting angle and grain
    # size are assumptions for a gravel (not from a test)
    ("material", "mu(I)",
     sub("Material/Mohr-Coulomb", {"limiting friction angle": "45",
                                   "reference inertial number": "0.279",
                                   "grain diameter": "0.01",
                                   "separated volume": "recoverable"})),
]

# The input takes the slope's contact force at its end value, the
# FLIP/PIC blend per 10 ms and the Newton tolerance of the granular
# benchmarks (doc/theory.md, "Contact force in time"; the net, a moving
# coupling interface, keeps the trapezoidal rule). The variants of the
# earlier input, trapezoidal contact on the slope, the blend once per step,
# the default Newton tolerance and energy jumps committed with a warning,
# are appended with it ("trapezoidal" in their study's name) for
# comparison.
TRAPEZOIDAL = sub("Solver", {"contact force in time": "trapezoidal",
                             "start acceleration": "projected",
                             "FLIP fraction reference step": "0",
                             "residual tolerance": "1e-8",
                             "increment tolerance": "1e-8",
                             "increment test": "last correction"}) \
    + sub("Time", {"energy jump action": "warn"})

def refined(h, **time):
    """The input on cells of h = 0.1 or 0.05 m (0.2 m in the base), with
    the given entries of subsection Time (e.g. time_step="0.005")."""
    cells = {"0.1": "140, 76", "0.05": "280, 152"}[h]
    text = sub("Background grid", {"subdivisions": cells})
    if time:
        text += sub("Time", {k.replace("_", " "): v for k, v in time.items()})
    return text


# the MPM grid and shape functions of the input
GRID = [
    # MPM cell size: 0.2 m (base), 0.1 m, 0.05 m; points per cell fixed;
    # "warn": the steps whose energy balance jumps committed with a warning
    # (EnergyJumpMonitor; the input rejects them and retries with half the
    # step); "dt": the step halved with the cell, so that the flow crosses
    # the same fraction of a cell per step as at 0.2 m (v dt / h ~ 0.25)
    ("cell size", "h=0.1", refined("0.1")),
    ("cell size", "h=0.1 warn", refined("0.1", energy_jump_action="warn")),
    ("cell size", "h=0.1 dt=0.005", refined("0.1", time_step="0.005")),
    ("cell size", "h=0.1 dt=0.005 warn",
     refined("0.1", time_step="0.005", energy_jump_action="warn")),
    ("cell size", "h=0.05 dt=0.0025", refined("0.05", time_step="0.0025")),
    ("cell size", "h=0.05 dt=0.0025 warn",
     refined("0.05", time_step="0.0025", energy_jump_action="warn")),
    # the default Newton tolerance (residual 1e-8, last correction)
    ("cell size", "Newton 1e-8",
     sub("Solver", {"residual tolerance": "1e-8",
                    "increment tolerance": "1e-8",
                    "increment test": "last correction"})),
    # shape functions: uGIMP (no cell-crossing error)
    ("shape functions", "uGIMP", sub("Solver", {"shape functions": "uGIMP"})),
    ("shape functions", "uGIMP h=0.1",
     sub("Solver", {"shape functions": "uGIMP"}) +
     refined("0.1")),
]

# the same for the earlier input (with the default Newton tolerance)
TRAPEZOIDAL_GRID = [
    # MPM cell size: 0.2 m (base), 0.1 m, 0.05 m; points per cell fixed
    ("cell size", "h=0.1", refined("0.1")),
    ("cell size", "h=0.05", refined("0.05")),
    # the MPM's Newton tolerance of the granular benchmarks (residual 1e-6,
    # estimated error): the default 1e-8 stalls at rest on the finer grids
    ("cell size", "Newton 1e-6", sub("Solver", NEWTON_1E6)),
    ("cell size", "h=0.1 Newton 1e-6",
     sub("Solver", NEWTON_1E6) +
     refined("0.1")),
    # the same with the step of the spurious solution at 3.27 s rejected
    # and retried with half the step (EnergyJumpMonitor)
    ("cell size", "h=0.1 Newton 1e-6 reject",
     sub("Solver", NEWTON_1E6) +
     refined("0.1") +
     sub("Time", {"energy jump action": "reject"})),
    ("cell size", "h=0.05 Newton 1e-6",
     sub("Solver", NEWTON_1E6) +
     refined("0.05")),
    # shape functions: uGIMP (no cell-crossing error) on the three grids
    ("shape functions", "uGIMP", sub("Solver", {"shape functions": "uGIMP"})),
    ("shape functions", "uGIMP h=0.1",
     sub("Solver", {"shape functions": "uGIMP"}) +
     refined("0.1")),
    ("shape functions", "uGIMP h=0.05",
     sub("Solver", {"shape functions": "uGIMP"}) +
     refined("0.05")),
]

# (study, name, appended prm text), the same for both inputs
STUDIES = [
    # the net's elements (14 per member in the base)
    ("net mesh", "net 7", sub("Structure/Line members", {"elements per member": "7"})),
    ("net mesh", "net 28", sub("Structure/Line members", {"elements per member": "28"})),
    # time step (0.01 s in the base)
    ("time step", "dt=0.02", sub("Time", {"time step": "0.02"})),
    ("time step", "dt=0.005", sub("Time", {"time step": "0.005"})),
    # coupling tolerance (relative 1e-5 in the base)
    ("coupling tolerance", "tol=1e-4",
     sub("Coupling", {"relative tolerance": "1e-4"})),
    ("coupling tolerance", "tol=1e-6",
     sub("Coupling", {"relative tolerance": "1e-6"})),
    # net stiffness: the string's E (EA = 1e6 N in the base)
    ("net stiffness", "EA x0.5", sub("Structure/Line members", {"Young's modulus": "5e9"})),
    ("net stiffness", "EA x2", sub("Structure/Line members", {"Young's modulus": "2e10"})),
    # brake activation force (20 kN/m in the base, where the rope carries
    # at most 1.8 kN/m: the brake does not slide); below the rope force
    ("brake", "brake 1 kN/m",
     sub("Structure/Brake", {"activation force": "1e3"})),
    ("brake", "brake 0.5 kN/m",
     sub("Structure/Brake", {"activation force": "5e2"})),
] + SLOPE_AND_MATERIAL + [
    # the Drucker-Prager cone matched to Mohr-Coulomb in plane strain
    ("material", "Drucker-Prager",
     sub("Material", {"model": "Drucker-Prager"}) +
     sub("Material/Drucker-Prager", {"friction angle": "35"})),
]

# the time step with the blend per 10 ms whatever the step (the earlier
# input applied it once per step)
FLIP_PER_10_MS = [
    ("time step", "dt=0.01, FLIP per 10 ms",
     sub("Solver", {"FLIP fraction reference step": "0.01"})),
    ("time step", "dt=0.02, FLIP per 10 ms",
     sub("Time", {"time step": "0.02"})
     + sub("Solver", {"FLIP fraction reference step": "0.01"})),
    ("time step", "dt=0.005, FLIP per 10 ms",
     sub("Time", {"time step": "0.005"})
     + sub("Solver", {"FLIP fraction reference step": "0.01"})),
]

# a boulder at the flow's front (0.5 m square, 696 kg per metre, elastic,
# E = 1e8 Pa), each body with its own velocity field (friction 0.4 between
# them); the slope then acts on the material points (a boundary whose
# particles act on the grid has one velocity field)
BOULDER = [
    ("bodies", "boulder",
     sub("Body", {"number of bodies": "2"}) +
     sub("Body 2", {"material": "Material 2", "geometry": "polygon",
                    "vertices": "3.65, 3.903; 4.083, 3.653; 4.333, 4.086; "
                                "3.90, 4.336",
                    "points per cell per direction": "2"}) +
     sub("Material 2", {"model": "neo-Hookean", "density": "2784",
                        "Young's modulus": "1e8", "Poisson's ratio": "0.3"}) +
     sub("Body contact", {"contact": "multi-velocity field",
                          "friction coefficient": "0.4"}) +
     sub("Boundary particles/Boundary 1",
         {"contact side": "material points"})),
]
# the net's contact force with its end value on both fields
INTERFACE_END = sub("Coupling", {"interface force in time": "end of step"})
# (its contact point then moves with the material point; the variant
# 'interpolated' measures the gap anew at every step)
INTERPOLATED = sub("Boundary particles/Boundary 2",
                   {"contact point motion": "interpolated"})
BOULDER += [("bodies", "boulder, interface end of step",
             BOULDER[0][2] + INTERFACE_END),
            ("bodies", "boulder, interface end of step, interpolated",
             BOULDER[0][2] + INTERFACE_END + INTERPOLATED)]

VARIANTS = [("base", "base", "")] + GRID + STUDIES + [
    ("time step", "dt=0.0025", sub("Time", {"time step": "0.0025"})),
    ("interface force", "interface end of step", INTERFACE_END),
    ("interface force", "interface end of step, interpolated",
     INTERFACE_END + INTERPOLATED)] + \
    BOULDER + [
    ("trapezoidal " + study, "trapezoidal " + name, TRAPEZOIDAL + extra)
    for study, name, extra in [("base", "base", "")] + TRAPEZOIDAL_GRID
    + STUDIES + FLIP_PER_10_MS]


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def resample(t, f, dt=0.01):
    """f(t) linearly interpolated on the uniform times 0, dt, 2 dt, ..."""
    values, j = [], 0
    for i in range(int(round(t[-1] / dt)) + 1):
        x = i * dt
        while j + 1 < len(t) and t[j + 1] < x:
            j += 1
        k = min(j + 1, len(t) - 1)
        w = 0. if t[k] == t[j] else (x - t[j]) / (t[k] - t[j])
        values.append((1 - w) * f[j] + w * f[k])
    return values


def moving_average(values, half):
    """Centred moving average over 2 half + 1 samples (inner points)."""
    return [sum(values[i - half:i + half + 1]) / (2 * half + 1)
            for i in range(half, len(values) - half)]


def ringing(t, f, dt=0.01, width=0.1):
    """High-frequency content of a force history: the RMS of f minus its
    centred moving average over width (a low-pass above ~1/width Hz),
    after resampling on a uniform grid of step dt, from 0.2 s after the
    first impact's peak on (the spike of the impact itself is not
    ringing) while f is above 5 % of its largest value."""
    values = resample(t, f, dt)
    half = int(round(width / dt / 2))
    threshold = 0.05 * max(values)
    first = values.index(max(values)) + int(round(0.2 / dt))
    squares = []
    for i in range(max(half, first), len(values) - half):
        if values[i] < threshold:
            continue
        mean = sum(values[i - half:i + half + 1]) / (2 * half + 1)
        squares.append((values[i] - mean) ** 2)
    return (sum(squares) / len(squares)) ** 0.5 if squares else 0.


def run_in(talus, out, text, reuse):
    """Write the input text to out/run.prm and run talus on it in out
    (log in out/log), unless reuse is set: then only read the finished run
    there (exit code -1 if there is none); return
    the exit code, the wall time [s], the CPU time [s] of the run (user +
    system; -1 for a run recorded without it) and the log."""
    prm = os.path.join(out, "run.prm")
    done = os.path.join(out, "exit_code_and_wall")
    if reuse and not os.path.exists(done):
        # not finished (or still running in another invocation): do not
        # start a second run in the same directory
        return -1, 0., -1., "not run: no finished run in %s (--reuse)" % out
    if not reuse:
        with open(prm, "w") as f:
            f.write(text)
        start = time.time()
        with open(os.path.join(out, "log"), "w") as log:
            child = subprocess.Popen(["nice", talus, prm], stdout=log,
                                     stderr=subprocess.STDOUT, cwd=out)
            _, status, usage = os.wait4(child.pid, 0)
            rc = os.waitstatus_to_exitcode(status)
        with open(done, "w") as f:
            f.write("%d %.1f %.1f\n" % (rc, time.time() - start,
                                         usage.ru_utime + usage.ru_stime))
    with open(done) as f:
        fields = f.read().split()
    with open(os.path.join(out, "log")) as f:
        log = f.read()
    cpu = float(fields[2]) if len(fields) > 2 else -1.
    return int(fields[0]), float(fields[1]), cpu, log


def run_variant(talus, work, name, extra, reuse, input_file):
    """Run prm/<input_file> with the text extra appended in
    work/<name> (its output directories there); return that directory,
    the exit code, the wall and CPU times [s] and the log."""
    tag = re.sub(r"[^A-Za-z0-9.=-]+", "_", name)
    out = os.path.join(work, tag)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(ROOT, "prm", input_file)) as f:
        text = f.read()
    text = re.sub(r"set output directory = .*",
                  "set output directory = %s" % out, text)
    rc, wall, cpu, log = run_in(talus, out, text + "\n" + extra, reuse)
    return out, rc, wall, cpu, log


def failure(rc, log):
    """The row of a run that failed."""
    return "failed (exit %d): %s" % (rc, log.strip().splitlines()[-1])


def run(talus, work, name, extra, reuse):
    """Run one variant, return its row of results (or an error string)."""
    out, rc, wall, _, log = run_variant(talus, work, name, extra, reuse,
                                        "flexible_barrier_2d.prm")
    if rc != 0:
        return failure(rc, log)
    s = read_csv(os.path.join(out, "structure.csv"))
    c = read_csv(os.path.join(out, "coupling.csv"))
    released = c["gravitational_energy"][0] - c["gravitational_energy"][-1]
    i_peak = max(range(len(s["net_force"])), key=lambda i: s["net_force"][i])
    barrier = (c["structure_energy"][-1] - c["structure_energy"][0] +
               c["barrier_dissipation"][-1])
    ring = 100 * ringing(s["time"], s["net_force"]) / s["net_force"][-1]
    m = re.search(r"Done: (\d+) coupled steps \((\d+) rejected\), "
                  r"([0-9.]+) coupling iterations per step", log)
    return dict(
        F_peak=s["net_force"][i_peak] / 1e3, t_peak=s["time"][i_peak],
        F_avg=max(moving_average(resample(s["time"], s["net_force"]), 5))
        / 1e3,
        F_end=s["net_force"][-1] / 1e3,
        rope=max(s["rope_force"]) / 1e3,
        stroke=s["brake_stroke"][-1],
        defl_max=max(s["largest_displacement"]),
        defl_end=s["largest_displacement"][-1],
        E_bar=100 * barrier / released,
        fric=100 * c["friction_dissipation"][-1] / released,
        plast=100 * c["plastic_dissipation"][-1] / released,
        bal=100 * c["energy_change"][-1] / released,
        ring=ring,
        its=float(m.group(3)) if m else float("nan"),
        rej=int(m.group(2)) if m else -1,
        wall=wall)


COLUMNS = [("F_peak", "%.1f"), ("t_peak", "%.2f"), ("F_avg", "%.1f"),
           ("F_end", "%.1f"),
           ("rope", "%.1f"), ("stroke", "%.3f"), ("defl_max", "%.3f"),
           ("defl_end", "%.3f"), ("E_bar", "%.2f"), ("fric", "%.1f"),
           ("plast", "%.1f"), ("bal", "%.2f"), ("ring", "%.2f"),
           ("its", "%.2f"),
           ("rej", "%d"), ("wall", "%.0f")]


def plot_studies(work, variants, results, path, series, ylabel, xmin):
    """One panel per study, each with the base: series(run directory)
    gives the times and the force [kN] of a run. The earlier input's
    family (studies named "trapezoidal ...") is in the table only."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    studies = []
    for study, _, _ in variants:
        if study != "base" and not study.startswith("trapezoidal") and \
                study not in studies:
            studies.append(study)
    studies = studies or ["base"]
    columns = 2
    rows = (len(studies) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(12, 3.2 * rows),
                             squeeze=False, sharex=True)
    base = os.path.join(work, "base")
    for ax, study in zip(axes.flat, studies):
        if os.path.exists(os.path.join(base, "exit_code_and_wall")):
            ax.plot(*series(base), "k-", lw=1, label="base")
        for (st, name, _), r in zip(variants, results):
            if st != study or isinstance(r, str):
                continue
            tag = re.sub(r"[^A-Za-z0-9.=-]+", "_", name)
            ax.plot(*series(os.path.join(work, tag)), lw=1, label=name)
        ax.set_title(study, fontsize=10)
        ax.set_ylabel(ylabel)
        ax.set_xlim(xmin, None)
        ax.legend(fontsize=8)
    for ax in axes.flat[len(studies):]:
        ax.axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    print("wrote %s" % path, file=sys.stderr)


def run_study(description, variants, run, columns, default_work, plot):
    """The command line of a study: run the variants (run(talus, work,
    name, appended text, reuse) returns a row or an error string), draw
    them with plot(work, variants, results, path) and print the table."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--talus", default=os.path.join(ROOT, "build",
                                                         "talus"))
    parser.add_argument("--only", nargs="*", help="variant names to run")
    parser.add_argument("--work", default=default_work)
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--plot", metavar="PNG",
                        help="draw the force of every variant")
    parser.add_argument("--reuse", action="store_true",
                        help="report the runs already in the work "
                        "directory instead of running them again")
    args = parser.parse_args()
    talus = os.path.abspath(args.talus)
    work = os.path.abspath(args.work)
    chosen = [v for v in variants if not args.only or v[1] in args.only]
    unknown = set(args.only or []) - {v[1] for v in variants}
    if unknown:
        sys.exit("unknown variants: %s (known: %s)" % (
            ", ".join(sorted(unknown)), ", ".join(v[1] for v in variants)))
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda v: run(talus, work, v[1], v[2],
                                                args.reuse),
                                chosen))
    if args.plot:
        plot(work, chosen, results, args.plot)
    print("| study | variant | " + " | ".join(c for c, _ in columns) + " |")
    print("|---" * (len(columns) + 2) + "|")
    for (study, name, _), r in zip(chosen, results):
        if isinstance(r, str):
            print("| %s | %s | %s |" % (study, name, r))
        else:
            print("| %s | %s | " % (study, name) + " | ".join(
                f % r[c] for c, f in columns) + " |")


def net_force(directory):
    """Times and net force [kN/m] of a run of the 2D study."""
    s = read_csv(os.path.join(directory, "structure.csv"))
    return s["time"], [f / 1e3 for f in s["net_force"]]


def main():
    run_study(__doc__.splitlines()[0], VARIANTS, run, COLUMNS,
              "flexible_barrier_2d_study",
              lambda work, variants, results, path: plot_studies(
                  work, variants, results, path, net_force,
                  "net force [kN/m]", 2.0))


if __name__ == "__main__":
    main()
