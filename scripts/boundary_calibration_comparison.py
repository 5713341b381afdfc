#!/usr/bin/python3
"""The viscous boundary's coefficients calibrated with the DEM in the loop by four optimisers (the
convergence comparison, after Ma et al. 2022's Figure of LHS-WCA against WCA and GA).

The problem: the four coefficients of data/spaces/ma2022_viscous_boundary.json on data/scenes/wave_strip.json (seed
1, the same specimen for every candidate), the fitness Ma's total recovery time over the fixed far side's
(demcal-invert --objective minimise). Each optimiser runs with the same budget of DEM runs and three optimiser
seeds; a finished run is kept (the folder is resumable: rerunning skips it, and an interrupted one reuses its DEM
runs). Writes OUT/summary.md (per optimiser: best total recovery time and the DEM runs it took to come within
5 % of that best, medians over the seeds) and, with --figure, the best-so-far against DEM runs.

    scripts/boundary_calibration_comparison.py --build build [--budget 200] [--seeds 3] [--figure F.png]
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

SCENE = "data/scenes/wave_strip.json"
FIXED_SCENE = "data/scenes/wave_strip_fixed.json"
SPACE = "data/spaces/ma2022_viscous_boundary.json"
# Populations of 20 let a 200-run budget see several generations; the annealing tries two moves at once (two
# cores) with its temperature scaled to a fitness of order 1 and steps of a tenth of each range.
SETTINGS = {"lhs-wca": ["population=20"], "wca": ["population=20"], "ga": ["population=20"],
            "sa": ["T0=0.05", "markov_chain_length=10", "step_scale=0.1", "parallel_trials=2"]}


def fail(message):
    print(f"boundary_calibration_comparison.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip().splitlines()[-1:]}")
    return done


def reference(bin_dir, out, cache):
    """The fixed far side's total recovery time (seed 1): the fitness's unit."""
    path = os.path.join(out, "fixed.json")
    if not os.path.exists(path):
        run([os.path.join(bin_dir, "demcal-dem"), "run", "--scene", FIXED_SCENE, "--seed", "1", "--cache", cache,
             "--quiet", "--out", path])
    result = json.load(open(path))
    if result.get("status") != "ok":
        fail(f"{path}: the fixed strip's run failed: {result.get('reason')}")
    return result["macro"]["total_recovery_time_s"]


def history(path):
    """(DEM runs, best fitness so far) of one optimiser run."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [(int(r["evaluations"]), float(r["best_objective"])) for r in rows]


def runs_to_within(points, fraction):
    best = points[-1][1]
    for evaluations, value in points:
        if value <= best * (1 + fraction):
            return evaluations
    return points[-1][0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", help="default: BUILD/boundary_calibration")
    parser.add_argument("--budget", type=int, default=200, help="DEM runs per optimiser run")
    parser.add_argument("--seeds", type=int, default=3, help="optimiser seeds per optimiser")
    parser.add_argument("--jobs", default="2")
    parser.add_argument("--figure", help="PNG of the best-so-far against DEM runs")
    args = parser.parse_args()
    if args.budget < 10 or args.seeds < 1:
        fail("--budget must be at least 10 and --seeds at least 1")
    bin_dir = os.path.join(args.build, "bin")
    out = args.out or os.path.join(args.build, "boundary_calibration")
    cache = os.path.join(args.build, "cache")
    os.makedirs(out, exist_ok=True)
    ref = reference(bin_dir, out, cache)
    print(f"fixed far side: total recovery time {ref:.3f} s (the fitness's unit)", flush=True)
    table = {}
    for algo, settings in SETTINGS.items():
        for seed in range(1, args.seeds + 1):
            name = f"{algo}_seed{seed}"
            solution, hist = os.path.join(out, name + ".json"), os.path.join(out, name + "_history.csv")
            if not (os.path.exists(solution) and os.path.exists(hist)):
                command = [os.path.join(bin_dir, "demcal-invert"), "--dem-scene", SCENE, "--space", SPACE,
                           "--target", f"total_recovery_time_s={ref!r}", "--objective", "minimise", "--algo", algo,
                           "--seed", str(seed), "--budget", str(args.budget), "--stop-below", "0", "--jobs",
                           args.jobs, "--cache", cache, "--quiet", "--out", solution, "--history", hist]
                for s in settings:
                    command += ["--set", s]
                started = datetime.datetime.now()
                run(command)
                print(f"{name}: {(datetime.datetime.now() - started).total_seconds():.0f} s", flush=True)
            points = history(hist)
            result = json.load(open(solution))
            table.setdefault(algo, []).append({"seed": seed, "best_s": points[-1][1] * ref, "runs": points[-1][0],
                                               "to_5pct": runs_to_within(points, 0.05), "x": result.get("x"),
                                               "points": points})
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    lines = [f"Measured {datetime.date.today()} at commit {commit or 'unknown'} on {os.cpu_count()} cores, "
             f"{platform.processor() or platform.machine()}, {platform.system()} {platform.release()}; "
             f"budget {args.budget} DEM runs, {args.seeds} optimiser seeds; fixed far side {ref:.3f} s.", "",
             "| optimiser | best total recovery s, median (range) | DEM runs to within 5 % of its best, median (range) | coefficients of the best run (xi_in, eta_in, xi_far, eta_far) |",
             "|---|---|---|---|"]
    for algo, rows in table.items():
        best = [r["best_s"] for r in rows]
        to5 = [r["to_5pct"] for r in rows]
        top = min(rows, key=lambda r: r["best_s"])
        x = top["x"] or {}
        coefficients = ", ".join(f"{x.get(k, float('nan')):.2f}"
                                 for k in ("xi_input", "eta_input", "xi_reflecting", "eta_reflecting"))
        lines.append(f"| {algo} | {statistics.median(best):.3f} ({min(best):.3f}-{max(best):.3f}) | "
                     f"{statistics.median(to5):.0f} ({min(to5)}-{max(to5)}) | {coefficients} |")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        for algo, rows in table.items():
            for k, r in enumerate(rows):
                e, v = zip(*r["points"])
                ax.step(e, [x * ref for x in v], where="post", lw=1, alpha=0.8, color=f"C{list(table).index(algo)}",
                        label=algo if k == 0 else None)
        ax.set_xlabel("DEM runs")
        ax.set_ylabel("best total recovery time so far, s")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.figure, dpi=110)


if __name__ == "__main__":
    main()
