#!/usr/bin/env python3
"""Figures of a generated rock mass (blockdem generate): the cumulative block volume distribution
(log axis) and a rendered view of the blocks.

Usage: plot_rock_mass.py DIR [--title TEXT]
Reads DIR/blocks.csv, DIR/rock_mass.json and DIR/blocks.vtk; writes
DIR/block_volume_distribution.png and DIR/blocks.png.
       plot_rock_mass.py --run-vtk FILE --png OUT [--title TEXT]
Renders a run's blocks_NNNNNN.vtu (blockdem run) seen from the south, faces coloured by their
block's displacement: the state after an excavation, key blocks stand out.
"""
import argparse
import csv
import json
import os
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def read_vtk(path):
    """Points, polygons and integer cell arrays of the POLYDATA file blockdem writes."""
    with open(path) as f:
        tokens = f.read().split("\n")
    i = 0
    points, polygons, cells = None, [], {}
    while i < len(tokens):
        line = tokens[i].split()
        if not line:
            i += 1
            continue
        if line[0] == "POINTS":
            n = int(line[1])
            points = np.array([[float(x) for x in tokens[i + 1 + k].split()] for k in range(n)])
            i += n + 1
        elif line[0] == "POLYGONS":
            n = int(line[1])
            polygons = [[int(x) for x in tokens[i + 1 + k].split()[1:]] for k in range(n)]
            i += n + 1
        elif line[0] == "SCALARS":
            n = len(polygons)
            cells[line[1]] = np.array([int(tokens[i + 2 + k]) for k in range(n)])
            i += n + 2
        elif line[0] == "VECTORS":
            n = len(polygons)
            cells[line[1]] = np.array(
                [[float(x) for x in tokens[i + 1 + k].split()] for k in range(n)])
            i += n + 1
        else:
            i += 1
    return points, polygons, cells


def read_vtu(path):
    """Points, face polygons and per-face cell arrays of a run's VTK XML frame (docs/outputs.md):
    an UnstructuredGrid of polyhedra, its arrays appended raw, each behind a UInt64 byte count."""
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    raw = data[data.index(b"_", start) + 1:]
    header = data[:start].decode() + "</VTKFile>"
    types = {"Float64": "<f8", "Int64": "<i8", "Int32": "<i4", "UInt8": "u1"}

    def array(node):
        offset = int(node.get("offset"))
        size = int(np.frombuffer(raw, "<u8", 1, offset)[0])
        values = np.frombuffer(raw[offset + 8:offset + 8 + size], types[node.get("type")])
        k = int(node.get("NumberOfComponents", "1"))
        return values.reshape(-1, k) if k > 1 else values

    piece = ET.fromstring(header).find("UnstructuredGrid/Piece")
    arrays = {a.get("Name"): a for a in piece.iter("DataArray")}
    points = array(arrays["Points"])
    faces, ends = array(arrays["faces"]), array(arrays["faceoffsets"])
    # Each cell's face stream: its number of faces, then each face as a count and point ids.
    polygons, owner, at = [], [], 0
    for cell, end in enumerate(ends):
        at += 1
        while at < end:
            n = int(faces[at])
            polygons.append([int(i) for i in faces[at + 1:at + 1 + n]])
            owner.append(cell)
            at += n + 1
    cells = {}
    for a in piece.find("CellData").iter("DataArray"):
        if a.get("type") in types:
            cells[a.get("Name")] = array(a)[np.array(owner, dtype=int)]
    return points, polygons, cells


def volume_distribution(out, volumes, title):
    v = np.sort(np.asarray(volumes))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(v, 100.0 * np.cumsum(v) / v.sum(), label="by volume", color="tab:blue")
    ax.plot(v, 100.0 * np.arange(1, len(v) + 1) / len(v), label="by number", color="tab:orange",
            linestyle="--")
    ax.set_xscale("log")
    ax.set_xlabel("block volume (m³)")
    ax.set_ylabel("cumulative share at or below (%)")
    ax.set_ylim(0, 100)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    ax.set_title(f"{title}: {len(v)} blocks, V50 = {np.median(v):.3g} m³")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "block_volume_distribution.png"), dpi=150)
    plt.close(fig)


