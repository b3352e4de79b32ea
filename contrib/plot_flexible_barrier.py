#!/usr/bin/python3
"""Pictures of a 3D coupled barrier run (prm/flexible_barrier.prm).

Reads the output directory of the run: particles_*.pvtu (material points),
net_*.vtu and the barrier's line meshes (posts, retaining_ropes, brakes,
top_cable, bottom_cable, edge_cable_left/right, lateral_ropes: reference
points plus "displacement"), coupling.csv and structure.csv.
Writes
  snapshots.png  side view (y-z) and plan view (x-y) of the flow and the
                 deformed barrier at three instants (before, at and after
                 the peak impact force), points coloured by speed;
  forces.png     the impact force on the net (total and per field), the
                 cable, post and anchor forces, the post rotations, the
                 net's deflection and residual height, the brake strokes,
                 and the energies of the coupled system over time.
Prints the peak and final impact force and the largest member forces.
Needs numpy and matplotlib (Debian: python3-matplotlib).

Usage: plot_flexible_barrier.py OUTPUT_DIRECTORY
"""
import argparse
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_particles import read_particles, read_vtu  # noqa: E402
from plot_flexible_barrier_2d import numbered, plot_energies, read_csv  # noqa: E402,E501

LINES = (("posts", "k-", 2.0), ("retaining_ropes", "b-", 1.0),
         ("brakes", "m-", 2.5), ("top_cable", "g-", 1.2),
         ("bottom_cable", "g-", 1.2), ("edge_cable_left", "g-", 1.2),
         ("edge_cable_right", "g-", 1.2), ("lateral_ropes", "c-", 1.0))


def deformed(path):
    x, f = read_vtu(path)
    return x + f.get("displacement", np.zeros_like(x))


