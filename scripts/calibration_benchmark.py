#!/usr/bin/python3
"""The calibration benchmark (docs/explanation/calibration_benchmark.md): every target of data/benchmarks/calibration_targets.json
calibrated with `make calibrate`'s command and the same settings, then, for the targets marked global_strategy, the
old strategy (one global screening + Box-Behnken surface, data/studies/rock_response_surface.json with the target
swapped in) side by side. It runs for hours: each target is resumable, finished ones are skipped, and --only runs a
part. The summary (a Markdown table with the machine, the date and the commit) goes to
BUILD/calibration_benchmark/summary.md.

    scripts/calibration_benchmark.py [--build build] [--jobs 2] [--only NAME,NAME] [--global] [--kriging]
                                     [--summary-only]

--kriging also runs `calibrate --strategy kriging` on the targets marked global_strategy (stored as NAME_kriging), so
the three strategies meet on the same targets.
"""
import argparse
import json
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))

from demcal_study.cost import study_cost  # noqa: E402
from demcal_study.errors import StudyError, load_json  # noqa: E402
from measured_on import commit, machine  # noqa: E402 (scripts/, the script's own folder)

TARGETS = os.path.join(REPO, "data", "benchmarks", "calibration_targets.json")
GLOBAL_TEMPLATE = os.path.join(REPO, "data", "studies", "rock_response_surface.json")


def environment(build, jobs):
    return dict(os.environ, BIN=os.path.join(build, "bin"), JOBS=str(jobs), CACHE=os.path.join(build, "cache"),
                PYTHONPATH=os.path.join(REPO, "python"))


def stored_name(entry, strategy):
    """Where a target's calibration is stored: its name, suffixed by any strategy but the default."""
    return entry["name"] + ("" if strategy == "trust-region" else "_" + strategy)


def run_target(entry, settings, build, jobs, out_root, strategy="trust-region"):
    name = stored_name(entry, strategy)
    cmd = ["/usr/bin/python3", "-m", "demcal_study", "calibrate", "--scene", entry["scene"], "--name", name,
           "--tolerance", str(settings["tolerance"]), "--budget", str(settings["budget"]), "--out-root", out_root,
           "--strategy", strategy]
    for k, v in entry["targets"].items():
        cmd += ["--target", f"{k}={v}"]
    print(f"== {name}: {' '.join(cmd[3:])}", flush=True)
    code = subprocess.run(cmd, cwd=REPO, env=environment(build, jobs)).returncode
    if code not in (0, 3, 4):
        raise SystemExit(f"calibration_benchmark: {name}: calibrate failed (exit {code})")


def run_global(entry, settings, build, jobs, out_root):
    """The old strategy, as the README's rock study ran it, on this target and the benchmark's tolerance."""
    study = load_json(GLOBAL_TEMPLATE, "study")
    study["name"] = f"global_{entry['name']}"
    study["targets"] = entry["targets"]
    study["screening"]["outputs"] = sorted(entry["targets"])
    study["surfaces"][0]["outputs"] = sorted(entry["targets"])
    study["verification"] = {"seeds": 5, "max_seeds": 5, "tolerance": settings["tolerance"]}
    study["description"] = (f"The global-surface strategy of rock_response_surface.json on the {entry['name']} "
                            "targets of the calibration benchmark (5-seed verification, as it ran before).")
    folder = os.path.join(out_root, "studies")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"global_{entry['name']}.json")
    with open(path, "w") as f:
        json.dump(study, f, indent=1)
    print(f"== global strategy on {entry['name']}", flush=True)
    code = subprocess.run([os.path.join(REPO, "scripts", "run_study.sh"), path, build, str(jobs), "quiet"], cwd=REPO,
                          env=environment(build, jobs)).returncode
    if code != 0:
        print(f"calibration_benchmark: the global study on {entry['name']} stopped (exit {code})", file=sys.stderr)


