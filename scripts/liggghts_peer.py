#!/usr/bin/python3
"""Our 3D DEM against LIGGGHTS on the same rotating drum: data/scenes/drum_spheres_3d.json in demcal-dem and, through
data/external/liggghts/liggghts_drum.json, in Debian's LIGGGHTS 3.8 (installed on demand), over several seeds at the
scene's defaults, one process and one thread each. Writes OUT/summary.md: per code the dynamic angle's mean over the
seeds with its 95 % interval (Student's t), the samples' SD, the particles and steps, the wall time of a run and
the particle-steps per second (whole run; for LIGGGHTS also its own loop time), and the speed ratio. Runs are kept
in OUT (rerunning reuses every finished one). Time runs on a quiet machine: a busy core makes both slower, unevenly.

    scripts/liggghts_peer.py --build build [--seeds 5] [--out build/liggghts_peer] [--only angles|speed]
"""
import argparse
import datetime
import json
import math
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "python"))
import debian_package  # noqa: E402
from measured_on import commit, machine  # noqa: E402
from demcal_study.trust_region import t975  # noqa: E402

OURS = "data/scenes/drum_spheres_3d.json"
THEIRS = "data/external/liggghts/liggghts_drum.json"


def run_once(binary, scene, seed, out_json, work=None):
    """A finished run's result (reused when its file says ok or failed), else a fresh run's."""
    if os.path.exists(out_json):
        with open(out_json) as f:
            return json.load(f)
    command = [binary, "run", "--scene", scene, "--seed", str(seed), "--threads", "1", "--out", out_json + ".part"]
    if work:
        command += ["--work", work]
    print(" ".join(command), file=sys.stderr, flush=True)
    subprocess.run(command, check=False, stdout=subprocess.DEVNULL)
    if not os.path.exists(out_json + ".part"):
        sys.exit(f"liggghts_peer: {' '.join(command)} wrote no result")
    os.replace(out_json + ".part", out_json)
    with open(out_json) as f:
        return json.load(f)


def angle_and_cost(result, external):
    """(angle, samples' SD, particles, steps, wall_s, particle-steps per wall second, loop-only rate or None)."""
    if result["status"] != "ok":
        return None
    if external:
        x = result["extra_outputs"]
        rate = x["particle_steps"] / x["wall_s"]
        return (result["macro"]["aor_deg"], result["macro"]["aor_sd_deg"], int(x["particles"]), int(x["steps"]),
                x["wall_s"], rate, x["particle_steps_per_s"])
    particle_steps = result["particles"] * result["steps"]
    return (result["macro"]["aor_deg"], result["macro"]["aor_sd_deg"], result["particles"], result["steps"],
            result["wall_s"], particle_steps / result["wall_s"], None)


def interval(values):
    """(mean, 95 % half-width by Student's t, SD) over the seeds."""
    mean = statistics.fmean(values)
    if len(values) < 2:
        return mean, math.nan, math.nan
    sd = statistics.stdev(values)
    return mean, t975(len(values) - 1) * sd / math.sqrt(len(values)), sd


def summary(rows, seeds, out_dir):
    lines = [f"Measured {datetime.date.today().isoformat()} at commit {commit()} on {machine()}; "
             f"LIGGGHTS {debian_package.version('liggghts')}; "
             f"{OURS} at its defaults, seeds 1-{seeds}, one process and one thread each.", "",
             "| code | runs ok | aor_deg, mean (95 % interval) | SD over seeds | samples' SD, mean | particles | steps | "
             "wall s per run | particle-steps/s (whole run) | particle-steps/s (LIGGGHTS' loop) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    rates = {}
    for code, measured, failed in rows:
        if not measured:
            lines.append(f"| {code} | 0 of {len(measured) + len(failed)} | | | | | | | | |")
            continue
        mean, half, sd = interval([m[0] for m in measured])
        rate = statistics.fmean(m[5] for m in measured)
        rates[code] = rate
        loop = [m[6] for m in measured if m[6]]
        loop_rate = f"{statistics.fmean(loop) / 1e6:.2f} M" if loop else ""
        lines.append(
            f"| {code} | {len(measured)} of {len(measured) + len(failed)} | "
            f"{mean:.2f} ({mean - half:.2f}-{mean + half:.2f}) | {sd:.2f} | "
            f"{statistics.fmean(m[1] for m in measured):.2f} | {statistics.fmean(m[2] for m in measured):.0f} | "
            f"{statistics.fmean(m[3] for m in measured):.0f} | {statistics.fmean(m[4] for m in measured):.1f} | "
            f"{rate / 1e6:.2f} M | {loop_rate} |")
        for seed, reason in failed:
            lines.append(f"|  | seed {seed} failed: {reason} | | | | | | | | |")
    if len(rates) == 2 and all(rates.values()):
        lines += ["", f"Ours over LIGGGHTS per particle-step (whole runs): **{rates['demcal'] / rates['LIGGGHTS']:.2f}x**."]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "summary.md"), "w") as f:
        f.write(text)
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--out", default=None)
    parser.add_argument("--only", choices=["demcal", "liggghts"], help="run one code only (the other's runs are still summarised)")
    args = parser.parse_args()
    if args.seeds < 1:
        sys.exit("liggghts_peer: --seeds must be at least 1")
    binary = os.path.join(args.build, "bin", "demcal-dem")
    if not os.path.exists(binary):
        sys.exit(f"liggghts_peer: {binary} is missing; build first (make build)")
    out_dir = args.out or os.path.join(args.build, "liggghts_peer")
    os.makedirs(out_dir, exist_ok=True)
    if args.only != "demcal":
        debian_package.ensure("liggghts", "liggghts", "liggghts_peer")
    rows = []
    for code, scene, external in (("demcal", OURS, False), ("LIGGGHTS", THEIRS, True)):
        measured, failed = [], []
        for seed in range(1, args.seeds + 1):
            out_json = os.path.join(out_dir, f"{code.lower()}_seed{seed}.json")
            if args.only and args.only != code.lower() and not os.path.exists(out_json):
                continue
            work = os.path.join(out_dir, f"{code.lower()}_seed{seed}") if external else None
            result = run_once(binary, scene, seed, out_json, work)
            m = angle_and_cost(result, external)
            if m:
                measured.append(m)
            else:
                failed.append((seed, result.get("reason", "")))
        rows.append((code, measured, failed))
    print(summary(rows, args.seeds, out_dir), end="")


if __name__ == "__main__":
    main()
