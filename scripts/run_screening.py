#!/usr/bin/python3
"""Runs a screening study file: design (demcal-doe), DEM batch (demcal-dem, resumable),
range analysis and ANOVA (demcal-analyze) with main-effects and Pareto plots.

    /usr/bin/python3 scripts/run_screening.py data/studies/concrete_screening.json [--build build] [--jobs 2]

The batch and its HDF5 responses live in BUILD/studies/NAME/ (rerunning resumes it); the
results the study names (CSV of design + responses, Markdown tables, PNGs, summary) go to
its "results" folder.
"""
import argparse
import json
import os
import subprocess
import sys
import time

from study import analyze_screening


def fail(message):
    print(f"run_screening.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def run(command):
    print("+ " + " ".join(command), flush=True)
    code = subprocess.run(command).returncode
    return code


parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("study")
parser.add_argument("--build", default="build")
parser.add_argument("--jobs", default=str(os.cpu_count() or 2))
args = parser.parse_args()
try:
    study = json.load(open(args.study))
except (OSError, ValueError) as e:
    fail(f"cannot read {args.study}: {e}")
allowed = {"name", "description", "scene", "space", "design", "seeds", "responses", "results"}
unknown = set(study) - allowed
if unknown:
    fail(f"{args.study}: unknown field(s) {', '.join(sorted(unknown))} (allowed: {', '.join(sorted(allowed))})")
for key in ("name", "scene", "space", "design", "responses", "results"):
    if key not in study:
        fail(f"{args.study}: missing \"{key}\"")
design_spec = study["design"]
if design_spec.get("kind") != "oa":
    fail(f"{args.study}: design.kind must be \"oa\" for a screening (range analysis and ANOVA need an orthogonal plan)")

bin_dir = os.path.join(args.build, "bin")
work = os.path.join(args.build, "studies", study["name"])
results = study["results"]
os.makedirs(work, exist_ok=True)
os.makedirs(results, exist_ok=True)
start = time.time()

design = os.path.join(work, "design.csv")
if run([os.path.join(bin_dir, "demcal-doe"), "oa", "--space", study["space"], "--runs", str(design_spec["runs"]),
        "--blank", str(design_spec.get("blank", 0)), "--out", design, "--quiet"]) != 0:
    fail("the design could not be made")
responses_h5 = os.path.join(work, "responses.h5")
responses_csv = os.path.join(work, "responses.csv")
points_dir = responses_h5 + ".points"
done_before = len(os.listdir(points_dir)) if os.path.isdir(points_dir) else 0
batch_start = time.time()
code = run([os.path.join(bin_dir, "demcal-dem"), "batch", "--scene", study["scene"], "--design", design, "--out",
            responses_h5, "--csv", responses_csv, "--seeds", str(study.get("seeds", 1)), "--jobs", args.jobs,
            "--cache", os.path.join(args.build, "cache")])
batch_wall = time.time() - batch_start
# The wall time of the batch runs that did work, kept across resumed runs.
times_path = os.path.join(work, "batch_wall_s.json")
times = json.load(open(times_path)) if os.path.exists(times_path) else []
if len(os.listdir(points_dir)) > done_before:
    times.append(batch_wall)
    json.dump(times, open(times_path, "w"))
batch_wall = sum(times)
if code not in (0, 4):
    fail(f"the DEM batch stopped (exit code {code}); rerun to resume")

# The analysis a study's screening stage makes (scripts/study.py), with every DEM output in the table.
os.environ["BIN"] = bin_dir
factors = [p["name"] for p in json.load(open(study["space"]))["parameters"]]
failed = analyze_screening(design, responses_csv, factors, list(study["responses"]), results, extra_outputs=True)
with open(design) as f:
    design_points = sum(1 for _ in f) - 1

anova = json.load(open(os.path.join(results, "anova.json")))
with open(os.path.join(results, "summary.md"), "w") as f:
    f.write(f"# {study['name']}\n\n{study.get('description', '')}\n\n")
    f.write(f"Study file `{args.study}`; scene `{study['scene']}`; {design_points} design points x "
            f"{study.get('seeds', 1)} seed(s).\n\n")
    f.write(f"DEM batch wall time: {batch_wall:.0f} s ({batch_wall / 60:.1f} min) on {args.jobs} parallel jobs, "
            f"summed over the {len(times)} run(s) of the batch that computed points (a resumed batch repeats none).\n\n")
    f.write(f"Failed points: {len(failed)}" + ("".join(f"\n- run {r}: {s}" for r, s in failed)) + "\n\n")
    f.write("| response | significant at p < 0.01 (**) or p < 0.05 (*), by F |\n|---|---|\n")
    for response, rows in anova.items():
        marks = [(row.get("F") or 0, name + row["significance"]) for name, row in rows.items()
                 if name != "error" and row.get("significance")]
        f.write(f"| {response} | {', '.join(m for _, m in sorted(marks, reverse=True)) or 'none'} |\n")
print(f"results in {results}/ (screening.csv, range.md, anova.md, main_effects_*.png, pareto_*.png, summary.md)")
