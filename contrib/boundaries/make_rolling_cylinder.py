#!/usr/bin/env python3
"""Write tests/boundaries/cylinder_60_<case>.prm (VERIFICATION.md 2.4): a
cylinder (disk, R = 0.25 m, neo-Hookean E = 200 MPa, nu = 0.3,
7800 kg/m^3, as in Kratos' validation example) on a 60 degree incline that
is a 'line' boundary rotated by 20 degrees against the grid (gravity rotated
with it). Frictionless contact: it slides, a = g sin 60; Coulomb friction
mu = 0.7 >= tan(60)/3: it rolls without slip, a = (2/3) g sin 60. Checked:
the displacement of the center of mass, within 2 % of s(t) = a t^2 / 2.

    usage: make_rolling_cylinder.py <output dir> [--with-rolling]
           [--material-point-contact] [--ogrid M] [--ppc N] [--cell H]
           [--penalty-factor F] [--clip] [--name NAME] [--test]

--material-point-contact: 'contact side = material points' (the contact is
checked at the lowest point of every material point's extent against the
line, with a geometric gap) and write cylinder_60_*_points.prm;
--ogrid M: the disk's points from an O-grid Gmsh mesh of the disk (an
M x M square and 4 M arcs; written next to the input as <name>.msh, rings
of points at constant radius) instead of the background cells' points
inside a 64-gon; with --material-point-contact the disk is placed so that
the lowest extent of its points touches the line; --ppc N: points per
cell and direction (default 2); --cell H: the background cell size [m]
(default 0.05); --penalty-factor F: the boundary's penalty factor; --clip:
'clip points to the body' for the lattice disk; --test:
write ctest inputs (.prm.in, the mesh under @SOURCE_DIR@). With
--material-point-contact the check is 2 % of s(t) at 0.2 s and 0.4 s
('relative displacement error tolerance').
"""
import math
import os
import sys

G, THETA, RHO, R, H = 9.81, math.radians(60.), math.radians(20.), 0.25, 0.05


def ogrid_disk(P, c, radius, m, k, a):
    """Quadrilaterals of an O-grid mesh of the disk (centre c, local incline
    coordinates mapped by P): an m x m square of half width a and four
    blocks of k layers from its sides to the circle (4 m arcs)."""
    nodes, index, quads = [], {}, []

    def node(x, y):
        key = (round(x, 12), round(y, 12))
        if key not in index:
            index[key] = len(nodes)
            nodes.append((x, y))
        return index[key]

    def quad(ids):
        (x0, y0), (x1, y1), (x2, y2), (x3, y3) = (nodes[i] for i in ids)
        area = (x0 * y1 - x1 * y0) + (x1 * y2 - x2 * y1) + (x2 * y3 - x3 * y2) + (x3 * y0 - x0 * y3)
        quads.append(ids if area > 0 else ids[::-1])

    sq = lambda i, j: node(c[0] - a + 2 * a * i / m, c[1] - a + 2 * a * j / m)
    for i in range(m):
        for j in range(m):
            quad([sq(i, j), sq(i + 1, j), sq(i + 1, j + 1), sq(i, j + 1)])
    # the square's perimeter, counterclockwise from (-a, -a), 4 m segments
    perimeter = []
    for i in range(m):
        perimeter.append((-a + 2 * a * i / m, -a))
    for i in range(m):
        perimeter.append((a, -a + 2 * a * i / m))
    for i in range(m):
        perimeter.append((a - 2 * a * i / m, a))
    for i in range(m):
        perimeter.append((-a, a - 2 * a * i / m))

    def layer(i, j):
        i %= 4 * m
        sx, sy = perimeter[i]
        th = -0.75 * math.pi + 0.5 * math.pi * i / m
        t = j / k
        return node(c[0] + (1 - t) * sx + t * radius * math.cos(th),
                    c[1] + (1 - t) * sy + t * radius * math.sin(th))

    for i in range(4 * m):
        for j in range(k):
            quad([layer(i, j), layer(i + 1, j), layer(i + 1, j + 1), layer(i, j + 1)])
    return [P(x, y) for x, y in nodes], quads


