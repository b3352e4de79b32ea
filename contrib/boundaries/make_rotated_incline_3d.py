#!/usr/bin/env python3
"""Write tests/boundaries/incline_plane_3d_<rho>_<case>.prm and its body mesh:
the 3D version of the rotated incline (VERIFICATION.md 2.3). A block
(0.4 x 0.2 x 0.2 m, neo-Hookean, 2000 kg/m^3) on a 30 degree incline with
Coulomb friction; the incline is a 'plane' boundary rotated by rho about the
y axis against the grid, gravity rotated with it. The block is a structured
hexahedral Gmsh mesh (format 2.2) of the rotated block.
Reference: s(t) = g (sin 30 - mu cos 30) t^2 / 2 along t = (cos rho, 0, sin rho).

    usage: make_rotated_incline_3d.py <output dir>
"""
import math
import sys

G, THETA, H = 9.81, math.radians(30.), 0.1


def write_block_mesh(path, P, s_range, w_range, h_range):
    """A structured hexahedral Gmsh mesh (format 2.2) of the block
    {P(s, w, h): s, w, h in the ranges (first, last, number of cells)}."""
    (s0, s1, ns), (w0, w1, nw), (h0, h1, nh) = s_range, w_range, h_range
    nodes = {}
    for k in range(nh + 1):
        for j in range(nw + 1):
            for i in range(ns + 1):
                nodes[(i, j, k)] = len(nodes) + 1
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for (i, j, k), idx in nodes.items():
            p = P(s0 + (s1 - s0) * i / ns, w0 + (w1 - w0) * j / nw,
                  h0 + (h1 - h0) * k / nh)
            f.write("%d %.12g %.12g %.12g\n" % (idx, *p))
        f.write("$EndNodes\n$Elements\n%d\n" % (ns * nw * nh))
        e = 0
        for k in range(nh):
            for j in range(nw):
                for i in range(ns):
                    e += 1
                    v = [nodes[(i, j, k)], nodes[(i + 1, j, k)], nodes[(i + 1, j + 1, k)],
                         nodes[(i, j + 1, k)], nodes[(i, j, k + 1)], nodes[(i + 1, j, k + 1)],
                         nodes[(i + 1, j + 1, k + 1)], nodes[(i, j + 1, k + 1)]]
                    f.write("%d 5 2 1 1 %s\n" % (e, " ".join(map(str, v))))
        f.write("$EndElements\n")


def plane_triangles(P, s_nodes, w_nodes):
    """The parallelogram {P(s, w, 0)} cut at the coordinates s_nodes and
    w_nodes into quadrilaterals, each split into two triangles along
    alternating diagonals; vertices of each triangle ordered right-handed
    about the plane's normal t x e2."""
    ns, nw = len(s_nodes) - 1, len(w_nodes) - 1
    point = lambda i, j: P(s_nodes[i], w_nodes[j], 0.)
    tris = []
    for j in range(nw):
        for i in range(ns):
            A, B, C, D = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
            tris += [(A, B, C), (A, C, D)] if (i + j) % 2 == 0 else \
                    [(A, B, D), (B, C, D)]
    nodes = {}
    for t in tris:
        for v in t:
            nodes.setdefault(v, len(nodes) + 1)
    return [(nodes[v], point(*v)) for v in nodes], \
           [tuple(nodes[v] for v in t) for t in tris]


def write_surface(path, nodes, tris, normal):
    """Triangles as a Gmsh 2.2 mesh (.msh) or an ASCII STL (.stl)."""
    coords = dict(nodes)
    with open(path, "w") as f:
        if path.endswith(".stl"):
            f.write("solid incline\n")
            for t in tris:
                f.write("  facet normal %.12g %.12g %.12g\n    outer loop\n" % normal)
                for v in t:
                    f.write("      vertex %.12g %.12g %.12g\n" % coords[v])
                f.write("    endloop\n  endfacet\n")
            f.write("endsolid incline\n")
            return
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for idx, p in nodes:
            f.write("%d %.12g %.12g %.12g\n" % (idx, *p))
        f.write("$EndNodes\n$Elements\n%d\n" % len(tris))
        for e, t in enumerate(tris):
            f.write("%d 2 2 1 1 %d %d %d\n" % (e + 1, *t))
        f.write("$EndElements\n")


