#!/usr/bin/python3
"""Convergence of the inversion algorithms: best objective against evaluations.

Reads the records written by `demcal-invert --history ALGO_seedN.csv --out ALGO_seedN.json`
in one folder and writes a Markdown table (per algorithm, medians over seeds: evaluations to
reach a threshold, final objective, wall time) and a PNG of the median best-so-far curves
with the 10-90 % band.

    /usr/bin/python3 scripts/plot_convergence.py DIR --threshold 1e-3 --budget 20000 \
        --table DIR/comparison.md --out DIR/convergence.png
"""
import argparse
import csv
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ORDER = ["ga", "sa", "sa-vfsr", "wca", "lhs-wca", "hs", "search"]


def fail(message):
    print(f"plot_convergence.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_history(path):
    steps = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            steps.append((int(row["evaluations"]), float(row["best_objective"])))
    return steps


def best_at(steps, grid):
    """Best objective so far at each evaluation count of `grid` (inf before the first)."""
    values = np.full(len(grid), np.inf)
    j, best = 0, np.inf
    for i, g in enumerate(grid):
        while j < len(steps) and steps[j][0] <= g:
            best = steps[j][1]
            j += 1
        values[i] = best
    return values


def load(folder):
    runs = {}
    for path in sorted(glob.glob(os.path.join(folder, "*_seed*.csv"))):
        match = re.match(r"(.+)_seed(\d+)\.csv$", os.path.basename(path))
        if not match:
            continue
        algo = match.group(1)
        solution_path = path[:-4] + ".json"
        try:
            solution = json.load(open(solution_path))
        except (OSError, ValueError) as e:
            fail(f"cannot read {solution_path}: {e}")
        runs.setdefault(algo, []).append((read_history(path), solution))
    if not runs:
        fail(f"no ALGO_seedN.csv records in {folder}")
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--threshold", type=float, default=1e-3, help="objective counted as reached")
    parser.add_argument("--coarse-threshold", type=float, default=0.1,
                        help="a second, engineering threshold (Wang & Cao stop at 10 %%)")
    parser.add_argument("--budget", type=int, default=None, help="x-axis end (evaluations)")
    parser.add_argument("--table", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    if not os.path.isdir(args.folder):
        fail(f"{args.folder} is not a folder")
    runs = load(args.folder)
    algos = [a for a in ORDER if a in runs] + sorted(a for a in runs if a not in ORDER)
    budget = args.budget or max(s["evaluations"] for a in algos for _, s in runs[a])
    grid = np.unique(np.geomspace(1, budget, 400).astype(int))

    lines = [
        f"| algorithm | runs | reached {args.coarse_threshold:g} | evaluations to {args.coarse_threshold:g} (median) | "
        f"reached {args.threshold:g} | evaluations to {args.threshold:g} (median) | "
        "final objective (median) | final objective (worst) | evaluations (median) | wall time (median) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    fig, ax = plt.subplots(figsize=(8, 5))
    for algo in algos:
        records = runs[algo]
        finals = [s["objective"] if s["objective"] is not None else np.inf for _, s in records]
        def evaluations_to(threshold):
            hits = []
            for steps, _ in records:
                hit = next((e for e, v in steps if v <= threshold), None)
                if hit is not None:
                    hits.append(hit)
            return hits

        coarse, needed = evaluations_to(args.coarse_threshold), evaluations_to(args.threshold)
        evaluations = [s["evaluations"] for _, s in records]
        walls = [s["wall_s"] for _, s in records]
        lines.append(
            f"| {algo} | {len(records)} | {len(coarse)} | {int(np.median(coarse)) if coarse else 'never'} | {len(needed)} | "
            f"{int(np.median(needed)) if needed else 'never'} | {np.median(finals):.3g} | {max(finals):.3g} | "
            f"{int(np.median(evaluations))} | {np.median(walls) * 1000:.1f} ms |")
        curves = np.array([best_at(steps, grid) for steps, _ in records])
        median = np.median(curves, axis=0)
        low, high = np.percentile(curves, 10, axis=0), np.percentile(curves, 90, axis=0)
        finite = np.isfinite(median)
        line, = ax.plot(grid[finite], median[finite], label=algo)
        band = np.isfinite(low) & np.isfinite(high)
        ax.fill_between(grid[band], low[band], high[band], color=line.get_color(), alpha=0.15)
    ax.axhline(args.threshold, color="grey", linestyle=":", label=f"threshold {args.threshold:g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("objective evaluations")
    ax.set_ylabel("best objective so far (sum of relative errors)")
    ax.set_title(f"Inversion convergence: median and 10-90 % band over {len(runs[algos[0]])} seeds")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    with open(args.table, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(args.out)


if __name__ == "__main__":
    main()