def draw_barrier(ax, d, step, axes_xy):
    """The barrier's meshes at output step `step`, projected on axes_xy."""
    i, j = axes_xy
    for member, style, lw in LINES:
        files = numbered(d, member, "vtu")
        if step in files:
            x = deformed(files[step])
            for k in range(0, len(x) - 1, 2):  # one segment per cell
                ax.plot(x[k:k + 2, i], x[k:k + 2, j], style, lw=lw)
    files = numbered(d, "net", "vtu")
    if step in files:
        x = deformed(files[step])
        for k in range(0, len(x) - 3, 4):  # quads, lexicographic vertices
            q = x[[k, k + 1, k + 3, k + 2, k]]
            ax.plot(q[:, i], q[:, j], "r-", lw=0.3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory")
    args = parser.parse_args()
    d = args.directory
    coupling = read_csv(os.path.join(d, "coupling.csv"))
    s = read_csv(os.path.join(d, "structure.csv"))
    t = coupling["time"]
    force = np.sqrt(sum(coupling["interface_force_" + c] ** 2 for c in "xyz"))
    peak = int(np.argmax(force))
    print("peak impact force %.4g kN at t = %.3g s; at the end %.4g kN"
          % (force[peak] / 1e3, t[peak], force[-1] / 1e3))
    for name in sorted(s):
        if name.endswith("_force") and not name.startswith("field"):
            k = int(np.argmax(np.abs(s[name])))
            print("  %-32s largest |force| %9.4g kN at t = %.3g s"
                  % (name, abs(s[name][k]) / 1e3, s["time"][k]))

    # Snapshots: particle outputs are numbered by output, the barrier's by
    # step; output k was written at the k-th output.
    particles = sorted(numbered(d, "particles", "pvtu").items())
    if not particles:
        sys.exit("error: no particles_*.pvtu in %s (format = vtu?)" % d)
    net_files = sorted(numbered(d, "net", "vtu").items())
    n_out = min(len(particles), len(net_files))
    out_times = [t[min(int(st) - 1, len(t) - 1)] if st > 0 else 0.
                 for st, _ in net_files][:n_out]
    wanted = [max(0., t[peak] - 0.75), t[peak], t[-1]]
    picks = sorted(set(int(np.argmin([abs(x - w) for x in out_times]))
                       for w in wanted))
    fig, axes = plt.subplots(len(picks), 2, figsize=(13, 3.6 * len(picks)),
                             squeeze=False,
                             gridspec_kw={"width_ratios": [1.1, 1]})
    data, vmax = [], 1e-12
    for k in picks:
        pts, fields = read_particles(particles[k][1])
        speed = np.linalg.norm(fields["velocity"], axis=1) \
            if "velocity" in fields else np.zeros(len(pts))
        vmax = max(vmax, speed.max())
        data.append((k, pts, speed))
    for row, (k, pts, speed) in zip(axes, data):
        step = net_files[k][0]
        for ax, (i, j), labels in ((row[0], (1, 2), ("y [m]", "z [m]")),
                                   (row[1], (0, 1), ("x [m]", "y [m]"))):
            ax.axhline(0., color="0.5", lw=0.8) if j == 2 else None
            sc = ax.scatter(pts[:, i], pts[:, j], c=speed, s=3,
                            cmap="viridis", vmin=0., vmax=vmax)
            draw_barrier(ax, d, step, (i, j))
            ax.set_aspect("equal")
            ax.set_xlabel(labels[0])
            ax.set_ylabel(labels[1])
        row[0].set_xlim(-3, 12)
        row[0].set_ylim(-0.5, 4.5)
        row[0].set_title("side view (slope frame), t = %.2f s"
                         % out_times[k], fontsize=10)
        row[1].set_title("plan view, t = %.2f s" % out_times[k], fontsize=10)
    fig.colorbar(sc, ax=axes, label="speed [m/s]", shrink=0.6)
    fig.savefig(os.path.join(d, "snapshots.png"), dpi=100,
                bbox_inches="tight")

    ts = s["time"]
    fields = sorted(k for k in s if k.startswith("field_"))
    fig, ax = plt.subplots(4, 1, figsize=(9, 12), sharex=True)
    ax[0].plot(t, force / 1e3, "k-", lw=2, label="impact force on the net")
    for name in fields:
        ax[0].plot(ts, s[name] / 1e3, label=name.replace("_", " "))
    ax[0].set_ylabel("force [kN]")
    ax[0].legend(fontsize=8)
    for name, style in (("top_cable_force", "g-"),
                        ("bottom_cable_force", "g--"),
                        ("edge_cable_left_force", "g:"),
                        ("retaining_ropes_force", "b-"),
                        ("lateral_ropes_force", "c-"),
                        ("posts_force", "k-")):
        if name in s:
            ax[1].plot(ts, s[name] / 1e3, style,
                       label=name.replace("_force", "").replace("_", " ")
                       + (" (largest |N|, signed)" if name == "posts_force"
                          else ""))
    ax[1].set_ylabel("axial force [kN]")
    ax[1].legend(fontsize=8, ncol=2)
    for name in (k for k in s if k.endswith("_rotation")):
        ax[2].plot(ts, s[name], label=name.replace("_", " ") + " [deg]")
    if "net_deflection" in s:
        ax[2].plot(ts, s["net_deflection"], "r-", lw=2,
                   label="net deflection [m]")
        ax[2].plot(ts, s["net_residual_height"], "r--",
                   label="net residual height [m]")
    for name in (k for k in s if k.endswith("_stroke") and k != "brakes_stroke"):
        ax[2].plot(ts, s[name], "m:", lw=0.8)
    ax[2].set_ylabel("[m] or [deg]")
    ax[2].legend(fontsize=8, ncol=2)
    plot_energies(ax[3], coupling, "kJ")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "forces.png"), dpi=100)
    print("wrote %s and %s" % (os.path.join(d, "snapshots.png"),
                               os.path.join(d, "forces.png")))


if __name__ == "__main__":
    main()
