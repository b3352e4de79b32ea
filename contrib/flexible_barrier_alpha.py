#!/usr/bin/env python3
"""The dynamic pressure coefficient of the flagships' first impact.

alpha = F_1 / (rho v^2 h w) (../shared/VERIFICATION.md section 5: 0.5-2.0
for flexible barriers), with F_1 the first impact (the largest force on
the net within 0.3 s of the first contact, as in
contrib/flexible_barrier_3d_study.py) and v, h, w the flow's speed, depth
and width just before contact, measured on the material points of the
last particle output before the first contact (interface force
above 1 kN, or 1 kN/m in 2D), in the front: the points within 'front length' of the
foremost point downslope.

  v  mass-weighted mean speed of the front's points [m/s]
  h  the front's depth normal to the ground: the 95th percentile of
     the points' height plus half a point spacing [m]
  w  the front's width across the slope: 5th to 95th percentile of x plus
     one point spacing [m] (3D)

3D (prm/flexible_barrier.prm, the slope frame): the slope is z = 0, the
flow runs towards -y. 2D (prm/flexible_barrier_2d.prm, per metre of
width, w = 1 m): the flow runs towards +x over the flat runout y = 0
before the net, h from y. The inputs write particles every 0.25 s (3D)
and 0.1 s (2D); for the state just before contact run them again into
OUTPUT_DIR with 'output interval = 0.02' and 'end time = 1.92' (3D), or
0.01 and 2.79 (2D), and take the first impact from the full run's
coupling.csv (--impact RUN_DIR):

usage: contrib/flexible_barrier_alpha.py OUTPUT_DIR [--impact RUN_DIR]
       [--density 2085] [--front-length 1] [--spacing 0.25]

Needs PyVista (PyPI) to read the VTU files.
"""

import argparse
import math
import os
import xml.etree.ElementTree as ET

from flexible_barrier_2d_study import read_csv


def first_impact(directory):
    """First contact time [s], first impact [N] and its time [s]."""
    c = read_csv(os.path.join(directory, "coupling.csv"))
    zero = [0.] * len(c["time"])
    force = [math.sqrt(x * x + y * y + z * z)
             for x, y, z in zip(c["interface_force_x"], c["interface_force_y"],
                                c.get("interface_force_z", zero))]
    contact = [i for i, f in enumerate(force) if f > 1e3]
    if not contact:
        raise SystemExit("no contact in %s/coupling.csv" % directory)
    t0 = c["time"][contact[0]]
    window = [i for i in contact if c["time"][i] <= t0 + 0.3 + 1e-9]
    i1 = max(window, key=lambda i: force[i])
    return (t0, force[i1], c["time"][i1], c["time"][-1],
            "interface_force_z" in c)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory")
    parser.add_argument("--impact", help="the run whose coupling.csv gives "
                        "the first impact (default: DIRECTORY)")
    parser.add_argument("--density", type=float, default=2085.)
    parser.add_argument("--front-length", type=float, default=1.)
    parser.add_argument("--spacing", type=float,
                        help="initial point spacing [m] (cell / points "
                        "per cell per direction; default 0.25 in 3D, 0.1 "
                        "in 2D)")
    args = parser.parse_args()
    import numpy
    import pyvista

    t0, f1, t1, t_end, three_d = first_impact(args.impact or args.directory)
    spacing = args.spacing or (0.25 if three_d else 0.1)
    pvd = ET.parse(os.path.join(args.directory, "particles.pvd")).getroot()
    outputs = [(float(d.get("timestep")), d.get("file"))
               for d in pvd.iter("DataSet")]
    before = [o for o in outputs if o[0] < t0 - 1e-9]
    if not before:
        raise SystemExit("no particle output before the first contact")
    t, name = before[-1]
    m = pyvista.read(os.path.join(args.directory, name))
    xyz, mass, vel = m.points, m["mass"], m["velocity"]
    # along the flow (the front is its foremost point), height, across
    if three_d:
        frame = [(-p[1], p[2], p[0]) for p in xyz]
    else:
        frame = [(p[0], p[1], 0.) for p in xyz]
    front = max(p[0] for p in frame)
    ids = [i for i, p in enumerate(frame)
           if p[0] >= front - args.front_length]
    weight = sum(mass[i] for i in ids)
    v = sum(mass[i] * math.sqrt(sum(c * c for c in vel[i]))
            for i in ids) / weight
    h = numpy.percentile([frame[i][1] for i in ids], 95) + 0.5 * spacing
    w = (numpy.percentile([frame[i][2] for i in ids], 95) -
         numpy.percentile([frame[i][2] for i in ids], 5) + spacing) \
        if three_d else 1.
    alpha = f1 / (args.density * v * v * h * w)
    print("first contact %.3f s; particles at %.3f s: %d points within "
          "%.2f m of the front" % (t0, t, len(ids), args.front_length))
    print("v = %.2f m/s, h = %.2f m, w = %.2f m; first impact F_1 = %.1f kN%s "
          "at %.3f s" % (v, h, w, f1 / 1e3, "" if three_d else "/m", t1))
    print("alpha = F_1 / (rho v^2 h w) = %.2f" % alpha)
    if t_end < t0 + 0.3:
        print("(the run ends within 0.3 s of the first contact: F_1 may "
              "not be the first impact's peak)")


if __name__ == "__main__":
    main()
