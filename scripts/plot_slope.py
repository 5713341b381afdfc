#!/usr/bin/python3
"""Snapshots of a slope run and its monitoring points' velocity histories (Ma et al. 2022's figures of the rockfill
slope under the El Centro record).

Reads the VTK snapshots the slope test writes with --vtk (slope_start.vtk, slope_input_end.vtk, slope_end.vtk: disks
with their radii) and draws each, the bedrock grey and the rockfill brown (told apart by radius, --fill-radius-m);
with --result and --curve, a second figure of the horizontal and vertical velocity at the points named by --points:

    demcal-dem run --scene data/scenes/rockfill_slope_earthquake.json --out quake.json --curve quake.csv --vtk quake
    /usr/bin/python3 scripts/plot_slope.py --vtk quake --out slope_snapshots.png \\
        --result quake.json --curve quake.csv --points 3-3 1-1 --velocity-out slope_velocity.png
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection  # noqa: E402

SNAPSHOTS = (("slope_start.vtk", "at rest, before the input"), ("slope_input_end.vtk", "when the input ends"),
             ("slope_end.vtk", "at the end of the run"))


def fail(message):
    print(f"plot_slope.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_disks(path):
    """(x, y, radius, time label) of a legacy-VTK disk snapshot."""
    try:
        lines = open(path).read().split("\n")
    except OSError as e:
        fail(f"cannot read {path}: {e}")
    try:
        n = int(lines[4].split()[1])
        points = np.array([[float(v) for v in line.split()[:2]] for line in lines[5:5 + n]])
        start = lines.index("SCALARS radius double 1") + 2
        radius = np.array(" ".join(lines[start:start + n]).split()[:n], dtype=float)
    except (IndexError, ValueError):
        fail(f"{path}: not a disk snapshot of the slope test (POINTS and a radius field expected)")
    if len(points) != n or len(radius) != n:
        fail(f"{path}: {n} disks announced, fewer given")
    when = lines[1].replace("demcal disks at t = ", "").replace(" s", "").strip()
    try:
        when = f"t = {float(when):.2f} s"
    except ValueError:
        pass
    return points[:, 0], points[:, 1], radius, when


def draw_snapshots(folder, fill_radius_m, out):
    paths = [(os.path.join(folder, name), title) for name, title in SNAPSHOTS]
    missing = [p for p, _ in paths if not os.path.exists(p)]
    if missing:
        fail(f"missing snapshot(s): {', '.join(missing)} (run the slope test with --vtk)")
    fig, axes = plt.subplots(len(paths), 1, figsize=(9, 2.3 * len(paths)), sharex=True)
    for ax, (path, title) in zip(axes, paths):
        x, y, r, when = read_disks(path)
        fill = r < fill_radius_m
        for mask, colour in ((~fill, "#9a9a9a"), (fill, "#a0522d")):
            d = 2 * r[mask]
            ax.add_collection(EllipseCollection(d, d, np.zeros(mask.sum()), units="xy",
                                                offsets=np.column_stack([x[mask], y[mask]]),
                                                transOffset=ax.transData, facecolors=colour, edgecolors="none"))
        ax.set_xlim(x.min() - 10, x.max() + 10)
        ax.set_ylim(min(0, y.min()) - 5, y.max() + 15)
        ax.set_aspect("equal")
        ax.set_title(f"{title} ({when}); rockfill {fill.sum()} disks, x from {np.percentile(x[fill], 1):.0f} "
                     f"to {np.percentile(x[fill], 99):.0f} m" if fill.any() else f"{title} ({when})", fontsize=9)
        ax.set_ylabel("y, m")
    axes[-1].set_xlabel("x, m")
    fig.tight_layout()
    fig.savefig(out, dpi=72)  # thousands of disks: a small figure for the docs


def draw_velocities(result_path, curve_path, points, out):
    try:
        result = json.load(open(result_path))
    except (OSError, json.JSONDecodeError) as e:
        fail(f"cannot read {result_path}: {e}")
    if result.get("status") != "ok":
        fail(f"{result_path}: the run failed ({result.get('reason', 'no reason given')}): nothing to draw")
    try:
        with open(curve_path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read {curve_path}: {e}")
    if not rows or "time_s" not in rows[0]:
        fail(f"{curve_path}: no time_s column (the slope test's curve expected)")
    t = np.array([float(r["time_s"]) for r in rows])
    fig, axes = plt.subplots(len(points), 1, figsize=(8, 2.4 * len(points)), sharex=True, squeeze=False)
    for ax, point in zip(axes[:, 0], points):
        label = point.replace("-", "_")
        for component in ("vx", "vy"):
            column = f"{component}_{label}_m_s"
            if column not in rows[0]:
                fail(f"{curve_path}: no column {column} (point {point} is not a monitoring point of this run)")
            ax.plot(t, [float(r[column]) for r in rows], lw=0.8, label=component)
        peak = result.get("macro", {}).get(f"peak_speed_m_s_{label}")
        ax.set_title(f"point {point}" + (f": peak {peak:.3f} m/s at {result['macro'][f'peak_time_s_{label}']:.2f} s"
                                         if peak is not None else ""), fontsize=9)
        ax.set_ylabel("m/s")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel("time, s")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vtk", required=True, help="folder of the run's VTK snapshots")
    parser.add_argument("--out", required=True, help="PNG of the snapshots")
    parser.add_argument("--fill-radius-m", type=float, default=1.0, help="disks smaller than this are rockfill")
    parser.add_argument("--result", help="the run's result JSON")
    parser.add_argument("--curve", help="the run's curve CSV")
    parser.add_argument("--points", nargs="+", default=["3-3"], help="monitoring points to draw")
    parser.add_argument("--velocity-out", help="PNG of the velocity histories")
    args = parser.parse_args()
    if (args.result or args.curve or args.velocity_out) and not (args.result and args.curve and args.velocity_out):
        fail("--result, --curve and --velocity-out go together")
    draw_snapshots(args.vtk, args.fill_radius_m, args.out)
    if args.result:
        draw_velocities(args.result, args.curve, args.points, args.velocity_out)


if __name__ == "__main__":
    main()
