#!/usr/bin/python3
"""The LAMMPS peer of `make bench` in 3D: the same packed sphere specimen, linear contact law, time step and steps
in LAMMPS and in demcal's 3D engine, one core each, back to back; then the cost of a step against the sphere count
on one and two threads, and the memory per sphere.

Each specimen (a box packed by demcal's 3D genesis to porosity 0.36, radii 1-1.5 mm, cached in BUILD/cache) is
written as a LAMMPS data file and run two ways: released (no walls: the packing's overlaps push the spheres apart,
many neighbour-list rebuilds) and in its box (six fixed planes: the packing stays nearly at rest, every contact
loaded). LAMMPS runs gran/hooke/history with no damping, nve/sphere and fix wall/gran for the box; demcal runs
bench_dem3d_released (PFC3D's linear model with the springs given: kn, ks, Coulomb friction, no damping). Same skin.
The kinetic energy histories say whether the two did the same work; the loop times give particle-steps per second
and their ratio. Each case runs --repeats times, the programs in turn; the table gives the median loop times and
the median of the paired ratios. Debian's lammps package is installed here on demand, never by `make test`.

    scripts/bench_lammps_3d.py [--build build] [--repeats 3] [--sizes 10000,100000] [--scaling 10000,50000,100000,200000]
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile

import debian_package

# Soft springs against the genesis overlaps (packed at 1 GPa, a few per cent of a radius): the released specimen
# expands at about a metre per second instead of exploding, so both programs rebuild their lists every few dozen
# steps, as a specimen released from a vessel does.
KN, KS, FRICTION = 1e4, 5e3, 0.5
DT_S, EVERY = 5e-6, 100
RADIUS_MIN, RADIUS_MAX, POROSITY = 1e-3, 1.5e-3, 0.36


def box_width_for(count):
    """The width W of a W x W x 2W box that genesis fills with about `count` spheres."""
    mean_cube = (RADIUS_MAX ** 4 - RADIUS_MIN ** 4) / (4 * (RADIUS_MAX - RADIUS_MIN))
    volume = count * 4.0 / 3.0 * math.pi * mean_cube / (1 - POROSITY)
    return round((volume / 2) ** (1 / 3), 5)


def specimen_args(count):
    w = box_width_for(count)
    return ["--vessel", "box", "--width", repr(w), "--depth", repr(w), "--height", repr(2 * w), "--radius-min",
            repr(RADIUS_MIN), "--radius-max", repr(RADIUS_MAX), "--porosity", repr(POROSITY), "--seed", "1"]


def steps_for(count):
    return max(1000, int(5e7 / count) // EVERY * EVERY)  # about 5e7 particle-steps per run


def run_ours(binary, count, cache, box, threads):
    command = [binary, *specimen_args(count), "--cache", cache, "--kn", repr(KN), "--ks", repr(KS), "--friction",
               repr(FRICTION), "--dt", repr(DT_S), "--steps", str(steps_for(count)), "--every", str(EVERY),
               "--threads", str(threads)]
    if box:
        command.append("--box")
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def lammps_input(data, ours, box, steps):
    lines = [
        "units si", "atom_style sphere", "boundary s s s", "comm_modify vel yes", f"read_data {data}",
        f"neighbor {ours['skin_m']!r} bin", "neigh_modify delay 0 every 1 check yes",
        f"pair_style gran/hooke/history {KN!r} {KS!r} 0 0 {FRICTION!r} 0", "pair_coeff * *", "fix 1 all nve/sphere",
    ]
    if box:
        wall = f"wall/gran hooke/history {KN!r} {KS!r} 0 0 {FRICTION!r} 0"
        lines += [f"fix 3 all {wall} xplane 0 {ours['width_m']!r}", f"fix 4 all {wall} yplane 0 {ours['depth_m']!r}",
                  f"fix 5 all {wall} zplane 0 {ours['height_m']!r}"]
    lines += [f"timestep {DT_S!r}", "compute ke all ke", "thermo_style custom step c_ke",
              "thermo_modify format float %.12g", f"thermo {EVERY}", f"run {steps}"]
    return "\n".join(lines) + "\n"


def run_lammps(workdir, data, ours, box, steps):
    script = os.path.join(workdir, "in.box" if box else "in.released")
    with open(script, "w") as f:
        f.write(lammps_input(data, ours, box, steps))
    out = subprocess.run(["lmp", "-in", script, "-log", "none"], check=True, capture_output=True, text=True,
                         cwd=workdir, env=dict(os.environ, OMP_NUM_THREADS="1")).stdout
    loop = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", out)
    if not loop:
        sys.exit("bench_lammps_3d: no loop time in LAMMPS's output:\n" + out[-2000:])
    history = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0].isdigit():
            try:
                history[int(parts[0])] = float(parts[1])
            except ValueError:
                pass
    return float(loop.group(1)), history


def energy_difference(ours, lammps_history, steps):
    """Largest |ours - LAMMPS| / LAMMPS of the translational kinetic energy, over the first quarter of the run and
    over all of it (the packings are chaotic: tiny differences of rounding grow late in the run)."""
    early, whole = 0.0, 0.0
    for step, translational, _ in ours["history"]:
        theirs = lammps_history.get(step)
        if theirs is None or theirs <= 0:
            continue
        d = abs(translational - theirs) / theirs
        whole = max(whole, d)
        if step <= steps // 4:
            early = max(early, d)
    return early, whole


def slope(points):
    """Least-squares slope of log(seconds per step) on log(spheres)."""
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = statistics.mean(xs), statistics.mean(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each program per case (median taken)")
    parser.add_argument("--sizes", default="10000,100000", help="sphere counts compared with LAMMPS")
    parser.add_argument("--scaling", default="10000,50000,100000,200000", help="sphere counts of the cost curve")
    args = parser.parse_args()
    if args.repeats < 1:
        sys.exit("bench_lammps_3d: --repeats must be at least 1")
    sizes = [int(v) for v in args.sizes.split(",") if v]
    scaling = [int(v) for v in args.scaling.split(",") if v]
    debian_package.ensure("lammps", "lmp", "bench_lammps_3d")
    binary = os.path.join(args.build, "bin", "bench_dem3d_released")
    cache = os.path.join(args.build, "cache")
    print(f"peer: LAMMPS {debian_package.version('lammps')}, gran/hooke/history, 3D; demcal's 3D linear model; "
          f"kn {KN:g} N/m, ks {KS:g} N/m, mu {FRICTION:g}, no damping, dt {DT_S:g} s, one core each unless said")
    for count in sorted(set(sizes + scaling)):  # pack first (cached), so no timing includes packing
        packed = json.loads(subprocess.run([binary, *specimen_args(count), "--cache", cache, "--pack-only"],
                                           check=True, capture_output=True, text=True).stdout)
        print(f"specimen ~{count}: {packed['spheres']} spheres, porosity {packed['porosity']:.4f}, "
              f"coordination {packed['coordination_number']:.2f}", flush=True)
    print(f"{'spheres':>8} {'case':<9} {'steps':>6} {'LAMMPS s':>9} {'M/s':>6} {'demcal s':>9} {'M/s':>6} {'ratio':>6} "
          f"{'2 thr s':>8} {'KE diff early/all':>18}")
    with tempfile.TemporaryDirectory() as workdir:
        for count in sizes:
            data = os.path.join(workdir, f"specimen_{count}.data")
            subprocess.run([binary, *specimen_args(count), "--cache", cache, "--lammps", data], check=True,
                           stdout=subprocess.DEVNULL)
            steps = steps_for(count)
            for box in (False, True):
                ours_s, ours2_s, lammps_runs = [], [], []
                for _ in range(args.repeats):
                    ours = run_ours(binary, count, cache, box, 1)
                    ours_s.append(ours["wall_s"])
                    lammps_runs.append(run_lammps(workdir, data, ours, box, steps))
                    ours2_s.append(run_ours(binary, count, cache, box, 2)["wall_s"])
                lammps_s = statistics.median(run[0] for run in lammps_runs)
                mine, mine2 = statistics.median(ours_s), statistics.median(ours2_s)
                ratio = statistics.median(run[0] / o for run, o in zip(lammps_runs, ours_s))
                early, whole = energy_difference(ours, lammps_runs[0][1], steps)
                n = ours["spheres"]
                print(f"{n:>8} {'box' if box else 'released':<9} {steps:>6} {lammps_s:>9.3f} "
                      f"{n * steps / lammps_s / 1e6:>6.2f} {mine:>9.3f} {n * steps / mine / 1e6:>6.2f} {ratio:>5.2f}x "
                      f"{mine2:>8.3f} {100 * early:>8.3f}% {100 * whole:>7.3f}%", flush=True)
    print(f"times: medians of {args.repeats} runs each; ratio: median over the runs of LAMMPS loop time / demcal loop "
          "time, one core each (> 1: demcal faster); 2 thr: demcal on two threads; KE diff: largest relative "
          "difference of the translational kinetic energy, first quarter / whole run")
    # Released, the rebuilds grow with the count (the fastest of more spheres is faster); in the box, with every
    # contact loaded and hardly a rebuild, the cost of the law and the sums alone.
    for box in (False, True):
        print()
        print(f"cost of a step against the sphere count ({'box' if box else 'released'}, demcal):")
        curves = {1: [], 2: []}
        for count in scaling:
            for threads in (1, 2):
                runs = [run_ours(binary, count, cache, box, threads) for _ in range(args.repeats)]
                per_step = statistics.median(r["wall_s"] / r["steps"] for r in runs)
                curves[threads].append((runs[0]["spheres"], per_step))
                memory = runs[0]["peak_rss_kib"] * 1024 / runs[0]["spheres"]
                print(f"{runs[0]['spheres']:>8} spheres  {threads} thread(s)  {1e3 * per_step:8.3f} ms/step  "
                      f"{runs[0]['spheres'] / per_step / 1e6:6.2f} M particle-steps/s  {runs[0]['rebuilds']:5d} rebuilds  "
                      f"peak memory {memory:6.0f} B/sphere", flush=True)
        for threads, points in curves.items():
            if len(points) > 1:
                print(f"slope of log(time per step) on log(spheres), {'box' if box else 'released'}, {threads} "
                      f"thread(s): {slope(points):.3f}")


if __name__ == "__main__":
    main()