def calibration_table(entries, out_root, strategy):
    lines = ["| target | status | DEM runs | wall min | verified error % (95 % half-width %) | scale factor |",
             "|---|---|---|---|---|---|"]
    for entry in entries:
        path = os.path.join(out_root, stored_name(entry, strategy), "solution.json")
        if not os.path.exists(path):
            lines.append(f"| {entry['name']} | not run | | | | |")
            continue
        s = load_json(path, "calibration solution")
        errors = "-"
        if s.get("verifications"):
            v = s["verifications"][-1]
            errors = ", ".join(f"{o} {v['errors_pct'][o]:+.1f} ({v['half_width_pct'][o]:.1f})" for o in sorted(v["errors_pct"]))
        wall = s.get("wall_s_total", s.get("wall_s", 0)) / 60
        scale = f"{s['scale_factor']:.3g}" if "scale_factor" in s else "-"
        lines.append(f"| {entry['name']} | {s['status']} | {s['dem_runs']} | {wall:.1f} | {errors} | {scale} |")
    return lines


def summary(config, build, out_root):
    lines = [f"Measured {time.strftime('%Y-%m-%d')} at commit {commit()} on {machine()}; "
             f"tolerance {100 * config['settings']['tolerance']:g} %, budget {config['settings']['budget']} DEM runs.",
             ""] + calibration_table(config["targets"], out_root, "trust-region")
    marked = [e for e in config["targets"] if e.get("global_strategy")]
    if any(os.path.exists(os.path.join(out_root, stored_name(e, "kriging"), "solution.json")) for e in marked):
        lines += ["", "The kriging strategy (`calibrate --strategy kriging`) on the targets marked global_strategy:", ""]
        lines += calibration_table(marked, out_root, "kriging")
    rows = []
    for entry in config["targets"]:
        out = os.path.join(build, "studies", f"global_{entry['name']}")
        if entry.get("global_strategy") and os.path.exists(os.path.join(out, "refined.json")):
            try:
                c = study_cost(out)
            except StudyError:
                continue
            wall = "-" if c["wall_s"] is None else f"{c['wall_s'] / 60:.1f}"
            rows.append(f"| {entry['name']} | {'passed' if c['passed'] else 'failed'} | {c['dem_runs']} | {wall} | "
                        f"{c['max_error_pct']:.1f} |")
    if rows:
        lines += ["", "The old global-surface strategy (L27 screening, Box-Behnken, quadratic surfaces, GA, 5-seed "
                  "verification, up to 3 refinement rounds):", "",
                  "| target | final verification | DEM runs | wall min | largest verified error % |", "|---|---|---|---|---|"]
        lines += rows
    text = "\n".join(lines) + "\n"
    os.makedirs(out_root, exist_ok=True)
    with open(os.path.join(out_root, "summary.md"), "w") as f:
        f.write(text)
    print(text)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default="build")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--only", help="comma-separated target names")
    p.add_argument("--global", dest="with_global", action="store_true", help="also the old strategy where marked")
    p.add_argument("--kriging", action="store_true", help="also calibrate --strategy kriging where marked")
    p.add_argument("--summary-only", action="store_true")
    args = p.parse_args()
    config = load_json(TARGETS, "benchmark targets")
    names = [t["name"] for t in config["targets"]]
    only = args.only.split(",") if args.only else names
    unknown = sorted(set(only) - set(names))
    if unknown:
        raise SystemExit(f"calibration_benchmark: --only: unknown target(s) {', '.join(unknown)} (known: {', '.join(names)})")
    build = os.path.abspath(args.build)
    out_root = os.path.join(build, "calibration_benchmark")
    if not args.summary_only:
        for entry in config["targets"]:
            if entry["name"] in only:
                run_target(entry, config["settings"], build, args.jobs, out_root)
        if args.kriging:
            for entry in config["targets"]:
                if entry["name"] in only and entry.get("global_strategy"):
                    run_target(entry, config["settings"], build, args.jobs, out_root, "kriging")
        if args.with_global:
            for entry in config["targets"]:
                if entry["name"] in only and entry.get("global_strategy"):
                    run_global(entry, config["settings"], build, args.jobs, out_root)
    summary(config, build, out_root)


if __name__ == "__main__":
    main()
