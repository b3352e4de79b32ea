#!/usr/bin/env python3
"""Input generator and runout extractor for the Bui et al. 2008 collapse in
CB-Geo MPM (https://github.com/cb-geo/mpm), the explicit peer code of the
time-to-solution comparison (doc/performance.md, contrib/benchmark/cbgeo_bui.sh).

  cbgeo_bui.py generate DIR --cell H [--dt DT] [--end-time T] [--scheme usf]
                        [--velocity-update pic|flip]
      writes DIR/mpm.json, mesh.txt, particles.txt, velocity-constraints.txt
      and friction-constraints.txt: the case of
      benchmarks/granular_collapse/bui2008_<H>mm*.prm as far as CB-Geo has it
      - grid 0.6 x 0.12 m of square 4-node cells (ED2Q4) of edge H;
      - column 0.2 x 0.1 m against the wall x = 0, 2 x 2 points per cell at
        the centres of the cell's quarters (Talus' 'points per cell per
        direction = 2'), each of volume H^2/4;
      - rho = 2650 kg/m^3, E = 0.84 MPa, nu = 0.3, Mohr-Coulomb
        (MohrCoulomb2D) phi = 19.8 deg, psi = 0, c = 0, no softening, no
        tension (cut-off 0): Talus' rate-independent Mohr-Coulomb; CB-Geo
        has no mu(I) friction;
      - initial stresses: geostatic, K0 = nu/(1 - nu) (particles-stresses.txt;
        CB-Geo's Mohr-Coulomb gives NaN from a zero stress);
      - wall x = 0 smooth (x-velocity 0), floor y = 0: y-velocity 0 and
        Coulomb friction mu = 0.36 = tan 19.8 deg (CB-Geo's nodal friction
        constraint);
      - explicit steps of DT (default 5e-5 s) to T (default 1 s), USF and
        PIC velocity update ('velocity_update': true maps the grid velocity
        back to the points; flip: false, the points' velocities are
        incremented by the grid acceleration); particles written at the
        first and the last step only (HDF5).
  cbgeo_bui.py runout DIR [--cell H]
      reads the last particles*.h5 under DIR/results and prints
      "runout L n_points" with Talus' definition (io/deposit_profile.h):
      points sorted by x, largest first, equal masses; the front is the
      first point at which more than 0.1 % of the points and more than one
      point have been counted; L = x_front + d_p/2, d_p = H/2 the point
      spacing.  Needs h5py.
"""
import argparse
import glob
import json
import os
import sys

DOMAIN = (0.6, 0.12)
COLUMN = (0.2, 0.1)
FLOOR_FRICTION = 0.36
RHO, E, NU, G = 2650.0, 0.84e6, 0.3, 9.81