def write(out, name, rho_deg, mu, condition, end_time=0.5, suffix="",
          surface=None, s_nodes=None):
    """surface: None (a 'plane' boundary) or 'msh' / 'stl': the same plane
    as a triangulated surface mesh ('mesh' boundary, <name><suffix>.msh or
    .stl, cut at s_nodes along the incline, 3 x 2 equal cells by default);
    the run then ends at end_time and reports there."""
    r = math.radians(rho_deg)
    t = (math.cos(r), 0., math.sin(r))
    e2 = (0., 1., 0.)
    n = (-math.sin(r), 0., math.cos(r))   # (t x e2)
    o = (0.15 + 0.2 * math.sin(r), 0.013, 0.117)
    P = lambda s, w, h: tuple(o[i] + s * t[i] + w * e2[i] + h * n[i] for i in range(3))
    # body mesh: s in [0.1, 0.5], w in [0.2, 0.4], h in [0, 0.2], 8 x 4 x 4 hexes
    write_block_mesh(f"{out}/{name}.msh", P, (0.1, 0.5, 8), (0.2, 0.4, 4),
                     (0., 0.2, 4))
    plane = [P(-0.1, -0.003, 0), P(1.6, -0.003, 0), P(-0.1, 0.58, 0)]
    if surface is None:
        boundary = f"""    set geometry = plane
    set name = incline
    set vertices = {'; '.join(", ".join("%.10g" % x for x in p) for p in plane)}"""
    else:
        nodes, tris = plane_triangles(
            P, s_nodes or [-0.1 + 1.7 * i / 3 for i in range(4)],
            [-0.003 + 0.583 * j / 2 for j in range(3)])
        surface_file = f"{name}{suffix}.{surface}"
        write_surface(f"{out}/{surface_file}", nodes, tris, n)
        boundary = f"""    set geometry = mesh
    set name = incline
    set mesh file = @SOURCE_DIR@/{surface_file}"""
    report = 0.25 if surface is None else end_time
    g = tuple(G * (math.sin(THETA) * t[i] - math.cos(THETA) * n[i]) for i in range(3))
    sliding = math.tan(THETA) > mu
    a = G * (math.sin(THETA) - mu * math.cos(THETA)) if sliding else 0.
    upper = (math.ceil((o[0] + 1.6 * t[0] + 0.1) / H) * H, 0.6,
             math.ceil((o[2] + 1.0 * t[2] + 0.5) / H) * H)
    fmt = lambda p: ", ".join("%.10g" % x for x in p)
    s_end = 0.5 * a * end_time ** 2
    with open(f"{out}/{name}{suffix}.prm.in", "w") as f:
        f.write(f"""# 3D block on a 30 degree incline rotated by {rho_deg} degrees about y
# against the grid, mu = {mu} ({condition}); the incline is a {"'plane'" if surface is None else "'mesh'"} boundary
# imposed by boundary particles{"" if surface is None else " (the plane as " + str(4 * (len(s_nodes) - 1) if s_nodes else 12) + (" graded" if s_nodes else "") + " triangles, " + ("Gmsh .msh" if surface == "msh" else "ASCII STL") + ")"}, the block a Gmsh mesh ({name}.msh).
# Written by contrib/boundaries/make_rotated_incline_3d.py.
# Reference: a = g (sin 30 - mu cos 30) = {a:.6g} m/s^2 along
# t = ({t[0]:.6g}, 0, {t[2]:.6g}); s({end_time} s) = {s_end:.6g} m.
set dimension = 3
subsection Background grid
  set lower corner = 0, 0, 0
  set upper corner = {fmt(upper)}
  set subdivisions = {round(upper[0] / H)}, {round(upper[1] / H)}, {round(upper[2] / H)}
end
subsection Body
  set geometry = gmsh
  set mesh file = @SOURCE_DIR@/{name}.msh
  set points per cell per direction = 1
end
subsection Material
  set model = neo-Hookean
  set density = 2000
  set Young's modulus = 1e7
  set Poisson's ratio = 0.3
end
subsection Boundary particles
  subsection Boundary 1
{boundary}
    set condition = {condition}
    set friction coefficient = {mu}
  end
end
subsection Solver
  set gravity = {fmt(g)}
  set linear solver = direct
end
subsection Time
  set end time = {end_time}
  set time step = 0.01
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
  set report times = {report}
  subsection Exact displacement
    set Function expression = {0.5 * a * t[0]:.10g}*t*t; 0; {0.5 * a * t[2]:.10g}*t*t
  end
  # 1 % of s({report} s), or 1 % of h at rest
  set displacement error tolerance = {0.01 * 0.5 * a * report ** 2 if sliding else 0.01 * H:.6g}
  set maximum penetration = {1e-3 * H:.6g}
{"  set maximum final speed = 1e-4" + chr(10) if not sliding else ""}{"  # at rest: the summed reaction is the weight m g, m = 2000 kg/m^3 x 0.4 x 0.2 x 0.2 m^3" + chr(10) + "  set expected reaction = %.10g" % (2000 * 0.4 * 0.2 * 0.2 * G) + chr(10) if not sliding and surface else ""}end
""")


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    # ~3 min each (direct solver on the whole 3D grid): '_slow' tests, run
    # by name.
    write(out, "incline_plane_3d_20_mu01", 20, 0.1, "friction", suffix="_slow")
    write(out, "incline_plane_3d_20_stick", 20, 0.7, "friction", suffix="_slow")
    # The incline as a triangulated surface, Gmsh and STL, to 0.2 s.
    write(out, "incline_plane_3d_20_mu01", 20, 0.1, "friction", 0.2,
          "_triangles", "msh")
    write(out, "incline_plane_3d_20_mu01", 20, 0.1, "friction", 0.2,
          "_stl", "stl")
    # stuck on the triangulated incline for 1 s: reaction = weight
    write(out, "incline_plane_3d_20_stick", 20, 0.7, "friction", 1.0,
          "_triangles", "msh")
    # graded: triangles from 0.05 to 0.8 m along the incline, refined cell
    # by cell to the grid's 0.1 m
    write(out, "incline_plane_3d_20_mu01", 20, 0.1, "friction", 0.2,
          "_graded", "msh", [-0.1, 0.0, 0.05, 0.1, 0.2, 0.4, 0.8, 1.6])
