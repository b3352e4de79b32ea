#!/usr/bin/env python3
"""Write benchmarks/granular_3d/block_on_rotated_plane.prm and its body mesh:
the 3D granular block of benchmarks/granular_3d/block_on_slope.prm (issue 3)
on a real 15 degree slope that does not follow the grid (issue 4, "Granular
on terrain").

block_on_slope.prm tilts gravity and puts the basal friction (mu = 0.6) on
the grid's bottom face. Here gravity is vertical and the slope is a 'plane'
boundary of boundary particles inclined by 15 degrees against the grid
(Coulomb friction mu = 0.6, penalty); the block (0.4 x 0.4 x 0.2 m,
Mohr-Coulomb, 256 points at the same places relative to the slope) starts
with 1 m/s down the slope. Both runs should give the same motion along the
slope; contrib/boundaries/compare_granular_block_3d.py compares them.

    usage: make_granular_block_3d.py [output dir]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_rotated_incline_3d import write_block_mesh  # noqa: E402

SLOPE = math.radians(15.)
# slope frame: s down the slope, w across (y), h along the normal
T = (math.cos(SLOPE), 0., -math.sin(SLOPE))
N = (math.sin(SLOPE), 0., math.cos(SLOPE))
ORIGIN = (0.05, 0., 0.65)


def P(s, w, h):
    return tuple(ORIGIN[i] + s * T[i] + (w if i == 1 else 0.) + h * N[i]
                 for i in range(3))


def main():
    top = os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        top, "benchmarks", "granular_3d")
    name = "block_on_rotated_plane"
    # 8 x 8 x 4 hexes of 0.05 m, one point each: the 2 x 2 x 2 points per
    # 0.1 m cell of block_on_slope.prm
    write_block_mesh(os.path.join(out, name + ".msh"), P, (0.1, 0.5, 8),
                     (0.2, 0.6, 8), (0., 0.2, 4))
    fmt = lambda p: ", ".join("%.10g" % x for x in p)
    plane = [P(-0.02, 0.001, 0.), P(1.95, 0.001, 0.), P(-0.02, 0.799, 0.)]
    with open(os.path.join(out, name + ".prm"), "w") as f:
        f.write(f"""# The granular block of block_on_slope.prm on a 15 degree slope that does
# not follow the grid: gravity vertical, the slope a 'plane' of boundary
# particles with Coulomb friction mu = 0.6 (penalty), the y walls slip
# faces of the grid as there. Written by
# contrib/boundaries/make_granular_block_3d.py; compared with
# block_on_slope.prm by contrib/boundaries/compare_granular_block_3d.py
# (doc/verification.md, "3D granular block on a slope"). Run from the
# repository root: build/talus benchmarks/granular_3d/block_on_rotated_plane.prm
# Down the slope: t = ({fmt(T)}); slope normal n = ({fmt(N)}).
set dimension = 3
subsection Background grid
  set lower corner = 0, 0, 0.1
  set upper corner = 2.0, 0.8, 1.0
  set subdivisions = 20, 8, 9
  set slip boundaries = 2, 3
end
subsection Body
  set geometry = gmsh
  set mesh file = benchmarks/granular_3d/{name}.msh
  set points per cell per direction = 1
  subsection Initial velocity
    set Function expression = {fmt(T).replace(", ", "; ")}
  end
end
subsection Material
  set model = Mohr-Coulomb
  set density = 2085
  set Young's modulus = 5e6
  set Poisson's ratio = 0.3
  subsection Mohr-Coulomb
    set friction angle = 30
    set cohesion = 0
    set dilatancy angle = 0
  end
end
subsection Boundary particles
  subsection Boundary 1
    set geometry = plane
    set name = slope
    set vertices = {'; '.join(fmt(p) for p in plane)}
    set condition = friction
    set friction coefficient = 0.6
  end
end
subsection Solver
  set gravity = 0, 0, -9.81
  set volumetric locking treatment = F-bar
  set linear solver = direct
  set line search = true
end
subsection Time
  set end time = 3
  set time step = 0.01
  set adaptive time step = true
end
subsection Output
  set output directory = output/granular_3d_rotated
  set format = vtu
  set output interval = 0.25
end
subsection Verification
  set energy balance tolerance = 0.05
  set maximum final speed = 0.01
  set final speed measure = grid velocity
end
""")


if __name__ == "__main__":
    main()
