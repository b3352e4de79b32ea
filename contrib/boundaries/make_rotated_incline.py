#!/usr/bin/env python3
"""Write the rotated-incline inputs of tests/boundaries (VERIFICATION.md 2.3).

A block (0.4 m x 0.2 m, neo-Hookean, 2000 kg/m^3) slides on a 30 degree
incline with Coulomb friction mu. The whole problem (incline line and gravity)
is rotated by rho against the axis-aligned background grid; the incline is a
'line' boundary imposed by boundary particles. Reference: the block slides
along t = (cos rho, sin rho) by s(t) = a t^2 / 2 with
a = g (sin 30 - mu cos 30) when tan 30 > mu, and stays at rest otherwise.

    usage: make_rotated_incline.py <output dir>
"""
import math
import sys

G, THETA = 9.81, math.radians(30.)
H = 0.05  # background cell size [m]


def write(path, rho_deg, mu, condition, method_lines="", end_time=1.0,
          mpi_note="", max_penetration=None, solver_lines="", offset=0.,
          damping=True, output_directory=None):
    rho = math.radians(rho_deg)
    t = (math.cos(rho), math.sin(rho))
    n = (-math.sin(rho), math.cos(rho))
    # incline line through o, from s = -0.2 to s = 3.2
    # (offset: a shift of the whole problem along y, which changes how the
    # incline and the block cut the cells)
    o = (0.3 + 0.2 * math.sin(rho), 0.137 + offset)
    line = [(o[0] + s * t[0], o[1] + s * t[1]) for s in (-0.2, 3.2)]
    # block corners: s in [0.1, 0.5], normal offset in [0, 0.2]
    corners = []
    for s, h in ((0.1, 0.), (0.5, 0.), (0.5, 0.2), (0.1, 0.2)):
        corners.append((o[0] + s * t[0] + h * n[0], o[1] + s * t[1] + h * n[1]))
    xs = [p[0] for p in line + corners]
    ys = [p[1] for p in line + corners]
    upper = (math.ceil((max(xs) + 0.2) / H) * H,
             math.ceil((max(ys) + 0.3) / H) * H)
    gvec = (G * (math.sin(THETA) * t[0] - math.cos(THETA) * n[0]),
            G * (math.sin(THETA) * t[1] - math.cos(THETA) * n[1]))
    sliding = math.tan(THETA) > mu
    a = G * (math.sin(THETA) - mu * math.cos(THETA)) if sliding else 0.
    fmt = lambda p: "%.10g, %.10g" % p
    newmark = ("""  # numerical damping of the acceleration jumps when boundary particles
  # start or stop acting (doc/theory.md, "Boundary particles")
  set Newmark gamma = 0.6
  set Newmark beta = 0.3025
""" if damping else "")
    out_dir = output_directory or \
        "output-" + path.split('/')[-1].split('.')[0]
    with open(path, "w") as f:
        f.write(f"""# Block on a 30 degree incline rotated by {rho_deg} degrees against the
# grid, Coulomb friction mu = {mu} ({condition}), imposed by boundary particles
# (VERIFICATION.md 2.3). Written by contrib/boundaries/make_rotated_incline.py.
# Reference: a = g (sin 30 - mu cos 30) = {a:.6g} m/s^2 along
# t = ({t[0]:.6g}, {t[1]:.6g}); s(t) = a t^2 / 2{"" if sliding else " = 0 (stick)"}.
set dimension = 2
subsection Background grid
  set lower corner = 0, 0
  set upper corner = {fmt(upper)}
  set subdivisions = {round(upper[0] / H)}, {round(upper[1] / H)}
end
subsection Body
  set geometry = polygon
  set vertices = {'; '.join(fmt(c) for c in corners)}
  set points per cell per direction = 2
end
subsection Material
  set model = neo-Hookean
  set density = 2000
  set Young's modulus = 1e7
  set Poisson's ratio = 0.3
end
subsection Boundary particles
  subsection Boundary 1
    set geometry = line
    set name = incline
    set vertices = {'; '.join(fmt(p) for p in line)}
    set condition = {condition}
    set friction coefficient = {mu}
{method_lines}  end
end
subsection Solver
  set gravity = {fmt(gvec)}
  set linear solver = direct
{solver_lines}end
subsection Time
  set end time = {end_time}
  set time step = 0.01
{newmark}end
subsection Output
  set output directory = {out_dir}
  set format = none
  set test mode = true
end
subsection Verification
  set compare with exact solution = true
  set report times = 0.5
  subsection Exact displacement
    set Function expression = {0.5 * a * t[0]:.10g}*t*t; {0.5 * a * t[1]:.10g}*t*t
  end
  # 1 % of s(0.5 s) for sliding; 1 % of h for the stick case (the elastic
  # settlement of the block under its weight is about 1.5e-4 m)
  set displacement error tolerance = {0.01 * 0.125 * a if sliding else 0.01 * H:.6g}
  set maximum penetration = {max_penetration or 1e-3 * H:.6g}
{"  set maximum final speed = 1e-4" + chr(10) if not sliding else ""}end
""")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    for rho in (0, 15, 30, 45):
        write(f"{out}/incline_rotated_{rho}_mu0.prm", rho, 0.0, "contact")
        write(f"{out}/incline_rotated_{rho}_mu01.prm", rho, 0.1, "friction")
        write(f"{out}/incline_rotated_{rho}_stick.prm", rho, 0.7, "friction")
    # the cell-wise constraint (one mean gap per cell and boundary)
    write(f"{out}/incline_rotated_30_mu01_per_cell.prm", 30, 0.1, "friction",
          method_lines="    set constraint = per cell\n")
    write(f"{out}/incline_rotated_30_stick_per_cell.prm", 30, 0.7, "friction",
          method_lines="    set constraint = per cell\n")
    # augmented Lagrangian with cell-wise constant multipliers: with penalty
    # factor 1 the penalty alone lets the block sink by 4.6e-4 h; the
    # multipliers hold the gap below 1e-5 h (per particle, the constraints
    # of a rotated line over-determine the bilinear field and Uzawa stalls)
    al = ("    set method = augmented Lagrangian\n"
          "    set constraint = per cell\n")
    write(f"{out}/incline_rotated_30_stick_augmented_factor1.prm", 30, 0.7,
          "friction", method_lines=al + "    set penalty factor = 1\n",
          max_penetration=1e-5 * H)
    write(f"{out}/incline_rotated_30_mu01_augmented_factor10.prm", 30, 0.1,
          "friction", method_lines=al + "    set penalty factor = 10\n",
          max_penetration=1e-5 * H)
    write(f"{out}/incline_rotated_45_mu0_augmented.prm", 45, 0.0, "contact",
          method_lines=al)
    # Lagrange multipliers as Newton unknowns (saddle-point solve; the
    # multipliers are cell-wise constant by default): the gap holds to the
    # multiplier tolerance whatever the factor, which only enters the
    # trial force of the contact decisions
    lm = "    set method = Lagrange multiplier\n"
    write(f"{out}/incline_rotated_30_stick_lagrange_factor1.prm", 30, 0.7,
          "friction", method_lines=lm + "    set penalty factor = 1\n",
          max_penetration=1e-5 * H)
    write(f"{out}/incline_rotated_30_mu01_lagrange.prm", 30, 0.1,
          "friction", method_lines=lm, max_penetration=1e-5 * H)
    write(f"{out}/incline_rotated_45_mu0_lagrange_factor1000.prm", 45, 0.0,
          "contact", method_lines=lm + "    set penalty factor = 1000\n",
          max_penetration=1e-5 * H)
    # Nitsche's method (theta = -1, the default; stabilisation factor 100)
    ni = "    set method = Nitsche\n"
    write(f"{out}/incline_rotated_45_mu0_nitsche.prm", 45, 0.0, "contact",
          method_lines=ni)
    write(f"{out}/incline_rotated_30_mu01_nitsche.prm", 30, 0.1, "friction",
          method_lines=ni)
    write(f"{out}/incline_rotated_30_stick_nitsche.prm", 30, 0.7, "friction",
          method_lines=ni)
    # symmetric Nitsche (theta = 1): stable in the cut cells with the ghost
    # penalty, from stabilisation factor 10 on (doc/verification.md)
    sym = ni + "    set Nitsche symmetry = 1\n    set penalty factor = 10\n"
    ghost = "  set ghost penalty factor = 1\n"
    write(f"{out}/incline_rotated_45_mu0_nitsche_symmetric.prm", 45, 0.0,
          "contact", method_lines=sym, solver_lines=ghost)
    write(f"{out}/incline_rotated_30_stick_nitsche_symmetric.prm", 30, 0.7,
          "friction", method_lines=sym, solver_lines=ghost)
