#!/usr/bin/env python3
"""3D renders and an animation of a coupled barrier run (prm/flexible_barrier.prm).

Reads the run's .pvd collections (particles: material points; net: the
membrane; posts, retaining_ropes, brakes, top/bottom/edge cables, lateral
ropes: line meshes in their reference position plus "displacement") and
renders them off screen with PyVista (VTK), in the world frame: the run
works in the slope's frame (slope = plane z = 0, gravity tilted by the
slope angle read from the prm file's "gravity"), the renders turn it back
so that gravity points down and the slope is inclined.

Colours: material points by speed [m/s]; the net by its largest principal
membrane force [kN/m] on the deformed net; cables, ropes and posts by
their axial force [kN] (tension > 0); brakes in magenta.

Writes into the output directory
  render.png      four instants of the run (release, first contact, the
                  largest impact force, the end) in one picture;
  render_<t>.png  the same instants one by one (with --each);
  animation.gif   every output step (with --animation).
Needs PyVista (PyPI: pip install pyvista imageio; off-screen rendering
through VTK's EGL/OSMesa, no display needed).

Usage: render_flexible_barrier.py OUTPUT_DIRECTORY [--prm FILE]
           [--times T1 T2 ...] [--animation] [--each]
"""
import argparse
import csv
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

try:
    import pyvista as pv
except ImportError:
    sys.exit("render_flexible_barrier.py: needs PyVista "
             "(pip install pyvista imageio)")

pv.OFF_SCREEN = True

# camera (position, focal point, up) in the world frame: uphill and to the
# left of the barrier, looking down the slope at it
CAMERA = [(-6., 24., 20.), (7.5, 2., 0.), (0., 0., 1.)]

LINE_MEMBERS = ("posts", "retaining_ropes", "top_cable", "bottom_cable",
                "edge_cable_left", "edge_cable_right", "lateral_ropes")


def collection(d, name):
    """(time, file) of a .pvd collection, in time order; [] if absent."""
    path = os.path.join(d, name + ".pvd")
    if not os.path.isfile(path):
        return []
    root = ET.parse(path).getroot()
    out = [(float(e.get("timestep")), os.path.join(d, e.get("file")))
           for e in root.iter("DataSet")]
    return sorted(out)


def nearest(items, t):
    """The file of `items` whose time is closest to t."""
    return min(items, key=lambda x: abs(x[0] - t))[1] if items else None


def net_thickness(prm):
    """The membrane thickness [m] of the prm file, None if not given."""
    if prm and os.path.isfile(prm):
        for line in open(prm):
            m = re.match(r"\s*set\s+thickness\s*=\s*([^#]+)", line)
            if m:
                return float(m.group(1))
    return None


def slope_angle(prm):
    """The slope angle [rad] from the prm file's gravity (0, -g sin, -g cos)."""
    if prm and os.path.isfile(prm):
        for line in open(prm):
            m = re.match(r"\s*set\s+gravity\s*=\s*([^#]+)", line)
            if m:
                g = [float(v) for v in m.group(1).split(",")]
                if len(g) == 3 and g[2] != 0.:
                    return math.atan2(-g[1], -g[2])
    return 0.


def to_world(mesh, angle):
    """Rotate from the slope frame to the world frame (about x)."""
    mesh.rotate_x(math.degrees(angle), point=(0., 0., 0.), inplace=True)
    return mesh


def deformed(path, angle):
    m = pv.read(path)
    if "displacement" in m.point_data:
        m.points = m.points + m.point_data["displacement"]
    return to_world(m, angle)


def first_contact_and_peak(d):
    """Times of the first non-zero and of the largest impact force."""
    path = os.path.join(d, "coupling.csv")
    if not os.path.isfile(path):
        return None, None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    keys = [k for k in rows[0] if k.startswith("interface_force_")]
    if not keys:
        return None, None
    t = np.array([float(r["time"]) for r in rows])
    force = np.linalg.norm([[float(r[k]) for k in keys] for r in rows],
                           axis=1)
    touched = np.nonzero(force > 1e-3 * max(force.max(), 1e-30))[0]
    return (t[touched[0]] if len(touched) else None,
            t[int(np.argmax(force))])


