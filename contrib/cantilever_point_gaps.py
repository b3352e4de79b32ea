#!/usr/bin/env python3
"""Gaps between the points' GIMP domains in the large-deformation cantilever.

doc/verification.md, "Cantilever swinging under its own weight": runs the
MPM beam of tests/mpm/cantilever_neo_hookean.prm.in (n x n points per cell,
h = 0.25 m / 2^level) with the given shape functions up to each of the given
times, dumps the points (TALUS_DEBUG_DUMP_POINTS) and measures, for every
pair of neighbouring points (neighbours in the undeformed lattice of
spacing h/n, along X and along Y), their distance and the gap between
their axis-aligned boxes: gap = max_i (|x_b,i - x_a,i| - l_a,i - l_b,i),
positive when the boxes no longer touch, with the half-widths of the
chosen shape functions (uGIMP: l0 = h/(2n); cpGIMP: |F_ii| l0; cpGIMP-box:
sum_j |F_ij| l0; capped at h); for CPDI the gap between the two
parallelograms spanned by r_i = F e_i l0 along the line between the
points: distance - sum over both points and i of |e . r_i|. Prints per time the largest gap (in cells)
and its pair's undeformed position, the stretch of that pair (distance
over the undeformed h/n) against the stretch of their own F along the
pair (|F N| averaged over the two, N the undeformed direction), the number
of pairs with a gap, the largest neighbour distance (in cells) and the
lowest point.

usage: python3 contrib/cantilever_point_gaps.py TALUS SHAPE LEVEL T1,T2,... [DT [N]]
       (SHAPE: linear, uGIMP, cpGIMP, cpGIMP-box or CPDI; DT the time step,
       default that of the test, 0.01 s, or "-"; N points per cell per
       direction, default 2)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
talus, shape, level = os.path.abspath(sys.argv[1]), sys.argv[2], int(sys.argv[3])
times = [float(t) for t in sys.argv[4].split(',')]
dt = sys.argv[5] if len(sys.argv) > 5 and sys.argv[5] != '-' else None
n = int(sys.argv[6]) if len(sys.argv) > 6 else 2
h = 0.25 / 2 ** level
l0 = h / (2. * n)
template = open(os.path.join(here, 'tests/mpm/cantilever_neo_hookean.prm.in')).read()
choice = 'set shape functions = ' + shape
if shape == 'cpGIMP-box':
    choice = ('set shape functions = cpGIMP\n'
              '  set cpGIMP domain stretch = bounding box')
work = tempfile.mkdtemp()
print('| shape | h [m] | t [s] | largest gap [cells] | at X [m] (pair) | pair stretch | F stretch of the pair | pairs with a gap | largest neighbour distance [cells] | lowest point y [m] |')
print('|---|---|---|---|---|---|---|---|---|---|')
for t in times:
    prm = template
    prm = prm.replace('set subdivisions = 20, 26',
                      'set subdivisions = %d, %d' % (20 * 2 ** level, 26 * 2 ** level))
    prm = prm.replace('set shape functions = linear', choice)
    prm = prm.replace('set end time = 2', 'set end time = %g' % t)
    prm = prm.replace('set points per cell per direction = 2',
                      'set points per cell per direction = %d' % n)
    if dt is not None:
        prm = prm.replace('set time step = 0.01', 'set time step = ' + dt)
    prm = re.sub(r'set output directory = .*', 'set output directory = out', prm)
    prm = prm.replace('set test mode = true', 'set test mode = false')
    prm = re.sub(r'\n\s*set (peak )?tolerance = .*', '', prm)
    prm = re.sub(r'\n\s*set reference file = .*', '', prm)
    name = os.path.join(work, 'run.prm')
    open(name, 'w').write(prm)
    dump = os.path.join(work, 'points.txt')
    env = dict(os.environ, TALUS_DEBUG_DUMP_POINTS=dump)
    subprocess.run([talus, name], cwd=work, env=env, check=True,
                   stdout=subprocess.DEVNULL)
    points = {}
    for line in open(dump):
        v = [float(x) for x in line.split()]
        x, props = v[1:3], v[3:]
        F = props[6:10]  # row by row
        X = (round(props[16] / (h / n) - 0.5), round(props[17] / (h / n) - 0.5))
        if shape == 'cpGIMP':
            l = [abs(F[0]) * l0, abs(F[3]) * l0]
        elif shape == 'cpGIMP-box':
            l = [(abs(F[0]) + abs(F[1])) * l0, (abs(F[2]) + abs(F[3])) * l0]
        else:
            l = [l0, l0]
        points[X] = (x, [min(a, h) for a in l], (props[16], props[17]), F)
    worst, where, n_gaps, far = -1e300, None, 0, 0.
    for (i, j), (xa, la, Xa, Fa) in points.items():
        for nb in ((i + 1, j), (i, j + 1)):
            if nb not in points:
                continue
            xb, lb, Xb, Fb = points[nb]
            d = [abs(xb[k] - xa[k]) for k in range(2)]
            if shape == 'CPDI':
                # parallelograms spanned by r_i = F r_i^0: their gap along
                # the line between the points (separating axis e), the
                # distance minus the half-extents sum_i |e . r_i|
                v = [xb[k] - xa[k] for k in range(2)]
                dist = (v[0] ** 2 + v[1] ** 2) ** 0.5
                e = [v[0] / dist, v[1] / dist]
                ext = lambda F: l0 * (abs(e[0] * F[0] + e[1] * F[2]) +
                                      abs(e[0] * F[1] + e[1] * F[3]))
                gap = dist - ext(Fa) - ext(Fb)
            else:
                gap = max(d[k] - la[k] - lb[k] for k in range(2))
            far = max(far, (d[0] ** 2 + d[1] ** 2) ** 0.5 / h)
            if gap > 0.:
                n_gaps += 1
            if gap > worst:
                c = 0 if nb[0] != i else 1  # the undeformed direction
                fs = sum(((F[c]) ** 2 + (F[2 + c]) ** 2) ** 0.5
                         for F in (Fa, Fb)) / 2
                ps = (d[0] ** 2 + d[1] ** 2) ** 0.5 / (h / n)
                worst, where, stretch = gap, (Xa, Xb), (ps, fs)
    lowest = min(p[0][1] for p in points.values())
    print('| %s | %g | %g | %.3f | (%.3f, %.3f)-(%.3f, %.3f) | %.2f | %.2f | %d | %.2f | %.2f |' % (
        shape, h, t, worst / h, where[0][0], where[0][1], where[1][0],
        where[1][1], stretch[0], stretch[1], n_gaps, far, lowest))
shutil.rmtree(work)
