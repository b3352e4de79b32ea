#!/usr/bin/python3
"""Pictures of a 2D coupled barrier run (prm/flexible_barrier_2d.prm).

Reads the output directory of the run: particles_*.pvtu (material points),
net_*.vtu, post_*.vtu, rope_*.vtu, brake_*.vtu (the barrier's line meshes:
reference points plus "displacement"), coupling.csv and structure.csv.
Writes
  snapshots.png  the flow and the deformed barrier at three instants
                 (before, at and after the peak impact force), coloured by
                 speed;
  forces.png     the impact force on the net, the forces of post, rope and
                 brake, the brake stroke, the net's largest displacement,
                 and the energies of the coupled system by category over time.
Prints the peak and final impact force. Needs numpy and matplotlib
(Debian: python3-matplotlib).

Usage: plot_flexible_barrier_2d.py OUTPUT_DIRECTORY [--slope x0,y0;x1,y1;...]
"""
import argparse
import csv
import glob
import os
import re
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_particles import read_particles, read_vtu  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("error: %s has no rows" % path)
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def numbered(directory, stem, extension):
    """{number: path} of stem_NNNNN.extension files."""
    files = {}
    for path in glob.glob(os.path.join(directory, stem + "_*." + extension)):
        m = re.search(r"_(\d+)\." + extension + "$", path)
        if m:
            files[int(m.group(1))] = path
    return files


def plot_energies(ax, c, unit):
    """The coupled run's energies by category (coupling.csv) over time."""
    t = c["time"]
    released = c["gravitational_energy"][0] - c["gravitational_energy"]
    # friction split by boundary where coupling.csv has it
    split = [(c[k], "friction on the %s" % k[:-len("_friction_dissipation")])
             for k in c if k.endswith("_friction_dissipation")]
    for values, label in [
            (released, "gravitational energy released"),
            (c["kinetic_energy"], "kinetic (material)"),
            (c["plastic_dissipation"], "plastic dissipation (material)")] + (
            split or [(c["friction_dissipation"], "friction (slope and net)")]
    ) + [
            (c["numerical_dissipation"],
             "numerical (resets, transfer, integrator)"),
            (c["strain_energy"] + c["spring_energy"],
             "strain + contact springs (material)"),
            (c["structure_energy"] - c["structure_energy"][0],
             "barrier: elastic + kinetic change"),
            (c["barrier_dissipation"], "barrier: brakes + damping"),
            (c["energy_change"], "balance error")]:
        ax.plot(t, values / 1e3, "k:" if label == "balance error" else "-",
                label=label)
    ax.set_ylabel("energy [%s]" % unit)
    ax.set_xlabel("t [s]")
    ax.legend(fontsize=8)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory")
    parser.add_argument("--slope", default="-1,6.57735;10.3923,0;15,0",
                        help="ground polyline x,y;x,y;... [m]")
    args = parser.parse_args()
    d = args.directory
    coupling = read_csv(os.path.join(d, "coupling.csv"))
    members = read_csv(os.path.join(d, "structure.csv"))
    t = coupling["time"]
    force = np.hypot(coupling["interface_force_x"],
                     coupling["interface_force_y"])
    peak = int(np.argmax(force))
    print("peak impact force %.4g N/m at t = %.3g s; at the end %.4g N/m"
          % (force[peak], t[peak], force[-1]))

    # Snapshots: particle outputs are numbered by output, the barrier's by
    # step; pick the outputs nearest to three instants.
    particles = sorted(numbered(d, "particles", "pvtu").items())
    if not particles:
        sys.exit("error: no particles_*.pvtu in %s (format = vtu?)" % d)
    n_out = len(particles)
    steps = coupling["step"]
    # output k was written at the k-th output time: map outputs to times by
    # the barrier files' step numbers (same outputs, same order)
    net_files = sorted(numbered(d, "net", "vtu").items())
    out_times = [t[min(int(s) - 1, len(t) - 1)] if s > 0 else 0.
                 for s, _ in net_files][:n_out]
    wanted = [max(0., t[peak] - 0.6), t[peak], t[-1]]
    picks = [int(np.argmin([abs(x - w) for x in out_times])) for w in wanted]
    ground = np.array([[float(v) for v in p.split(",")]
                       for p in args.slope.split(";")])

    fig, axes = plt.subplots(len(picks), 1, figsize=(9, 2.6 * len(picks)),
                             sharex=True)
    vmax = 0.
    data = []
    for k in picks:
        pts, fields = read_particles(particles[k][1])
        speed = np.linalg.norm(fields["velocity"], axis=1) \
            if "velocity" in fields else np.zeros(len(pts))
        vmax = max(vmax, speed.max())
        data.append((k, pts, speed))
    for ax, (k, pts, speed) in zip(axes, data):
        ax.plot(ground[:, 0], ground[:, 1], "k-", lw=1.5)
        sc = ax.scatter(pts[:, 0], pts[:, 1], c=speed, s=6, cmap="viridis",
                        vmin=0., vmax=max(vmax, 1e-12))
        step = net_files[k][0] if k < len(net_files) else None
        for member, style in (("net", "r-"), ("post", "k-"),
                              ("rope", "b-"), ("brake", "m-")):
            files = numbered(d, member, "vtu")
            if step in files:
                x, f = read_vtu(files[step])
                u = f.get("displacement", np.zeros_like(x))
                xy = x[:, :2] + u[:, :2]
                for i in range(0, len(xy) - 1, 2):  # one segment per cell
                    ax.plot(xy[i:i + 2, 0], xy[i:i + 2, 1], style, lw=2)
        ax.set_aspect("equal")
        ax.set_ylim(-0.6, 7)
        ax.set_title("t = %.2f s" % out_times[k], fontsize=10)
        ax.set_ylabel("y [m]")
    axes[-1].set_xlabel("x [m]")
    fig.colorbar(sc, ax=axes, label="speed [m/s]", shrink=0.8)
    fig.savefig(os.path.join(d, "snapshots.png"), dpi=110,
                bbox_inches="tight")

    fig, ax = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    ax[0].plot(t, force / 1e3, "r-", label="impact force on the net")
    tm = members["time"]
    for name, style in (("post_force", "k-"), ("rope_force", "b-"),
                        ("net_force", "r--")):
        if name in members:
            sign = -1. if name == "post_force" else 1.
            label = name.replace("_force", "") + (" (compression)"
                                                  if sign < 0 else "")
            ax[0].plot(tm, sign * members[name] / 1e3, style, label=label)
    ax[0].set_ylabel("force [kN/m]")
    ax[0].legend(fontsize=8)
    ax[1].plot(tm, members["largest_displacement"], "r-",
               label="barrier: largest displacement")
    if "brake_stroke" in members:
        ax[1].plot(tm, members["brake_stroke"], "m-", label="brake stroke")
    ax[1].set_ylabel("[m]")
    ax[1].legend(fontsize=8)
    plot_energies(ax[2], coupling, "kJ/m")
    fig.tight_layout()
    fig.savefig(os.path.join(d, "forces.png"), dpi=110)
    print("wrote %s and %s" % (os.path.join(d, "snapshots.png"),
                               os.path.join(d, "forces.png")))


if __name__ == "__main__":
    main()