def write_msh(path, nodes, quads):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for i, (x, y) in enumerate(nodes):
            f.write("%d %.12g %.12g 0\n" % (i + 1, x, y))
        f.write("$EndNodes\n$Elements\n%d\n" % len(quads))
        for e, q in enumerate(quads):
            f.write("%d 3 2 1 1 %s\n" % (e + 1, " ".join(str(i + 1) for i in q)))
        f.write("$EndElements\n")


def lowest_extent(nodes, quads, n, ppc):
    """min over the material points of a Gmsh body (as MaterialPoints makes
    them: midpoints of ppc x ppc sub-cells of each bilinear quad, volume
    JxW) of n . x_p - sqrt(V0)/2, the lowest point of their extents."""
    low = float("inf")
    for q in quads:
        X = [nodes[i] for i in q]
        for a in range(ppc):
            for b in range(ppc):
                u, v = (a + 0.5) / ppc, (b + 0.5) / ppc
                w = ((1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v)
                du = (-(1 - v), 1 - v, v, -v)
                dv = (-(1 - u), -u, u, 1 - u)
                x = [sum(w[k] * X[k][d] for k in range(4)) for d in range(2)]
                J = [[sum(du[k] * X[k][d] for k in range(4)) for d in range(2)],
                     [sum(dv[k] * X[k][d] for k in range(4)) for d in range(2)]]
                V0 = abs(J[0][0] * J[1][1] - J[0][1] * J[1][0]) / ppc ** 2
                low = min(low, n[0] * x[0] + n[1] * x[1] - 0.5 * math.sqrt(V0))
    return low


def write(path, mu, condition, factor, end_time=0.4, points_contact=False,
          ogrid=0, cell=H, ppc=2, penalty_factor=None, template=False,
          clip=False):
    t = (math.cos(RHO), math.sin(RHO))
    n = (-math.sin(RHO), math.cos(RHO))
    o = (0.2 + 0.1 * math.sin(RHO), 0.137)
    P = lambda s, h: (o[0] + s * t[0] + h * n[0], o[1] + s * t[1] + h * n[1])
    fmt = lambda p: "%.10g, %.10g" % p
    line = [P(-0.1, 0.), P(2.2, 0.)]
    c = (0.4, R + 1e-3)
    disk = [P(c[0] + R * math.cos(2 * math.pi * k / 64), c[1] + R * math.sin(2 * math.pi * k / 64))
            for k in range(64)]
    pts = line + disk
    upper = (math.ceil((max(p[0] for p in pts) + 0.2) / H) * H,
             math.ceil((max(p[1] for p in pts) + 0.3) / H) * H)
    name = os.path.basename(path)[:-len('.prm')]
    # a ctest input (.prm.in): the mesh is found in the source directory
    mesh_dir = "@SOURCE_DIR@/" if template else ""
    if ogrid:
        # outer layer about as thick as its arcs are long (square points)
        layers = max(1, round(3 * ogrid / 8))
        nodes, quads = ogrid_disk(P, c, R, ogrid, layers, 0.1)
        if points_contact:
            # touching: the lowest extent of the points on the line (the
            # contact is then closed from the start, as in the reference)
            shift = lowest_extent(nodes, quads, n, ppc) - (n[0] * o[0] + n[1] * o[1]) - 1e-8
            nodes = [(x - shift * n[0], y - shift * n[1]) for x, y in nodes]
        write_msh(os.path.join(os.path.dirname(path), name + ".msh"), nodes, quads)
        body = f"""  set geometry = gmsh
  set mesh file = {mesh_dir}{name}.msh"""
    else:
        body = f"""  set geometry = polygon
  set vertices = {'; '.join(fmt(p) for p in disk)}"""
        if clip:
            body += "\n  set clip points to the body = true"
    g = (G * (math.sin(THETA) * t[0] - math.cos(THETA) * n[0]),
         G * (math.sin(THETA) * t[1] - math.cos(THETA) * n[1]))
    a = factor * G * math.sin(THETA)
    # a lattice body rolls on the torque of its contact points: their
    # increment interpolated at x_c (doc/verification.md)
    side = ("\n    set contact side = material points"
            "\n    set contact point motion = interpolated"
            if points_contact else "")
    if penalty_factor is not None:
        side += f"\n    set penalty factor = {penalty_factor}"
    # 2 % of s(t) at every report time (material-point contact), or 2 % of
    # s at the first report time (the boundary-particle inputs)
    tolerance = ("set relative displacement error tolerance = 0.02" if points_contact else
                 f"set displacement error tolerance = {0.02 * 0.5 * a * (end_time / 2) ** 2:.6g}")
    s_end = 0.5 * a * end_time ** 2
    with open(path, "w") as f:
        f.write(f"""# Cylinder on a 60 degree incline (VERIFICATION.md 2.4), the incline a
# 'line' boundary rotated by 20 degrees against the grid, {condition}
# (mu = {mu}). Written by contrib/boundaries/make_rolling_cylinder.py.
# Reference: a = {"(2/3) " if factor < 1 else ""}g sin 60 = {a:.6g} m/s^2 along
# t = ({t[0]:.6g}, {t[1]:.6g}); s({end_time} s) = {s_end:.6g} m; checked: the
# center of mass within 2 % of s at {end_time / 2:g} s and {end_time:g} s.
set dimension = 2
subsection Background grid
  set lower corner = 0, 0
  set upper corner = {fmt(upper)}
  set subdivisions = {round(upper[0] / cell)}, {round(upper[1] / cell)}
end
subsection Body
{body}
  set points per cell per direction = {ppc}
end
subsection Material
  set model = neo-Hookean
  set density = 7800
  set Young's modulus = 2e8
  set Poisson's ratio = 0.3
end
subsection Boundary particles
  subsection Boundary 1
    set geometry = line
    set name = incline
    set vertices = {'; '.join(fmt(p) for p in line)}
    set condition = {condition}
    set friction coefficient = {mu}{side}
  end
end
subsection Solver
  set gravity = {fmt(g)}
  set linear solver = direct
end
subsection Time
  set end time = {end_time}
  set time step = 0.005
  set Newmark gamma = 0.6
  set Newmark beta = 0.3025
end
subsection Output
  set output directory = output-{name}
  set format = none
  set test mode = true
end
subsection Verification
  set compare with exact solution = true
  set compare center of mass = true
  set report times = {end_time / 2:g}
  subsection Exact displacement
    set Function expression = {0.5 * a * t[0]:.10g}*t*t; {0.5 * a * t[1]:.10g}*t*t
  end
  {tolerance}
end
""")


if __name__ == "__main__":
    args = sys.argv[1:]
    out = args[0] if args and not args[0].startswith("--") else "."
    points = "--material-point-contact" in args
    ogrid = int(args[args.index("--ogrid") + 1]) if "--ogrid" in args else 0
    ppc = int(args[args.index("--ppc") + 1]) if "--ppc" in args else 2
    cell = float(args[args.index("--cell") + 1]) if "--cell" in args else H
    suffix = ("_points" if points else "") + ("_ogrid" if ogrid else "")
    if "--name" in args:
        suffix = "_" + args[args.index("--name") + 1]
    template = "--test" in args
    factor = float(args[args.index("--penalty-factor") + 1]) if "--penalty-factor" in args else None
    opts = dict(points_contact=points, ogrid=ogrid, cell=cell, ppc=ppc,
                penalty_factor=factor, template=template, clip="--clip" in args)
    ext = ".prm.in" if template else ".prm"
    write(f"{out}/cylinder_60_frictionless{suffix}.prm", 0.0, "contact", 1.0, **opts)
    if template:
        os.replace(f"{out}/cylinder_60_frictionless{suffix}.prm", f"{out}/cylinder_60_frictionless{suffix}{ext}")
    # rolling with contact side = boundary particles does not pass
    # (doc/verification.md): written only on request
    if "--with-rolling" in args or points:
        write(f"{out}/cylinder_60_rolling{suffix}.prm", 0.7, "friction", 2. / 3., **opts)
        if template:
            os.replace(f"{out}/cylinder_60_rolling{suffix}.prm", f"{out}/cylinder_60_rolling{suffix}{ext}")