def render(out, points, polygons, cells, title):
    # Outer faces (region boundary) and excavation outlines of the blocks left after every
    # excavation: the rock mass as seen from outside, tunnel or cut open.
    source, block, exc = cells["face_source"], cells["block_index"], cells["excavation"]
    keep = [k for k in range(len(polygons)) if exc[k] < 0 and source[k] in (0, 2)]
    polys = [points[polygons[k]] for k in keep]
    rng = np.random.default_rng(1)
    palette = rng.uniform(0.45, 0.9, size=(int(block.max()) + 1, 3))
    light = np.array([0.4, -0.5, 0.77])
    colours = []
    for k, p in zip(keep, polys):
        n = np.cross(p[1] - p[0], p[2] - p[0])
        n = n / (np.linalg.norm(n) + 1e-300)
        shade = 0.55 + 0.45 * abs(n @ light)
        c = palette[block[k]] * shade
        colours.append(np.append(np.clip(c, 0, 1), 1.0))
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors=(0, 0, 0, 0.35),
                                         linewidths=0.3))
    lo, hi = points.min(axis=0), points.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.set_xlabel("x east (m)")
    ax.set_ylabel("y north (m)")
    ax.set_zlabel("z up (m)")
    ax.view_init(elev=22, azim=-60)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "blocks.png"), dpi=150)
    plt.close(fig)


def render_run(vtk, png, title):
    points, polygons, cells = read_vtu(vtk)
    disp = np.linalg.norm(cells["displacement"], axis=1) * 1e3
    polys = [points[p] for p in polygons]
    norm = matplotlib.colors.LogNorm(vmin=max(1e-3, disp.min() + 1e-3), vmax=max(disp.max(), 1e-2))
    cmap = plt.get_cmap("viridis")
    colours = [cmap(norm(max(d, 1e-3))) for d in disp]
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors=(0, 0, 0, 0.4),
                                         linewidths=0.3))
    lo, hi = points.min(axis=0), points.max(axis=0)
    # Each axis at least a quarter of the longest (padded about its middle, not stretched), so a
    # thin model (a slab, a slice) keeps room for its ticks; the scale is the same on all three.
    middle, span = (lo + hi) / 2, hi - lo
    span = np.maximum(span, 0.25 * span.max())
    lo, hi = middle - span / 2, middle + span / 2
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.locator_params(nbins=4)
    ax.set_xlabel("x east (m)")
    ax.set_ylabel("y north (m)")
    ax.set_zlabel("z up (m)")
    ax.view_init(elev=12, azim=-80)
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=ax, shrink=0.6, label="block displacement (mm)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(png, dpi=150)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", nargs="?")
    parser.add_argument("--title", default=None)
    parser.add_argument("--run-vtk", default=None)
    parser.add_argument("--png", default=None)
    args = parser.parse_args()
    if args.run_vtk:
        render_run(args.run_vtk, args.png, args.title or os.path.basename(args.run_vtk))
        return
    with open(os.path.join(args.dir, "blocks.csv")) as f:
        volumes = [float(r["volume_m3"]) for r in csv.DictReader(f)]
    with open(os.path.join(args.dir, "rock_mass.json")) as f:
        summary = json.load(f)
    title = args.title or os.path.basename(os.path.normpath(args.dir))
    volume_distribution(args.dir, volumes, title)
    points, polygons, cells = read_vtk(os.path.join(args.dir, "blocks.vtk"))
    removed = sum(e["blocks_inside"] for e in summary.get("excavations", []))
    label = f"{title}: {summary['blocks']} blocks" + (
        f", {removed} excavated" if removed else "")
    render(args.dir, points, polygons, cells, label)


if __name__ == "__main__":
    main()
