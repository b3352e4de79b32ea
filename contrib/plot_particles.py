#!/usr/bin/python3
"""Plot Talus material points (deal.II particle output) to a PNG picture.

Reads a `.pvtu` file (and the `.vtu` pieces it lists) or a single `.vtu`
file as written by deal.II's DataOut / Particles output, i.e. VTK XML
UnstructuredGrid with DataArrays in "binary" (base64, optionally
zlib-compressed with a UInt32/UInt64 block header) or "ascii" format.
Only the standard library, numpy and matplotlib are needed.

Usage:
  plot_particles.py INPUT.pvtu -o out.png [--color FIELD[:COMPONENT]]
                    [--view xy|xz|yz|3d] [--title TEXT] [--point-size S]
                    [--also INPUT2 ...]
  plot_particles.py INPUT.pvtu --list

  --color   field used for the colour; COMPONENT is an index (0, 1, ...),
            x/y/z or "norm". Vector fields default to their norm. Special
            names: "height" (y in 2D, z in 3D), "x", "y", "z".
            Default: speed (norm of "velocity") if present, else height.
  --view    projection plane or "3d" (mplot3d scatter). Default: xy for 2D
            data (all z == 0), xz for 3D data.
  --also    further files (e.g. the initial state) drawn in light grey.
  --list    print point count, coordinate ranges and the available fields.

Example:
  plot_particles.py out/particles_00002.pvtu --also out/particles_00000.pvtu \\
      --color stress_yy -o particles.png
"""
import argparse
import base64
import os
import re
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

VTK_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2",
             "Int32": "i4", "UInt32": "u4", "Int64": "i8", "UInt64": "u8",
             "Float32": "f4", "Float64": "f8"}
AXES = {"x": 0, "y": 1, "z": 2}


def b64decode(text):
    """Decode base64 that may consist of several padded chunks (header and
    data are often encoded separately and simply concatenated)."""
    return b"".join(base64.b64decode(c) for c in re.findall(r"[^=]+=*", text))


def read_data_array(elem, endian, header_type, compressed):
    """Return the contents of a <DataArray> as an (n, ncomp) float array."""
    ncomp = int(elem.get("NumberOfComponents", "1"))
    fmt = elem.get("format", "ascii")
    text = elem.text or ""
    if fmt == "ascii":
        values = np.array(text.split(), dtype=float)
    elif fmt == "binary":
        raw = b64decode("".join(text.split()))
        hdr = np.dtype(endian + VTK_TYPES[header_type])
        hs = hdr.itemsize
        if compressed:  # [nblocks, blocksize, lastblocksize, csize_0, ...]
            nblocks = int(np.frombuffer(raw[:hs], hdr)[0])
            sizes = np.frombuffer(raw[3 * hs:(3 + nblocks) * hs], hdr)
            pos, blocks = (3 + nblocks) * hs, []
            for size in sizes:
                blocks.append(zlib.decompress(raw[pos:pos + int(size)]))
                pos += int(size)
            data = b"".join(blocks)
        else:  # [nbytes] followed by the raw data
            nbytes = int(np.frombuffer(raw[:hs], hdr)[0])
            data = raw[hs:hs + nbytes]
        dtype = np.dtype(endian + VTK_TYPES[elem.get("type", "Float32")])
        values = np.frombuffer(data, dtype).astype(float)
    else:
        sys.exit("error: DataArray format '%s' is not supported" % fmt)
    return values.reshape(-1, ncomp)


def read_vtu(path):
    """Return (points (n,3), {name: (n, ncomp) array}) of one .vtu file."""
    root = ET.parse(path).getroot()
    endian = ">" if root.get("byte_order") == "BigEndian" else "<"
    header_type = root.get("header_type", "UInt32")
    compressor = root.get("compressor", "")
    if compressor and compressor != "vtkZLibDataCompressor":
        sys.exit("error: %s: compressor %s not supported" % (path, compressor))
    args = (endian, header_type, bool(compressor))
    points, fields = [], {}
    for piece in root.iter("Piece"):
        points.append(read_data_array(piece.find("Points/DataArray"), *args))
        for arr in piece.findall("PointData/DataArray"):
            fields.setdefault(arr.get("Name"), []).append(
                read_data_array(arr, *args))
    return (np.concatenate(points),
            {k: np.concatenate(v) for k, v in fields.items()})


def read_particles(path):
    """Read a .vtu file, or a .pvtu file and all pieces it lists."""
    if not path.endswith(".pvtu"):
        return read_vtu(path)
    root = ET.parse(path).getroot()
    pieces = [read_vtu(os.path.join(os.path.dirname(path), p.get("Source")))
              for p in root.iter("Piece")]
    common = set.intersection(*(set(f) for _, f in pieces))
    return (np.concatenate([p for p, _ in pieces]),
            {k: np.concatenate([f[k] for _, f in pieces])
             for k in pieces[0][1] if k in common})


