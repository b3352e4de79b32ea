#!/usr/bin/env python3
"""Convergence and sensitivity study of the 3D flagship.

Runs prm/flexible_barrier.prm (25 m^3 of granular material into the
three-field barrier, 0.5 m cells) once per variant, each variant the base
file with a few parameters set anew (appended subsections: the last value
set wins), and prints one table row per variant with what a barrier
engineer reads off a run:

  F_1      first impact: the largest force on the net within 0.3 s of
           the first contact [kN], and its time [s]
  F_peak   largest impact force on the net [kN] and its time [s]
  F_avg    largest 0.11 s moving average of that force [kN]
  F_end    the force at the end (material at rest) [kN]
  mid      share of the middle field in the force at the end [%]
  bottom   largest force in the bottom support cable [kN]
  rope     largest force in a retaining rope [kN]
  stroke   largest brake stroke at the end [m]
  E_diss   energy the barrier dissipated (brakes and damping) [kJ]
  defl     largest and final deflection of the net [m]
  height   residual height of the net's top edge at the end [m]
  E_bar    energy taken by the barrier: stored + kinetic change + brakes
           and damping, in % of the released gravitational energy
  fric, plast   friction and plastic dissipation [% released]
  bal      the energy balance error at the end [% released]
  its      coupling iterations per step, and per step in contact
  rej      rejected steps; cpu: CPU time of the run [s]

Studies (doc/verification.md, "Flexible barrier (3D): convergence and
sensitivity"): MPM cell size (1, 0.5, 0.25 m; the last takes hours),
net mesh, time step, coupling tolerance; net stiffness, the net's
wrinkling law, brake activation force, basal friction and material model;
the sensitivity studies also with the earlier input's trapezoidal contact
force on the slope and 20 ms steps (studies "trapezoidal ...").

usage: contrib/flexible_barrier_3d_study.py [--talus PATH] [--only NAME...]
       [--work DIR] [--jobs N] [--reuse] [--plot PNG]
"""

import math
import os
import re

from flexible_barrier_2d_study import (SLOPE_AND_MATERIAL, failure,
                                       moving_average, plot_studies, read_csv,
                                       resample, run_study, run_variant, sub)

# The input takes the slope's contact force at its end value, 10 ms steps
# (the net, a moving coupling interface, keeps the trapezoidal rule;
# doc/theory.md, "Contact force in time"). The variants of the earlier
# input, trapezoidal contact on the slope and 20 ms steps, are appended
# with it ("trapezoidal" in their study's name) for comparison.
TRAPEZOIDAL = sub("Solver", {"contact force in time": "trapezoidal",
                             "start acceleration": "projected"}) \
    + sub("Time", {"time step": "0.02"})

SENSITIVITY = [
    # the net's cells (10 x 8 per field in the base): twice as fine
    ("net mesh", "net 20x16",
     sub("Structure/Barrier", {"net cells per field": "20",
                               "net cells over height": "16"})),
    # coupling tolerance (relative 1e-4 in the base)
    ("coupling tolerance", "tol=1e-5",
     sub("Coupling", {"relative tolerance": "1e-5"})),
    # net stiffness: E t = 1e6 N/m in both directions in the base
    ("net stiffness", "Et x0.5",
     sub("Structure/Membrane", {"Young's modulus": "5e8",
                                "Young's modulus 2": "5e8"})),
    ("net stiffness", "Et x2",
     sub("Structure/Membrane", {"Young's modulus": "2e9",
                                "Young's modulus 2": "2e9"})),
    # the net without the wrinkling (tension-field) law: it then carries
    # compression
    ("net law", "no wrinkling",
     sub("Structure/Membrane", {"wrinkling": "false"})),
    # brake activation force (50 kN in the base, where the retaining
    # ropes carry at most 16 kN); below the rope force
    ("brake", "brake 10 kN",
     sub("Structure/Brake", {"activation force": "1e4"})),
    ("brake", "brake 5 kN",
     sub("Structure/Brake", {"activation force": "5e3"})),
] + SLOPE_AND_MATERIAL

