#!/usr/bin/python3
"""Picture of a DEM specimen from the VTK snapshots of `demcal-dem run --vtk DIR`.

Disks drawn to scale, aggregates (clumps) coloured apart from the mortar, bond breaks
marked by mode (tension / shear), and the walls (platens) as lines.

    /usr/bin/python3 scripts/plot_specimen.py DIR/final_000052.vtk [DIR/final_breaks_000052.vtk] \
        [--walls DIR/final_walls_000052.vtk] --out specimen.png
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import CircleCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
import numpy as np  # noqa: E402


def fail(message):
    print(f"plot_specimen.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_vtk_lines(path):
    """The segments ((x0, y0), (x1, y1)) and CELL_DATA scalars of a walls file as `demcal-dem run --vtk` writes it
    (legacy ASCII VTK POLYDATA: a point per line, one LINES section, then its cell scalars)."""
    try:
        lines = open(path).read().split("\n")
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    points, segments, scalars, i = None, [], {}, 0
    while i < len(lines):
        words = lines[i].split()
        if words and words[0] == "POINTS":
            points = np.array([[float(v) for v in lines[i + 1 + k].split()[:2]] for k in range(int(words[1]))])
            i += len(points)
        elif words and words[0] == "LINES" and points is not None:
            for k in range(int(words[1])):
                ends = [int(v) for v in lines[i + 1 + k].split()[1:3]]
                segments.append((points[ends[0]], points[ends[1]]))
            i += len(segments)
        elif words and words[0] == "SCALARS" and segments:
            scalars[words[1]] = np.array([float(lines[i + 2 + k]) for k in range(len(segments))])
            i += 1 + len(segments)
        i += 1
    if points is None:
        fail(f"{path}: no POINTS section")
    return segments, scalars


def read_vtk(path):
    """Points and point scalars of a legacy ASCII VTK POLYDATA file."""
    try:
        lines = open(path).read().split("\n")
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    points, scalars, i = None, {}, 0
    while i < len(lines):
        words = lines[i].split()
        if words and words[0] == "POINTS":
            n = int(words[1])
            points = np.array([[float(v) for v in lines[i + 1 + k].split()[:2]] for k in range(n)])
            i += n
        elif words and words[0] == "SCALARS" and points is not None:
            name = words[1]
            n = len(points)
            start = i + 2  # after LOOKUP_TABLE
            scalars[name] = np.array([float(lines[start + k]) for k in range(n)])
            i = start + n - 1
        i += 1
    if points is None:
        fail(f"{path}: no POINTS section")
    return points, scalars


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("disks")
    parser.add_argument("breaks", nargs="?")
    parser.add_argument("--walls", help="the walls file written with the disks (final_walls_*.vtk)")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    xy, s = read_vtk(args.disks)
    if "radius" not in s:
        fail(f"{args.disks}: no radius scalars (not a demcal disks file?)")
    clump = s.get("clump_id", np.full(len(xy), -1))
    fig, ax = plt.subplots(figsize=(5, 9))
    mortar, aggregate = clump < 0, clump >= 0
    patches_m = [Circle(p, r) for p, r in zip(xy[mortar], s["radius"][mortar])]
    patches_a = [Circle(p, r) for p, r in zip(xy[aggregate], s["radius"][aggregate])]
    ax.add_collection(PatchCollection(patches_m, facecolor="#d9d9d9", edgecolor="#969696", linewidth=0.2))
    ax.add_collection(PatchCollection(patches_a, facecolor="#8c6d31", edgecolor="#5a4520", linewidth=0.2))
    title = f"{len(xy)} disks, {int(aggregate.sum())} in {len(set(clump[aggregate]))} aggregates"
    if args.breaks:
        bxy, bs = read_vtk(args.breaks)
        mode = bs.get("mode", np.zeros(len(bxy)))
        for value, colour, label in ((0, "#e31a1c", "tension break"), (1, "#1f78b4", "shear break")):
            pts = bxy[mode == value]
            if len(pts):
                ax.plot(pts[:, 0], pts[:, 1], ".", markersize=2, color=colour, label=f"{label} ({len(pts)})")
        ax.legend(loc="upper right", fontsize=7, markerscale=4, framealpha=0.9)
    ax.set_xlim(xy[:, 0].min() - 0.002, xy[:, 0].max() + 0.002)
    ax.set_ylim(xy[:, 1].min() - 0.002, xy[:, 1].max() + 0.002)
    if args.walls:
        segments, ws = read_vtk_lines(args.walls)
        active = ws.get("active", np.ones(len(segments)))
        for (a, b), on in zip(segments, active):
            if on:
                ax.plot([a[0], b[0]], [a[1], b[1]], "-", color="#252525", linewidth=1.5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    print(args.out)


if __name__ == "__main__":
    main()
