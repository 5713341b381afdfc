#!/usr/bin/python3
"""The same parallel-bonded rock in 2D and in 3D: each dimension's shipped calibration pair (a UCS and a Brazilian
test per point: data/scenes/rock_pb_ucs_brazilian.json and rock_pb_ucs_brazilian_3d.json, with the same parameter
names) at the same micro-parameters (the scenes' defaults, or --set NAME=VALUE for both) over seeds 1..N. Prints a
Markdown table: sigma_u, E, nu, sigma_t and UCS/BTS, their mean and seed CV, and the wall time of a point (both
tests, specimens cached), for docs/explanation/lab_tests.md.

    scripts/compare_2d_3d.py --build build --seeds 5 --threads 2
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

SCENES = {"2D": "data/scenes/rock_pb_ucs_brazilian.json", "3D": "data/scenes/rock_pb_ucs_brazilian_3d.json"}
OUTPUTS = [("sigma_u_MPa", "sigma_u (MPa)"), ("E_GPa", "E (GPa)"), ("nu", "nu"), ("sigma_t_MPa", "sigma_t (MPa)")]


def run_point(binary, scene, seed, sets, threads, cache, workdir):
    out = os.path.join(workdir, f"{os.path.basename(scene)}.{seed}.json")
    command = [binary, "run", "--scene", scene, "--seed", str(seed), "--threads", str(threads), "--cache", cache,
               "--quiet", "--out", out]
    for s in sets:
        command += ["--set", s]
    subprocess.run(command, check=True)
    with open(out) as f:
        return json.load(f)


def macro(result, key):
    """A test list's result holds its tests' outputs together (a name two tests share gets the test's label)."""
    if key not in result.get("macro", {}):
        sys.exit(f"compare_2d_3d: no output {key} in the result (keys: {sorted(result.get('macro', {}))})")
    return result["macro"][key]


def summary(values):
    mean = statistics.mean(values)
    cv = 100 * statistics.stdev(values) / abs(mean) if len(values) > 1 else float("nan")
    return mean, cv


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--set", action="append", default=[], help="NAME=VALUE for both scenes")
    args = parser.parse_args()
    binary = os.path.join(args.build, "bin", "demcal-dem")
    cache = os.path.join(args.build, "cache")
    rows = {}
    with tempfile.TemporaryDirectory() as workdir:
        for dim, scene in SCENES.items():
            # A first run packs each seed's specimens into the cache; the timed runs below reuse them.
            for seed in range(1, args.seeds + 1):
                run_point(binary, scene, seed, args.set, args.threads, cache, workdir)
            results = [run_point(binary, scene, seed, args.set, args.threads, cache, workdir)
                       for seed in range(1, args.seeds + 1)]
            rows[dim] = results
    print(f"| output | 2D mean | 2D CV | 3D mean | 3D CV | 3D / 2D |")
    print("|---|---|---|---|---|---|")
    for key, name in OUTPUTS + [("ratio", "UCS/BTS")]:
        cells = []
        means = {}
        for dim in ("2D", "3D"):
            if key == "ratio":
                values = [macro(r, "sigma_u_MPa") / macro(r, "sigma_t_MPa") for r in rows[dim]]
            else:
                values = [macro(r, key) for r in rows[dim]]
            mean, cv = summary(values)
            means[dim] = mean
            cells += [f"{mean:.4g}", f"{cv:.1f} %"]
        print(f"| {name} | {cells[0]} | {cells[1]} | {cells[2]} | {cells[3]} | {means['3D'] / means['2D']:.2f} |")
    for dim in ("2D", "3D"):
        walls = [r["wall_s"] for r in rows[dim]]
        particles = [r.get("particles", 0) for r in rows[dim]]
        print(f"\n{dim}: {statistics.mean(walls):.1f} s a point on {args.threads} threads (both tests, cached specimens; "
              f"{min(walls):.1f}-{max(walls):.1f} s), particles per point {min(particles)}-{max(particles)}")


if __name__ == "__main__":
    main()
