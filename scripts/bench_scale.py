#!/usr/bin/python3
"""Cost of one DEM step against the particle count (the scale measurement of docs/benchmarks.md).

The parallel-bonded UCS scene (data/scenes/ucs_rock_pb.json) on specimens of
the same 1:2 shape from about 2,400 to 100,000 disks, each loaded over about
5,000 steps of its elastic range (a strain limit scaled with the height), on
one thread and on all cores. Prints disks, steps, loading time, nanoseconds
per particle-step, peak memory (from /usr/bin/time's accounting of the run,
the specimen loaded from the cache) and the slope of log(cost per step)
against log(disks); writes a log-log figure when --figure is given.
Specimens are packed once (build/cache); a first run of the largest takes
minutes.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

SCALES = [1, 2, 4, 8, 20, 42]  # area over the 25 x 50 mm scene: about 2.4k ... 100k disks
BASE_WIDTH_M, BASE_HEIGHT_M, BASE_STRAIN = 0.025, 0.05, 2e-4


def run(binary, scene, cache, threads, workdir):
    out = os.path.join(workdir, "result.json")
    timing = subprocess.run(["/usr/bin/time", "-v", binary, "run", "--scene", scene, "--cache", cache, "--threads",
                             str(threads), "--quiet", "--out", out], capture_output=True, text=True)
    if timing.returncode != 0:
        sys.exit("bench_scale: the run failed:\n" + timing.stderr[-2000:])
    peak_kib = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", timing.stderr).group(1))
    with open(out) as f:
        result = json.load(f)
    return result, peak_kib


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--figure", help="log-log figure of the cost per step (.png)")
    parser.add_argument("--largest", type=int, default=len(SCALES), help="how many of the sizes to run")
    args = parser.parse_args()
    binary = os.path.abspath(os.path.join(args.build, "bin", "demcal-dem"))
    cache = os.path.abspath(os.path.join(args.build, "cache"))
    base = os.path.abspath("data/scenes/ucs_rock_pb.json")
    rows = []
    print(f"{'disks':>7} {'steps':>6} {'threads':>7} {'loading s':>9} {'us/step':>9} {'ns/particle-step':>16} "
          f"{'peak MiB':>8}", flush=True)
    with tempfile.TemporaryDirectory() as workdir:
        for k in SCALES[:args.largest]:
            side = math.sqrt(k)
            scene = os.path.join(workdir, f"scale_{k}.json")
            with open(scene, "w") as f:
                json.dump({"extends": base, "name": f"scale_{k}",
                           "specimen": {"width_m": BASE_WIDTH_M * side, "height_m": BASE_HEIGHT_M * side},
                           "loading": {"strain_limit": BASE_STRAIN / side, "record_strain": BASE_STRAIN / side / 10}},
                          f)
            run(binary, scene, cache, 0, workdir)  # packs (or loads) the specimen: not timed
            for threads in (1, 0):
                result, peak_kib = run(binary, scene, cache, threads, workdir)
                n, steps, loading_s = result["particles"], result["steps"], result["test_wall_s"]
                rows.append((n, steps, result.get("threads", 1), loading_s, peak_kib))
                print(f"{n:>7} {steps:>6} {result.get('threads', 1):>7} {loading_s:>9.2f} "
                      f"{1e6 * loading_s / steps:>9.1f} {1e9 * loading_s / (n * steps):>16.1f} {peak_kib / 1024:>8.1f}",
                      flush=True)
    for threads in sorted({r[2] for r in rows}):
        part = [r for r in rows if r[2] == threads]
        if len(part) >= 2:
            print(f"slope of log(cost per step) on log(disks), {threads} thread(s): "
                  f"{slope([r[0] for r in part], [r[3] / r[1] for r in part]):.3f}")
    one = [r for r in rows if r[2] == 1]
    if len(one) >= 2:
        per_disk = (one[-1][4] - one[0][4]) * 1024 / (one[-1][0] - one[0][0])
        print(f"memory: {per_disk:.0f} bytes per disk (peak resident set, largest against smallest run)")
    if args.figure:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5.5, 4))
        for threads in sorted({r[2] for r in rows}):
            part = [r for r in rows if r[2] == threads]
            ax.loglog([r[0] for r in part], [1e6 * r[3] / r[1] for r in part], "o-",
                      label=f"{threads} thread(s), slope {slope([r[0] for r in part], [r[3] / r[1] for r in part]):.2f}")
        xs = [r[0] for r in one]
        ax.loglog(xs, [1e6 * one[0][3] / one[0][1] * x / xs[0] for x in xs], "k:", label="slope 1")
        ax.set_xlabel("disks")
        ax.set_ylabel("wall time per step (us)")
        ax.set_title("Bonded UCS, cost of one step")
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.figure, dpi=90)
        print("figure: " + args.figure)


if __name__ == "__main__":
    main()
