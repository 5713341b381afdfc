#!/usr/bin/python3
"""The viscous boundary's coefficients calibrated with the DEM in the loop by five optimisers (the convergence
comparison, after Ma et al. 2022's figure of LHS-WCA against WCA, GA and harmony search).

The problem: the coefficients of a space (for the wave strip data/spaces/ma2022_viscous_boundary.json, four; for
the rockfill slope data/spaces/ma2022_slope_boundary.json, six) on a scene (seed 1, the same specimen for every
candidate), the fitness Ma's total recovery time over the scene's fixed-boundary reference (demcal-invert
--objective minimise). Each optimiser runs with the same budget of DEM runs and several optimiser seeds; a finished
run is kept (the folder is resumable: rerunning skips it, and an interrupted one reuses its DEM runs). Writes
OUT/summary.md (per optimiser: best total recovery time, the DEM runs it took to come within 5 % of that best and
of the best any run found, medians and ranges over the seeds, and the coefficients of the best run) and, with
--figure, the best-so-far against DEM runs (each optimiser's median over its seeds and their range).

    scripts/boundary_calibration_comparison.py --build build [--scene S] [--budget N] [--seeds 3] [--figure F.png]

The shipped scenes know their space and reference; another scene needs --space and --fixed-scene.
"""
import argparse
import csv
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys

# Each shipped scene's space, fixed-boundary reference and default budget (DEM runs per optimiser run).
SCENES = {
    "data/scenes/wave_strip.json": {"space": "data/spaces/ma2022_viscous_boundary.json",
                                    "fixed": "data/scenes/wave_strip_fixed.json", "budget": 200},
    "data/scenes/rockfill_slope.json": {"space": "data/spaces/ma2022_slope_boundary.json",
                                        "fixed": "data/scenes/rockfill_slope_fixed.json", "budget": 400},
}
# Populations of 20 let a 200-run budget see several generations; the annealing tries two moves at once (two
# cores) with its temperature scaled to a fitness of order 1 and steps of a tenth of each range; harmony search
# improvises two points at once (two cores).
SETTINGS = {"lhs-wca": ["population=20"], "wca": ["population=20"], "ga": ["population=20"],
            "sa": ["T0=0.05", "markov_chain_length=10", "step_scale=0.1", "parallel_trials=2"],
            "hs": ["improvisations=2"]}


def fail(message):
    print(f"boundary_calibration_comparison.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip().splitlines()[-1:]}")
    return done


def reference(bin_dir, out, cache, fixed_scene):
    """The fixed boundary's total recovery time (seed 1): the fitness's unit."""
    path = os.path.join(out, "fixed.json")
    if not os.path.exists(path):
        run([os.path.join(bin_dir, "demcal-dem"), "run", "--scene", fixed_scene, "--seed", "1", "--cache", cache,
             "--quiet", "--out", path])
    result = json.load(open(path))
    if result.get("status") != "ok":
        fail(f"{path}: the fixed-boundary run failed: {result.get('reason')}")
    return result["macro"]["total_recovery_time_s"]


