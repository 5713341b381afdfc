#!/usr/bin/python3
"""The YADE peer of `make bench`: its CPM concrete in uniaxial compression
(scripts/yade_cpm_uniaxial.py) at two sizes against our parallel-bonded UCS
at similar particle counts, one thread each. A different model, and 3D
spheres (about 30 interactions each, as YADE counts them) against 2D disks
(a few bonds each), so the ratio is per particle-step of a bonded compression
test, not of equal work; the table says so. Debian's yade is installed here on demand, never by
`make test`.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import debian_package

YADE_SIZES = [(3000, 400), (12000, 100)]  # spheres asked, steps
OURS = [("data/scenes/ucs_rock_pb.json", "25 x 50 mm"), ("data/scenes/bench/ucs_pb_9k.json", "50 x 100 mm")]


def run_yade(spheres, steps, workdir):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "yade_cpm_uniaxial.py")
    out = subprocess.run(["yade", "-n", "-j1", "-x", script, str(spheres), str(steps)], capture_output=True,
                         text=True, cwd=workdir)
    for line in out.stdout.splitlines():
        if line.startswith("YADE_RESULT "):
            return json.loads(line[len("YADE_RESULT "):])
    sys.exit("bench_yade: YADE printed no result:\n" + (out.stdout + out.stderr)[-2000:])


def run_ours(binary, scene, cache, workdir):
    out = os.path.join(workdir, "ours.json")
    subprocess.run([binary, "run", "--scene", scene, "--cache", cache, "--threads", "1", "--quiet", "--out", out],
                   check=True)
    with open(out) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    args = parser.parse_args()
    debian_package.ensure("yade", "yade", "bench_yade")
    binary = os.path.join(args.build, "bin", "demcal-dem")
    cache = os.path.join(args.build, "cache")
    print(f"peer: YADE {debian_package.version('yade')}, CPM uniaxial compression of a prism "
          "(3D spheres); demcal: parallel-bonded UCS (2D disks); one thread each")
    print(f"{'YADE spheres':>12} {'steps':>6} {'interactions/sphere':>19} {'M/s':>7}   {'demcal disks':>12} {'steps':>6} "
          f"{'M/s':>7}   {'ratio per particle-step':>23}")
    with tempfile.TemporaryDirectory() as workdir:
        for (spheres, steps), (scene, _) in zip(YADE_SIZES, OURS):
            yade = run_yade(spheres, steps, workdir)
            ours = run_ours(binary, scene, cache, workdir)
            yade_rate = yade["spheres"] * yade["steps"] / yade["wall_s"]
            ours_rate = ours["particles"] * ours["steps"] / ours["test_wall_s"]
            print(f"{yade['spheres']:>12} {yade['steps']:>6} {2 * yade['interactions'] / yade['spheres']:>19.1f} "
                  f"{yade_rate / 1e6:>7.2f}   {ours['particles']:>12} {ours['steps']:>6} {ours_rate / 1e6:>7.2f}   "
                  f"{ours_rate / yade_rate:>22.1f}x")
    print("ratio: demcal particle-steps/s over YADE's (different models and dimensions: a per-particle figure only)")


if __name__ == "__main__":
    main()