def generate(args):
    h = args.cell
    nx, ny = round(DOMAIN[0] / h), round(DOMAIN[1] / h)
    cx, cy = round(COLUMN[0] / h), round(COLUMN[1] / h)
    if abs(nx * h - DOMAIN[0]) > 1e-12 or abs(cx * h - COLUMN[0]) > 1e-12 \
            or abs(cy * h - COLUMN[1]) > 1e-12:
        sys.exit("cbgeo_bui.py: --cell must divide 0.6, 0.2 and 0.1 m")
    os.makedirs(args.dir, exist_ok=True)

    def node(i, j):
        return j * (nx + 1) + i

    with open(os.path.join(args.dir, "mesh.txt"), "w") as f:
        f.write("! elementShape quadrilateral\n! elementNumPoints 4\n")
        f.write("%d\t%d\n" % ((nx + 1) * (ny + 1), nx * ny))
        for j in range(ny + 1):
            for i in range(nx + 1):
                f.write("%.10g\t%.10g\n" % (i * h, j * h))
        for j in range(ny):
            for i in range(nx):
                f.write("%d\t%d\t%d\t%d\n" % (node(i, j), node(i + 1, j),
                                              node(i + 1, j + 1),
                                              node(i, j + 1)))
    with open(os.path.join(args.dir, "velocity-constraints.txt"), "w") as f:
        for j in range(ny + 1):
            f.write("%d\t0\t0\n" % node(0, j))
        for i in range(nx + 1):
            f.write("%d\t1\t0\n" % node(i, 0))
    with open(os.path.join(args.dir, "friction-constraints.txt"), "w") as f:
        # node, normal direction, sign of the normal pointing into the floor,
        # friction coefficient
        for i in range(nx + 1):
            f.write("%d\t1\t-1\t%g\n" % (node(i, 0), FLOOR_FRICTION))
    points = [((i + 0.5) * h / 2, (j + 0.5) * h / 2)
              for j in range(2 * cy) for i in range(2 * cx)]
    with open(os.path.join(args.dir, "particles.txt"), "w") as f:
        f.write("%d\n" % len(points))
        for x, y in points:
            f.write("%.10g\t%.10g\n" % (x, y))

    # Initial stresses: the geostatic state of the column, sigma_yy =
    # -rho g (H - y), sigma_xx = sigma_zz = K0 sigma_yy with K0 = nu/(1-nu)
    # (uniaxial strain). CB-Geo's MohrCoulomb2D returns NaN from a zero
    # stress (the first step of a column released unstressed), and the
    # return maps this state onto the yield surface in the first step (K0 =
    # 0.43 lies below the active coefficient 0.49 for phi = 19.8 deg).
    k0 = NU / (1 - NU)
    with open(os.path.join(args.dir, "particles-stresses.txt"), "w") as f:
        f.write("%d\n" % len(points))
        for _, y in points:
            syy = -RHO * G * (COLUMN[1] - y)
            f.write("%.10g\t%.10g\t%.10g\t0\t0\t0\n" % (k0 * syy, syy,
                                                         k0 * syy))

    nsteps = round(args.end_time / args.dt)
    config = {
        "title": "Bui et al. 2008 collapse, %g mm cells (Talus comparison)" %
                 (1000 * h),
        "mesh": {
            "mesh": "mesh.txt",
            "io_type": "Ascii2D",
            "check_duplicates": False,
            "isoparametric": False,
            "node_type": "N2D",
            "cell_type": "ED2Q4",
            "particles_stresses": "particles-stresses.txt",
            "boundary_conditions": {
                "velocity_constraints": [{"file": "velocity-constraints.txt"}],
                "friction_constraints": [{"file": "friction-constraints.txt"}]
            }
        },
        "particles": [{
            "generator": {
                "type": "file",
                "location": "particles.txt",
                "io_type": "Ascii2D",
                "check_duplicates": False,
                "particle_type": "P2D",
                "material_id": 0,
                "pset_id": 0
            }
        }],
        "materials": [{
            "id": 0,
            "type": "MohrCoulomb2D",
            "density": RHO,
            "youngs_modulus": E,
            "poisson_ratio": NU,
            "softening": False,
            "friction": 19.8,
            "dilation": 0.0,
            "cohesion": 0.0,
            "residual_friction": 19.8,
            "residual_dilation": 0.0,
            "residual_cohesion": 0.0,
            "peak_pdstrain": 0.0,
            "residual_pdstrain": 0.0,
            "tension_cutoff": 0.0,
            "tolerance": 1.0e-12
        }],
        "external_loading_conditions": {"gravity": [0.0, -G]},
        "analysis": {
            "type": "MPMExplicit2D",
            "mpm_scheme": args.scheme,
            "velocity_update": args.velocity_update == "pic",
            "locate_particles": False,
            "dt": args.dt,
            "nsteps": nsteps,
            "uuid": "bui2008",
            "resume": {"resume": False}
        },
        "post_processing": {
            "path": "results/",
            # steps 0 and nsteps - 1 (the state at t = nsteps dt)
            "output_steps": nsteps - 1,
            "vtk": []
        }
    }
    with open(os.path.join(args.dir, "mpm.json"), "w") as f:
        json.dump(config, f, indent=2)
    print("%d %d %d" % (nx * ny, len(points), nsteps))


def runout(args):
    import h5py
    files = sorted(glob.glob(os.path.join(args.dir, "results", "**",
                                          "particles*.h5"), recursive=True))
    if not files:
        sys.exit("cbgeo_bui.py: no particles*.h5 under %s/results" % args.dir)
    with h5py.File(files[-1], "r") as f:
        table = f["table"][()]
    xs = sorted((float(x) for x in table["coord_x"]), reverse=True)
    n = len(xs)
    front = next(k for k in range(n) if k + 1 > 0.001 * n and k + 1 > 1)
    print("%.6f %d %s" % (xs[front] + args.cell / 4, n,
                          os.path.basename(files[-1])))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate")
    g.add_argument("dir")
    g.add_argument("--cell", type=float, required=True, help="cell edge [m]")
    g.add_argument("--dt", type=float, default=5e-5)
    g.add_argument("--end-time", type=float, default=1.0)
    g.add_argument("--scheme", default="usf", choices=["usf", "usl", "musl"])
    g.add_argument("--velocity-update", default="pic", choices=["pic", "flip"])
    r = sub.add_parser("runout")
    r.add_argument("dir")
    r.add_argument("--cell", type=float, required=True, help="cell edge [m]")
    args = parser.parse_args()
    if not args.dir.endswith("/"):
        args.dir += "/"
    generate(args) if args.command == "generate" else runout(args)


if __name__ == "__main__":
    main()