def history(path):
    """(DEM runs, best fitness so far) of one optimiser run."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(int(r["evaluations"]), float(r["best_objective"])) for r in rows]


def runs_to_within(points, fraction, best=None):
    """DEM runs until the best-so-far came within fraction of best (default: the run's own best); None if never."""
    best = points[-1][1] if best is None else best
    for evaluations, value in points:
        if value <= best * (1 + fraction):
            return evaluations
    return None


def median_and_range(counts):
    """'median (low-high)' of DEM-run counts where None (never) ranks above every count."""
    ranked = sorted(counts, key=lambda c: float("inf") if c is None else c)
    half = len(ranked) // 2
    middle = ranked[half - 1:half + 1] if len(ranked) % 2 == 0 else [ranked[half]]
    median = None if None in middle else sum(middle) / len(middle)
    show = lambda c: "never" if c is None else f"{c:g}"
    return f"{show(median)} ({show(ranked[0])}-{show(ranked[-1])})"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--scene", default="data/scenes/wave_strip.json")
    parser.add_argument("--space", help="the coefficients and their ranges (the shipped scenes know theirs)")
    parser.add_argument("--fixed-scene", help="the fixed-boundary reference (the shipped scenes know theirs)")
    parser.add_argument("--out", help="default: BUILD/boundary_calibration/<scene's name>")
    parser.add_argument("--budget", type=int, help="DEM runs per optimiser run (the strip 200, the slope 400)")
    parser.add_argument("--seeds", type=int, default=3, help="optimiser seeds per optimiser")
    parser.add_argument("--optimisers", nargs="+", default=list(SETTINGS), choices=list(SETTINGS))
    parser.add_argument("--jobs", default="2")
    parser.add_argument("--figure", help="PNG of the best-so-far against DEM runs")
    args = parser.parse_args()
    known = SCENES.get(os.path.normpath(args.scene), {})
    space, fixed_scene = args.space or known.get("space"), args.fixed_scene or known.get("fixed")
    budget = args.budget or known.get("budget", 200)
    if not space or not fixed_scene:
        fail(f"{args.scene}: not a shipped boundary scene; give --space and --fixed-scene")
    for path in (args.scene, space, fixed_scene):
        if not os.path.exists(path):
            fail(f"{path}: no such file")
    if budget < 10 or args.seeds < 1:
        fail("--budget must be at least 10 and --seeds at least 1")
    coefficients = [p["name"] for p in json.load(open(space))["parameters"]]
    bin_dir = os.path.join(args.build, "bin")
    name_of_scene = os.path.splitext(os.path.basename(args.scene))[0]
    out = args.out or os.path.join(args.build, "boundary_calibration", name_of_scene)
    cache = os.path.join(args.build, "cache")
    os.makedirs(out, exist_ok=True)
    ref = reference(bin_dir, out, cache, fixed_scene)
    print(f"fixed boundary: total recovery time {ref:.3f} s (the fitness's unit)", flush=True)
    table = {}
    for algo in args.optimisers:
        settings = SETTINGS[algo]
        for seed in range(1, args.seeds + 1):
            name = f"{algo}_seed{seed}"
            solution, hist = os.path.join(out, name + ".json"), os.path.join(out, name + "_history.csv")
            if not (os.path.exists(solution) and os.path.exists(hist)):
                command = [os.path.join(bin_dir, "demcal-invert"), "--dem-scene", args.scene, "--space", space,
                           "--target", f"total_recovery_time_s={ref!r}", "--objective", "minimise", "--algo", algo,
                           "--seed", str(seed), "--budget", str(budget), "--stop-below", "0", "--jobs",
                           args.jobs, "--cache", cache, "--quiet", "--out", solution, "--history", hist]
                for s in settings:
                    command += ["--set", s]
                started = datetime.datetime.now()
                run(command)
                print(f"{name}: {(datetime.datetime.now() - started).total_seconds():.0f} s", flush=True)
            points = history(hist)
            result = json.load(open(solution))
            table.setdefault(algo, []).append({"seed": seed, "best_s": points[-1][1] * ref, "runs": points[-1][0],
                                               "to_own_5pct": runs_to_within(points, 0.05), "x": result.get("x"),
                                               "points": points})
    best_any = min(r["best_s"] for rows in table.values() for r in rows)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    lines = [f"Measured {datetime.date.today()} at commit {commit or 'unknown'} on {os.cpu_count()} cores, "
             f"{platform.processor() or platform.machine()}, {platform.system()} {platform.release()}; "
             f"{args.scene}, budget {budget} DEM runs, {args.seeds} optimiser seeds; fixed boundary {ref:.3f} s.", "",
             f"| optimiser | best total recovery s, median (range) | DEM runs to within 5 % of its own best, median "
             f"(range) | DEM runs to within 5 % of the best any run found ({best_any:.3f} s), median (range) | "
             f"coefficients of the best run ({', '.join(coefficients)}) |",
             "|---|---|---|---|---|"]
    for algo, rows in table.items():
        best = [r["best_s"] for r in rows]
        to_own = [r["to_own_5pct"] for r in rows]
        # The common mark: every run measured against the best of all (in the fitness's unit, as the history).
        to_any = [runs_to_within(r["points"], 0.05, best_any / ref) for r in rows]
        top = min(rows, key=lambda r: r["best_s"])
        x = top["x"] or {}
        values = ", ".join(f"{x.get(k, float('nan')):.2f}" for k in coefficients)
        lines.append(f"| {algo} | {statistics.median(best):.3f} ({min(best):.3f}-{max(best):.3f}) | "
                     f"{median_and_range(to_own)} | {median_and_range(to_any)} | {values} |")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        for algo, rows in table.items():
            # Each seed's best-so-far on a common grid of DEM runs: the median line and the range shaded.
            grid = list(range(1, max(max(r["points"][-1][0] for r in rows), budget) + 1))  # drawn to the budget
            curves = []
            for r in rows:
                values, k = [], 0
                for e in grid:
                    while k + 1 < len(r["points"]) and r["points"][k + 1][0] <= e:
                        k += 1
                    values.append(r["points"][k][1] * ref if r["points"][k][0] <= e else float("nan"))
                curves.append(values)
            colour = f"C{list(table).index(algo)}"
            med = [statistics.median([c[i] for c in curves if c[i] == c[i]] or [float("nan")]) for i in range(len(grid))]
            low = [min([c[i] for c in curves if c[i] == c[i]] or [float("nan")]) for i in range(len(grid))]
            high = [max([c[i] for c in curves if c[i] == c[i]] or [float("nan")]) for i in range(len(grid))]
            ax.step(grid, med, where="post", lw=1.2, color=colour, label=f"{algo} (median of {len(rows)})")
            ax.fill_between(grid, low, high, step="post", color=colour, alpha=0.15)
        ax.set_xlabel("DEM runs")
        ax.set_ylabel("best total recovery time so far, s")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.figure, dpi=110)


if __name__ == "__main__":
    main()
