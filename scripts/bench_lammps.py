#!/usr/bin/python3
"""The LAMMPS peer of `make bench`: the same packed specimen, contact law,
time step and steps in LAMMPS and in demcal, one core each, back to back.

Each scene's specimen is exported (`demcal-dem export --lammps`) and run two
ways: released (no walls: its locked-in overlaps push the disks apart, many
neighbour-list rebuilds) and in a box (four fixed walls: the packing stays
nearly at rest, every contact loaded). LAMMPS runs gran/hooke/history with
no damping, nve/sphere disc, enforce2d and fix wall/gran for the box; demcal
runs `demcal-dem released` (linear springs kn, ks, Coulomb friction, no
damping). Same skin. The kinetic energy histories say whether the two did the
same work; the loop times give particle-steps per second and their ratio.
Each case runs --repeats times, the two programs in turn (ours, LAMMPS, ours,
LAMMPS ...); the table gives the median loop time of each and the median of
the paired ratios: on a shared machine one run of each can put the ratio
anywhere within +-20 %.
Debian's lammps package is installed here on demand, never by `make test`.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import statistics
import tempfile

import debian_package

KN, KS, FRICTION = 1e8, 5e7, 0.5
DT_S, STEPS, EVERY = 5e-8, 20000, 100
SCENES = [("data/scenes/ucs_rock_pb.json", "25 x 50 mm"), ("data/scenes/bench/ucs_pb_9k.json", "50 x 100 mm")]


def lammps_input(data, ours, box):
    lines = [
        "units si", "dimension 2", "atom_style sphere", "boundary s s p", "comm_modify vel yes",
        f"read_data {data}",
        f"set group all density/disc {ours['density_kg_m3'] * ours['thickness_m']!r}",
        f"neighbor {ours['skin_m']!r} bin", "neigh_modify delay 0 every 1 check yes",
        f"pair_style gran/hooke/history {KN!r} {KS!r} 0 0 {FRICTION!r} 0", "pair_coeff * *",
        "fix 1 all nve/sphere disc", "fix 2 all enforce2d",
    ]
    if box:
        wall = f"wall/gran hooke/history {KN!r} {KS!r} 0 0 {FRICTION!r} 0"
        lines += [f"fix 3 all {wall} xplane 0 {ours['width_m']!r}", f"fix 4 all {wall} yplane 0 {ours['height_m']!r}"]
    lines += [f"timestep {DT_S!r}", "compute ke all ke", "thermo_style custom step c_ke",
              "thermo_modify format float %.12g", f"thermo {EVERY}", f"run {STEPS}"]
    return "\n".join(lines) + "\n"


def run_lammps(workdir, data, ours, box):
    script = os.path.join(workdir, "in.box" if box else "in.released")
    with open(script, "w") as f:
        f.write(lammps_input(data, ours, box))
    out = subprocess.run(["lmp", "-in", script, "-log", "none"], check=True, capture_output=True, text=True,
                         cwd=workdir).stdout
    loop = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", out)
    if not loop:
        sys.exit("bench_lammps: no loop time in LAMMPS's output:\n" + out[-2000:])
    history = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0].isdigit():
            try:
                history[int(parts[0])] = float(parts[1])
            except ValueError:
                pass
    neighbours = re.search(r"Ave neighs/atom = ([0-9.]+)", out)
    return float(loop.group(1)), history, float(neighbours.group(1)) if neighbours else float("nan")


def run_ours(binary, scene, cache, box, threads):
    command = [binary, "released", "--scene", scene, "--cache", cache, "--kn", repr(KN), "--ks", repr(KS),
               "--friction", repr(FRICTION), "--dt", repr(DT_S), "--steps", str(STEPS), "--every", str(EVERY),
               "--threads", str(threads)]
    if box:
        command.append("--box")
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def energy_difference(ours, lammps_history):
    """Largest |ours - LAMMPS| / LAMMPS of the translational kinetic energy,
    over the first quarter of the run and over all of it (the packings are
    chaotic: tiny differences of rounding grow late in the run)."""
    early, whole = 0.0, 0.0
    for step, translational, _ in ours["history"]:
        theirs = lammps_history.get(step)
        if theirs is None or theirs <= 0:
            continue
        d = abs(translational - theirs) / theirs
        whole = max(whole, d)
        if step <= STEPS // 4:
            early = max(early, d)
    return early, whole


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each program per case (median taken)")
    args = parser.parse_args()
    if args.repeats < 1:
        sys.exit("bench_lammps: --repeats must be at least 1")
    debian_package.ensure("lammps", "lmp", "bench_lammps")
    binary = os.path.join(args.build, "bin", "demcal-dem")
    cache = os.path.join(args.build, "cache")
    version = "LAMMPS " + debian_package.version("lammps")
    print(f"peer: {version}, gran/hooke/history, 2D; demcal linear springs; kn {KN:g} N/m, ks {KS:g} N/m, "
          f"mu {FRICTION:g}, no damping, dt {DT_S:g} s, {STEPS} steps, one core each unless said")
    print(f"{'specimen':<24} {'case':<9} {'disks':>6} {'LAMMPS s':>9} {'M/s':>6} {'demcal s':>9} {'M/s':>6} "
          f"{'ratio':>6} {'2 thr s':>8} {'KE diff early/all':>18} {'neigh/atom':>10}")
    with tempfile.TemporaryDirectory() as workdir:
        for scene, label in SCENES:
            data = os.path.join(workdir, os.path.basename(scene) + ".data")
            subprocess.run([binary, "export", "--scene", scene, "--cache", cache, "--lammps", data], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            for box in (False, True):
                ours_s, ours2_s, lammps_runs = [], [], []
                for _ in range(args.repeats):
                    ours = run_ours(binary, scene, cache, box, 1)
                    ours_s.append(ours["wall_s"])
                    lammps_runs.append(run_lammps(workdir, data, ours, box))
                    ours2_s.append(run_ours(binary, scene, cache, box, 2)["wall_s"])
                lammps_s = statistics.median(run[0] for run in lammps_runs)
                _, history, neighbours = lammps_runs[0]
                mine, mine2 = statistics.median(ours_s), statistics.median(ours2_s)
                # Paired: each LAMMPS run against the demcal run just before it.
                ratio = statistics.median(run[0] / o for run, o in zip(lammps_runs, ours_s))
                early, whole = energy_difference(ours, history)
                n = ours["disks"]
                print(f"{label:<24} {'box' if box else 'released':<9} {n:>6} {lammps_s:>9.3f} "
                      f"{n * STEPS / lammps_s / 1e6:>6.1f} {mine:>9.3f} {n * STEPS / mine / 1e6:>6.1f} "
                      f"{ratio:>5.2f}x {mine2:>8.3f} "
                      f"{100 * early:>8.3f}% {100 * whole:>7.3f}% {neighbours:>10.2f}", flush=True)
    print(f"times: medians of {args.repeats} runs each; ratio: median over the runs of LAMMPS loop time / demcal "
          "loop time, one core each (> 1: demcal faster); 2 thr: demcal on two threads; KE diff: largest relative "
          "difference of the translational kinetic energy, first quarter / whole run")


if __name__ == "__main__":
    main()