# time steps of the trapezoidal family (the FLIP/PIC blend 0.95 per
# 20 ms, 'FLIP fraction reference step', whatever the step; "FLIP per
# step": the blend once per step, the reference step 0), and the contact
# onset event with its forecast: the step shortened ahead of the first
# touch of the net, steps of at most 2 ms while the number of points on
# it changes sharply
TRAPEZOIDAL_TIME_STEPS = [
    ("time step", "dt=%s" % dt, sub("Time", {"time step": dt}))
    for dt in ("0.01", "0.005", "0.0025")] + [
    ("time step", "dt=%s, FLIP per step" % dt,
     sub("Time", {"time step": dt})
     + sub("Solver", {"FLIP fraction reference step": "0"}))
    for dt in ("0.01", "0.005")] + [
    ("time step", "onset 2 ms",
     sub("Time", {"contact onset time step": "0.002"})),
    ("time step", "dt=0.01, onset 2 ms",
     sub("Time", {"time step": "0.01", "contact onset time step": "0.002"})),
]

# (study, name, appended prm text)
INTERFACE_END = sub("Coupling", {"interface force in time": "end of step"})

VARIANTS = [
    ("base", "base", ""),
] + [("time step", "dt=%s" % dt, sub("Time", {"time step": dt}))
     for dt in ("0.02", "0.005", "0.0025")] + [
    # MPM cell size: 0.5 m (base), 1 m, 0.25 m; 2 x 2 x 2 points per cell
    # and the net unchanged. At 1 m the grid starts at z = -1 m so that the
    # 1 m thick block fills whole cells (from the input's z = -0.25 m the
    # cells cut by its top face would make it 1.5 m thick). At 0.25 m the
    # grid starts at z = -0.125 m so that the slope z = 0 cuts a cell layer
    # in half, as at 0.5 m (on the input's z = -0.25 m the slope lies on
    # cell faces, and points pushed through it at the net's foot sink in
    # cells without boundary particles and leave the grid); 79 200 cells,
    # 12 800 points, hours of CPU time: a checkpoint every 10 minutes, so
    # that a stopped run continues with
    #   talus --resume <work>/h=0.25/checkpoints <work>/h=0.25/run.prm
    ("cell size", "h=1",
     sub("Background grid", {"lower corner": "0, -3, -1",
                             "upper corner": "15, 14, 4",
                             "subdivisions": "15, 17, 5"})),
    ("cell size", "h=0.25",
     sub("Background grid", {"lower corner": "0, -3, -0.125",
                             "upper corner": "15, 13.5, 4.875",
                             "subdivisions": "60, 66, 20"}) +
     sub("Checkpoint", {"every minutes": "10"})),
] + SENSITIVITY + [
    # the net's contact force with its end value on both fields, the
    # contact point moving with the material point (the default then) or
    # interpolated (the gap measured anew at every step)
    ("interface force", "interface end of step", INTERFACE_END),
    ("interface force", "interface end of step, interpolated",
     INTERFACE_END + sub("Boundary particles/Boundary 2",
                         {"contact point motion": "interpolated"})),
] + [
    ("trapezoidal " + study, "trapezoidal " + name, TRAPEZOIDAL + extra)
    for study, name, extra in [("base", "base", "")] + TRAPEZOIDAL_TIME_STEPS
    + SENSITIVITY]

BRAKES = ["0a", "0b", "1a", "1b", "2a", "2b", "3a", "3b"]


def impact_force(c):
    """The magnitude of the interface force on the net per step [N]."""
    return [math.sqrt(x * x + y * y + z * z)
            for x, y, z in zip(c["interface_force_x"], c["interface_force_y"],
                               c["interface_force_z"])]


