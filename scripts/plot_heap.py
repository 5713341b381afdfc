#!/usr/bin/python3
"""Picture of a settled heap (the heap test) with its surface profile and the two fitted flanks.

Reads the run's result (the fitted lines are its `specimen` entries aor_left/right_slope and _intercept_m),
its curve (the surface profile: x in the axial_strain column, the height in lateral_strain; a batch point's
JSON holds it, `demcal-dem run` writes it with --curve) and, when given, the final VTK snapshot of `--vtk DIR`:

    demcal-dem run --scene data/scenes/heap_powder.json --out heap.json --curve heap_profile.csv --vtk heap_vtk
    /usr/bin/python3 scripts/plot_heap.py heap.json --curve heap_profile.csv --vtk heap_vtk/final_000000.vtk --out heap.png
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_specimen import read_vtk  # noqa: E402


def fail(message):
    print(f"plot_heap.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("result", help="RESULT.json of a heap run")
    parser.add_argument("--curve", help="the run's curve as CSV (demcal-dem run --curve), when RESULT.json holds none")
    parser.add_argument("--vtk", help="the run's final VTK snapshot (particles)")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    try:
        result = json.load(open(args.result))
    except (OSError, json.JSONDecodeError) as e:
        fail(f"cannot read {args.result}: {e}")
    if result.get("status") != "ok":
        fail(f"{args.result}: the run failed ({result.get('reason', 'no reason given')}): nothing to draw")
    info, macro, curve = result.get("specimen", {}), result.get("macro", {}), result.get("curve", {})
    keys = ["aor_left_slope", "aor_left_intercept_m", "aor_right_slope", "aor_right_intercept_m"]
    if "aor_deg" not in macro or any(k not in info for k in keys):
        fail(f"{args.result}: not a heap result (no aor_deg or fitted lines)")
    if not curve:
        if not args.curve:
            fail(f"{args.result} holds no curve: give the run's --curve CSV")
        try:
            table = np.genfromtxt(args.curve, delimiter=",", names=True)
        except OSError as e:
            fail(f"cannot read {args.curve}: {e}")
        if table.dtype.names is None or not {"axial_strain", "lateral_strain"} <= set(table.dtype.names):
            fail(f"{args.curve}: no axial_strain and lateral_strain columns")
        curve = {name: np.atleast_1d(table[name]) for name in ("axial_strain", "lateral_strain")}
    x = np.array(curve.get("axial_strain", []))  # the profile: x along the plate ...
    h = np.array(curve.get("lateral_strain", []))  # ... and the surface height there
    fig, ax = plt.subplots(figsize=(9, 4))
    if args.vtk:
        xy, s = read_vtk(args.vtk)
        if "radius" not in s:
            fail(f"{args.vtk}: no radius scalars (not a demcal disks file?)")
        ax.add_collection(PatchCollection([Circle(p, r) for p, r in zip(xy, s["radius"])], facecolor="#c9b27c",
                                          edgecolor="#7a6a3f", linewidth=0.2))
    ax.plot(x, h, ".", color="#444444", markersize=3, label="surface profile (highest top per bin)")
    height = macro["heap_height_m"]
    for side, colour in (("left", "#e31a1c"), ("right", "#1f78b4")):
        slope, intercept = info[f"aor_{side}_slope"], info[f"aor_{side}_intercept_m"]
        # The line over the heights it was fitted between (10 % to 90 % of the heap's).
        xs = np.array([(0.1 * height - intercept) / slope, (0.9 * height - intercept) / slope])
        ax.plot(xs, intercept + slope * xs, "-", color=colour, linewidth=2,
                label=f"{side} flank {macro[f'aor_{side}_deg']:.1f} deg")
    ax.axhline(0, color="black", linewidth=1)
    ax.set_title(f"angle of repose {macro['aor_deg']:.1f} deg, heap {1000 * height:.1f} mm, "
                 f"flow time {macro['flow_time_s']:.2f} s")
    span = max(np.abs(x).max() if len(x) else 0.05, 0.01)
    ax.set_xlim(-1.1 * span, 1.1 * span)
    ax.set_ylim(-0.1 * height, 1.6 * height)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("height above the plate (m)")
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(args.out)


if __name__ == "__main__":
    main()