def color_values(spec, points, fields, dim):
    """Return (values, label) for a --color specification."""
    name, _, comp = spec.partition(":")
    if name == "height":
        return points[:, dim - 1], "height [m]"
    if name in AXES and name not in fields:
        return points[:, AXES[name]], name + " [m]"
    if name not in fields:
        sys.exit("error: unknown field '%s' (use --list)" % name)
    data = fields[name]
    if comp in ("", "norm", "mag") and data.shape[1] > 1:
        label = "speed" if name == "velocity" else "|%s|" % name
        return np.linalg.norm(data[:, :dim], axis=1), label
    idx = AXES[comp] if comp in AXES else int(comp or 0)
    return data[:, idx], name + (":" + comp if comp else "")


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input", help=".pvtu or .vtu particle file")
    ap.add_argument("-o", "--output", default="particles.png")
    ap.add_argument("--color", help="FIELD[:COMPONENT] (default: speed)")
    ap.add_argument("--view", choices=["xy", "xz", "yz", "3d"])
    ap.add_argument("--title")
    ap.add_argument("--point-size", type=float, default=4.0)
    ap.add_argument("--also", nargs="+", default=[], metavar="INPUT2")
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args()

    points, fields = read_particles(args.input)
    dim = 2 if np.all(points[:, 2] == 0) else 3
    if args.list:
        print("%s: %d points, dim %d" % (args.input, len(points), dim))
        for a, i in AXES.items():
            print("  %s: min %g max %g" % (a, points[:, i].min(), points[:, i].max()))
        for name, data in fields.items():
            print("  %-20s %d component(s)  min %g max %g"
                  % (name, data.shape[1], data.min(), data.max()))
        return

    spec = args.color or ("velocity" if "velocity" in fields else "height")
    values, label = color_values(spec, points, fields, dim)
    others = [read_particles(p)[0] for p in args.also]
    view = args.view or ("xy" if dim == 2 else "xz")
    allpts = np.concatenate([points] + others)

    fig = plt.figure(figsize=(8, 6), layout="constrained")
    cbar = dict(shrink=0.6, pad=0.15)
    if view == "3d":
        ax = fig.add_subplot(projection="3d")
        for o in others:
            ax.scatter(o[:, 0], o[:, 1], o[:, 2], s=args.point_size,
                       c="lightgrey", depthshade=False)
        sc = ax.scatter(points[:, 0], points[:, 1], points[:, 2],
                        s=args.point_size, c=values, cmap="viridis")
        lo, hi = allpts.min(axis=0), allpts.max(axis=0)
        span = np.maximum(hi - lo, 1e-3 * max((hi - lo).max(), 1e-12))
        mid = 0.5 * (lo + hi)
        ax.set_xlim(mid[0] - span[0] / 2, mid[0] + span[0] / 2)
        ax.set_ylim(mid[1] - span[1] / 2, mid[1] + span[1] / 2)
        ax.set_zlim(mid[2] - span[2] / 2, mid[2] + span[2] / 2)
        ax.set_box_aspect(span)  # equal scale on all axes
        ax.locator_params(axis="z", nbins=4)
        ax.set_zlabel("z [m]")
    else:
        i, j = AXES[view[0]], AXES[view[1]]
        extent = np.ptp(allpts[:, [i, j]], axis=0) + 1e-12
        aspect = min(max(extent[1] / extent[0], 0.1), 3.0)
        wide = aspect < 0.6  # flat domain: colorbar below the plot
        fig.set_size_inches(10, 10 * aspect + (2.5 if wide else 1.5))
        cbar = dict(orientation="horizontal" if wide else "vertical",
                    shrink=0.6 if wide else 1.0, aspect=40 if wide else 20)
        ax = fig.add_subplot()
        for o in others:
            ax.scatter(o[:, i], o[:, j], s=args.point_size, c="lightgrey",
                       linewidths=0)
        sc = ax.scatter(points[:, i], points[:, j], s=args.point_size,
                        c=values, cmap="viridis", linewidths=0)
        ax.set_aspect("equal")
    labels = {"3d": "xy"}.get(view, view)
    ax.set_xlabel(labels[0] + " [m]")
    ax.set_ylabel(labels[1] + " [m]")
    fig.colorbar(sc, ax=ax, label=label, **cbar)
    ax.set_title(args.title or "%s (%d points)"
                 % (os.path.basename(args.input), len(points)))
    fig.savefig(args.output, dpi=150, bbox_inches="tight")
    print("wrote", args.output)


if __name__ == "__main__":
    main()