def run(talus, work, name, extra, reuse):
    """Run one variant, return its row of results (or an error string)."""
    out, rc, _, cpu, log = run_variant(talus, work, name, extra, reuse,
                                       "flexible_barrier.prm")
    if rc != 0:
        return failure(rc, log)
    s = read_csv(os.path.join(out, "structure.csv"))
    c = read_csv(os.path.join(out, "coupling.csv"))
    force = impact_force(c)
    released = c["gravitational_energy"][0] - c["gravitational_energy"][-1]
    i_peak = max(range(len(force)), key=lambda i: force[i])
    barrier = (c["structure_energy"][-1] - c["structure_energy"][0] +
               c["barrier_dissipation"][-1])
    its = c["coupling_iterations"]
    contact = [i for i, f in enumerate(force) if f > 0]
    in_contact = [its[i] for i in range(contact[0], len(its))] \
        if contact else []
    m = re.search(r"Done: (\d+) coupled steps \((\d+) rejected\), "
                  r"([0-9.]+) coupling iterations per step", log)
    mid = s["field_1_force"][-1]
    fields = sum(abs(s["field_%d_force" % k][-1]) for k in range(3))
    first = [i for i in contact
             if c["time"][i] <= c["time"][contact[0]] + 0.3 + 1e-9] \
        if contact else [0]
    i_first = max(first, key=lambda i: force[i])
    return dict(
        F_1=force[i_first] / 1e3, t_1=c["time"][i_first],
        F_peak=force[i_peak] / 1e3, t_peak=c["time"][i_peak],
        F_avg=max(moving_average(resample(c["time"], force), 5)) / 1e3,
        F_end=force[-1] / 1e3,
        mid=100 * abs(mid) / fields if fields > 0 else 0.,
        bottom=max(s["bottom_cable_force"]) / 1e3,
        rope=max(s["retaining_ropes_force"]) / 1e3,
        stroke=max(s["brake_%s_stroke" % b][-1] for b in BRAKES),
        E_diss=s["dissipated_energy"][-1] / 1e3,
        defl_max=max(s["net_deflection"]),
        defl_end=s["net_deflection"][-1],
        height=s["net_residual_height"][-1],
        E_bar=100 * barrier / released,
        fric=100 * c["friction_dissipation"][-1] / released,
        plast=100 * c["plastic_dissipation"][-1] / released,
        bal=100 * c["energy_change"][-1] / released,
        its=float(m.group(3)) if m else float("nan"),
        its_c=sum(in_contact) / len(in_contact) if in_contact else 0.,
        rej=int(m.group(2)) if m else -1,
        cpu=cpu)


COLUMNS = [("F_1", "%.0f"), ("t_1", "%.2f"), ("F_peak", "%.0f"), ("t_peak", "%.2f"), ("F_avg", "%.0f"),
           ("F_end", "%.0f"), ("mid", "%.0f"), ("bottom", "%.0f"),
           ("rope", "%.1f"), ("stroke", "%.3f"), ("E_diss", "%.1f"),
           ("defl_max", "%.2f"), ("defl_end", "%.2f"), ("height", "%.2f"),
           ("E_bar", "%.2f"), ("fric", "%.1f"), ("plast", "%.1f"),
           ("bal", "%.2f"), ("its", "%.2f"), ("its_c", "%.2f"),
           ("rej", "%d"), ("cpu", "%.0f")]


def impact_series(directory):
    """Times and impact force [kN] of a run of the 3D study."""
    c = read_csv(os.path.join(directory, "coupling.csv"))
    return c["time"], [f / 1e3 for f in impact_force(c)]


def main():
    run_study(__doc__.splitlines()[0], VARIANTS, run, COLUMNS,
              "flexible_barrier_3d_study",
              lambda work, variants, results, path: plot_studies(
                  work, variants, results, path, impact_series,
                  "impact force [kN]", 1.5))


if __name__ == "__main__":
    main()
