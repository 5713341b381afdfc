#!/usr/bin/python3
"""Faster platens while elastic (loading.elastic_speedup) against the constant-rate UCS (docs/benchmarks.md).

Runs a UCS scene over seeds 1..N at one platen speed and with the platens f times faster until the most loaded bond
carries a share u of its strength, at the scene's resolution and at a finer one (--finer: disk radii divided by that
factor), and prints per output: the constant-rate mean and seed standard deviation, the faster run's mean, the mean of
the paired differences and that mean as a share of the seed deviation; then the steps and loading wall times. An
output passes when its paired mean difference lies within the seed standard deviation (the goal "within the seed
scatter"); a paired mean difference significant at 95 % (|t| at or above the Student value for N-1 degrees of
freedom) is marked, since a shift far inside the scatter can still be systematic.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

from measured_on import commit, machine

OUTPUTS = ("sigma_u_MPa", "E_GPa", "E50_GPa", "nu", "nu50", "peak_strain")
T95 = {2: 12.71, 3: 4.30, 4: 3.18, 5: 2.78, 6: 2.57, 7: 2.45, 8: 2.36, 9: 2.31, 10: 2.26}  # two-sided, by N


def run(binary, scene, cache, seed, threads, out):
    done = subprocess.run([binary, "run", "--scene", scene, "--cache", cache, "--seed", str(seed), "--threads",
                           str(threads), "--quiet", "--out", out], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"speedup_check: {scene} seed {seed} failed:\n{done.stderr[-2000:]}")
    with open(out) as f:
        result = json.load(f)
    if result.get("status") != "ok":
        sys.exit(f"speedup_check: {scene} seed {seed}: {result.get('reason')}")
    return result


def compare(label, constant, fast):
    n = len(constant)
    print(f"\n{label}: {n} seeds")
    print(f"{'output':<12} {'constant':>10} {'seed sd':>9} {'faster':>10} {'paired diff':>11} {'diff/sd':>7} "
          f"{'t':>6}  verdict")
    passed = True
    for key in OUTPUTS:
        a = [r["macro"][key] for r in constant]
        b = [r["macro"][key] for r in fast]
        diffs = [y - x for x, y in zip(a, b)]
        sd = statistics.stdev(a)
        mean_diff = statistics.mean(diffs)
        diff_sd = statistics.stdev(diffs)
        t = mean_diff / (diff_sd / math.sqrt(n)) if diff_sd > 0 else (0.0 if mean_diff == 0 else math.inf)
        ok = abs(mean_diff) <= sd
        passed &= ok
        shift = " (a significant shift)" if abs(t) >= T95.get(n, 1.96) else ""
        print(f"{key:<12} {statistics.mean(a):>10.4g} {sd:>9.3g} {statistics.mean(b):>10.4g} {mean_diff:>+11.3g} "
              f"{mean_diff / sd:>+7.2f} {t:>+6.2f}  {'within' if ok else 'OUTSIDE'}{shift}")
    steps = [r["steps"] for r in constant], [r["steps"] for r in fast]
    walls = [r["test_wall_s"] for r in constant], [r["test_wall_s"] for r in fast]
    switch = [r["specimen"]["elastic_speedup_until_strain"] / r["macro"]["peak_strain"] for r in fast]
    print(f"steps: {statistics.mean(steps[0]):.0f} constant, {statistics.mean(steps[1]):.0f} faster "
          f"({statistics.mean(steps[1]) / statistics.mean(steps[0]):.3f}x); loading wall {statistics.mean(walls[0]):.2f} s "
          f"and {statistics.mean(walls[1]):.2f} s; the platens slowed at {min(switch):.2f}-{max(switch):.2f} of the "
          f"peak strain")
    return passed


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--scene", default="data/scenes/ucs_rock_pb.json")
    parser.add_argument("--speedup", type=float, default=4.0, help="loading.elastic_speedup f")
    parser.add_argument("--until", type=float, default=0.5, help="loading.speedup_until_utilisation u")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--finer", type=float, default=2.0,
                        help="the second resolution: radii divided by this (0: the scene's resolution only)")
    parser.add_argument("--threads", type=int, default=0, help="per run (0: all cores)")
    args = parser.parse_args()
    if not 2 <= args.seeds <= 10:
        sys.exit("speedup_check: --seeds must lie in [2, 10]")
    if args.finer and args.finer <= 1:
        sys.exit("speedup_check: --finer must be above 1 (or 0 for the scene's resolution only)")
    binary = os.path.abspath(os.path.join(args.build, "bin", "demcal-dem"))
    cache = os.path.abspath(os.path.join(args.build, "cache"))
    base = os.path.abspath(args.scene)
    print(f"speedup_check: {args.scene}, elastic_speedup {args.speedup:g}, speedup_until_utilisation {args.until:g}; "
          f"{machine()}; commit {commit()}", flush=True)
    passed = True
    with tempfile.TemporaryDirectory() as work:
        for factor in (1.0, args.finer) if args.finer else (1.0,):
            scenes = {}
            for name, loading in (("constant", {}),
                                  ("faster", {"elastic_speedup": args.speedup,
                                              "speedup_until_utilisation": args.until})):
                path = os.path.join(work, f"{name}_{factor:g}.json")
                scene = {"extends": base, "name": f"speedup_check_{name}", "loading": loading}
                if factor != 1.0:
                    with open(base) as f:
                        spec = json.load(f).get("specimen", {})
                    if "radius_min_m" not in spec or "radius_max_m" not in spec:
                        sys.exit(f"speedup_check: {args.scene} has no specimen radii of its own to divide")
                    scene["specimen"] = {"radius_min_m": spec["radius_min_m"] / factor,
                                         "radius_max_m": spec["radius_max_m"] / factor}
                with open(path, "w") as f:
                    json.dump(scene, f)
                scenes[name] = path
            results = {name: [] for name in scenes}
            for seed in range(1, args.seeds + 1):
                for name, path in scenes.items():
                    results[name].append(run(binary, path, cache, seed, args.threads, os.path.join(work, "out.json")))
                print(f"  radii / {factor:g}, seed {seed}: {results['constant'][-1]['particles']} disks", flush=True)
            passed &= compare(f"radii / {factor:g} ({results['constant'][0]['particles']} disks)",
                              results["constant"], results["faster"])
    print("\nall outputs within the seed scatter" if passed else "\nsome output lies OUTSIDE the seed scatter")
    return 0 if passed else 1


if __name__ == "__main__":
    sys.exit(main())