class Scene:
    def __init__(self, d, angle, thickness):
        self.d = d
        self.angle = angle
        # membrane force per length [kN/m] = stress * thickness; the
        # stress [MPa] when the thickness is unknown
        self.net_scale = (thickness / 1e3) if thickness else 1e-6
        self.net_label = ("net force [kN/m]" if thickness else
                          "net stress [MPa]")
        self.particles = collection(d, "particles")
        self.members = {m: collection(d, m) for m in LINE_MEMBERS}
        self.net = collection(d, "net")
        self.brakes = collection(d, "brakes")
        grid = collection(d, "grid")
        b = pv.read(grid[0][1]).bounds if grid else (0, 15, -3, 14, 0, 5)
        self.slope = to_world(
            pv.Plane(center=((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, 0.),
                     direction=(0, 0, 1), i_size=b[1] - b[0] + 8.,
                     j_size=b[3] - b[2]), angle)
        self.speed_max = 0.
        for _, f in self.particles:
            v = pv.read(f).point_data["velocity"]
            self.speed_max = max(self.speed_max,
                                 float(np.linalg.norm(v, axis=1).max()))
        self.force_max = 1.
        for items in self.members.values():
            for _, f in items:
                m = pv.read(f)
                if "axial_force" in m.point_data:
                    self.force_max = max(
                        self.force_max,
                        float(np.abs(m.point_data["axial_force"]).max()) /
                        1e3)
        self.net_max = 1.
        for _, f in self.net:
            m = pv.read(f)
            if "max_principal_stress" in m.point_data:
                self.net_max = max(
                    self.net_max,
                    float(m.point_data["max_principal_stress"].max()) *
                    self.net_scale)

    def add(self, plotter, t, bars=True):
        p = plotter
        p.add_mesh(self.slope, color="tan", opacity=0.35)
        f = nearest(self.particles, t)
        if f:
            pts = to_world(pv.read(f), self.angle)
            pts["speed [m/s]"] = np.linalg.norm(pts.point_data["velocity"],
                                                axis=1)
            p.add_mesh(pts, scalars="speed [m/s]", cmap="viridis",
                       clim=(0., self.speed_max), point_size=7,
                       render_points_as_spheres=True, show_scalar_bar=bars,
                       scalar_bar_args=dict(vertical=True,
                                            position_x=0.88,
                                            position_y=0.55, height=0.4))
        f = nearest(self.net, t)
        if f:
            net = deformed(f, self.angle)
            net[self.net_label] = (
                net.point_data["max_principal_stress"] * self.net_scale)
            p.add_mesh(net, scalars=self.net_label, cmap="Reds",
                       clim=(0., self.net_max), opacity=0.75,
                       show_edges=True, edge_color="grey",
                       show_scalar_bar=bars,
                       scalar_bar_args=dict(vertical=True, position_x=0.88,
                                            position_y=0.05, height=0.4))
        first = True
        for member, items in self.members.items():
            f = nearest(items, t)
            if not f:
                continue
            m = deformed(f, self.angle)
            m["axial force [kN]"] = m.point_data["axial_force"] / 1e3
            width = 6 if member == "posts" else 3
            p.add_mesh(m, scalars="axial force [kN]", cmap="coolwarm",
                       clim=(-self.force_max, self.force_max),
                       line_width=width, render_lines_as_tubes=True,
                       show_scalar_bar=bars and first,
                       scalar_bar_args=dict(vertical=False, position_x=0.3,
                                            position_y=0.02, width=0.4))
            first = False
        f = nearest(self.brakes, t)
        if f:
            p.add_mesh(deformed(f, self.angle), color="magenta",
                       line_width=8, render_lines_as_tubes=True)
        p.add_text(f"t = {t:.2f} s", position="upper_left", font_size=12)
        p.camera_position = CAMERA


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("output")
    ap.add_argument("--prm", default=None,
                    help="prm file of the run (for the slope angle); "
                    "default prm/<output directory name>.prm")
    ap.add_argument("--times", type=float, nargs="*", default=None)
    ap.add_argument("--animation", action="store_true")
    ap.add_argument("--each", action="store_true")
    ap.add_argument("--camera", type=float, nargs=9, default=None,
                    help="position, focal point and up vector (9 numbers)")
    a = ap.parse_args()
    if a.camera:
        global CAMERA
        CAMERA = [tuple(a.camera[0:3]), tuple(a.camera[3:6]),
                  tuple(a.camera[6:9])]
    d = a.output
    prm = a.prm or os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "prm",
                                os.path.basename(os.path.normpath(d)) +
                                ".prm")
    angle = slope_angle(prm)
    scene = Scene(d, angle, net_thickness(prm))
    if not scene.particles:
        sys.exit(f"render_flexible_barrier.py: no particles.pvd in {d}")
    times = [t for t, _ in scene.particles]
    if a.times:
        shown = a.times
    else:
        contact, peak = first_contact_and_peak(d)
        shown = [times[0], contact if contact is not None else times[1],
                 peak if peak is not None else times[len(times) // 2],
                 times[-1]]
    shown = [min(times, key=lambda s: abs(s - t)) for t in shown]

    rows = (len(shown) + 1) // 2
    p = pv.Plotter(shape=(rows, 2), window_size=(1200, 480 * rows),
                   off_screen=True, border=False)
    for k, t in enumerate(shown):
        p.subplot(k // 2, k % 2)
        scene.add(p, t, bars=(k == 0))
    p.set_background("white")
    out = os.path.join(d, "render.png")
    p.screenshot(out)
    p.close()
    print(f"wrote {out} (t = {', '.join(f'{t:.2f}' for t in shown)} s, "
          f"slope {math.degrees(angle):.1f} deg)")

    if a.each:
        for t in shown:
            p = pv.Plotter(window_size=(1200, 760), off_screen=True)
            p.set_background("white")
            scene.add(p, t)
            out = os.path.join(d, f"render_{t:.2f}.png")
            p.screenshot(out)
            p.close()
            print(f"wrote {out}")

    if a.animation:
        out = os.path.join(d, "animation.gif")
        p = pv.Plotter(window_size=(960, 600), off_screen=True)
        p.open_gif(out, fps=4)
        for t in times:
            p.clear()
            p.set_background("white")
            scene.add(p, t)
            p.write_frame()
        p.close()
        print(f"wrote {out} ({len(times)} frames)")


if __name__ == "__main__":
    main()
