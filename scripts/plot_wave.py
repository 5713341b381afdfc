#!/usr/bin/python3
"""Velocity histories of wave-strip runs at their monitoring points, one panel per run (Ma et al. 2022's Figures 4
and 6: a fixed against a viscous boundary); with --points, the named points of any run whose curve carries them
(the slope's 2-1, as their Figure 14).

Reads each run's result JSON and its curve (time_s, vx_T1_m_s, vy_T1_m_s, ...: a batch point's JSON holds it,
`demcal-dem run` writes it with --curve) and draws the velocity along the pulse's path (x, for an input side on the
left or right) against time:

    demcal-dem run --scene data/scenes/wave_strip_velocity_fixed.json --out fixed.json --curve fixed.csv
    demcal-dem run --scene data/scenes/wave_strip.json --out viscous.json --curve viscous.csv
    /usr/bin/python3 scripts/plot_wave.py fixed.json viscous.json --curves fixed.csv viscous.csv \
        --labels "fixed" "viscous" --out wave.png
    /usr/bin/python3 scripts/plot_wave.py fixed.json calibrated.json --curves fixed.csv calibrated.csv \
        --points 2-1 --component vy --out slope_2_1.png
"""
import argparse
import json
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def fail(message):
    print(f"plot_wave.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def histories(path, component, curve_csv=None, named=None):
    """(time, {point: velocity}, macro values) of one wave-strip result, or of the named points (labels as 2-1)."""
    try:
        result = json.load(open(path))
    except (OSError, json.JSONDecodeError) as e:
        fail(f"cannot read {path}: {e}")
    if result.get("status") != "ok":
        fail(f"{path}: the run failed ({result.get('reason', 'no reason given')}): nothing to draw")
    curve = result.get("curve", {})
    if not curve and curve_csv:
        try:
            table = np.genfromtxt(curve_csv, delimiter=",", names=True)
        except OSError as e:
            fail(f"cannot read {curve_csv}: {e}")
        if table.dtype.names is None:
            fail(f"{curve_csv}: no header row")
        curve = {name: np.atleast_1d(table[name]) for name in table.dtype.names}
    if named:
        missing = [p for p in named if f"{component}_{p.replace('-', '_')}_m_s" not in curve]
        if missing or "time_s" not in curve:
            fail(f"{curve_csv or path}: no time_s or no {component} column for point(s) {', '.join(missing)}")
        return curve["time_s"], {p: curve[f"{component}_{p.replace('-', '_')}_m_s"] for p in named}, \
            result.get("macro", {})
    points = sorted((m.group(1) for m in (re.fullmatch(rf"{component}_(T\d+)_m_s", k) for k in curve) if m),
                    key=lambda name: int(name[1:]))
    if "time_s" not in curve or not points:
        fail(f"{path}: not a wave-strip result (no time_s and {component}_T1_m_s ... in its curve; give the run's "
             "--curve CSV with --curves when its JSON holds none)")
    return curve["time_s"], {p: curve[f"{component}_{p}_m_s"] for p in points}, result.get("macro", {})


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", nargs="+", help="result JSON of each wave-strip run")
    parser.add_argument("--curves", nargs="+", help="each run's curve CSV (demcal-dem run --curve), in the same order")
    parser.add_argument("--labels", nargs="+", help="a title per run (default: the file names)")
    parser.add_argument("--component", choices=["vx", "vy"], default="vx", help="velocity component drawn")
    parser.add_argument("--points", nargs="+", help="monitoring points to draw by label (the slope's 2-1); default: "
                        "the strip's T1, T2, ...")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    labels = args.labels or args.results
    if len(labels) != len(args.results):
        fail(f"{len(labels)} labels for {len(args.results)} results")
    curves = args.curves or [None] * len(args.results)
    if len(curves) != len(args.results):
        fail(f"{len(curves)} curves for {len(args.results)} results")
    fig, axes = plt.subplots(len(args.results), 1, figsize=(8, 2.6 * len(args.results)), sharex=True, squeeze=False)
    for ax, path, curve_csv, label in zip(axes[:, 0], args.results, curves, labels):
        t, v, macro = histories(path, args.component, curve_csv, args.points)
        for point, values in v.items():
            ax.plot(t, values, lw=1, label=point)
        total = macro.get("total_recovery_time_s")
        reflection = macro.get("reflection_coefficient")
        title = label
        if total is not None and reflection is not None:
            title += f": total recovery {total:.2f} s, reflection {reflection:+.2f}"
        elif args.points:
            recovered = [(p, macro.get(f"recovery_time_s_{p.replace('-', '_')}")) for p in args.points]
            title += ": recovery " + ", ".join(f"{p} {r:.2f} s" for p, r in recovered if r is not None)
        ax.set_title(title, fontsize=9)
        ax.set_ylabel(f"{args.component}, m/s")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=len(v), loc="upper right")
    axes[-1, 0].set_xlabel("time since the pulse started, s")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
