#!/usr/bin/python3
"""The Bayesian search checked on rocks whose answer is known (make uncertainty-benchmark): ROCKS synthetic rocks
made by our own DEM at parameter sets drawn from the prior (a Latin hypercube over the space's coded box), each
target the mean of 8 seeds at the truth with their SD and n = 8, calibrated with `STRATEGY=bayes`. The summary
says how often each identified parameter's 90 % credible interval holds the truth (simulation-based calibration),
the intervals' widths against the prior's, the DEM runs each calibration used, and whether the posterior
predictive's 95 % interval of a 5-specimen mean holds the mean of 5 fresh seeds at the truth.

    scripts/uncertainty_benchmark.py --build build --out build/uncertainty_benchmark [--rocks 20] [--jobs 2]

Resumable: every DEM batch and calibration is stored under OUT and a rerun repeats none. Summary: OUT/summary.md
and OUT/summary.json."""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "python"))

from demcal_study.calibrate_runs import one_point_batch  # noqa: E402
from demcal_study.calibration_problem import Problem  # noqa: E402
from demcal_study.commands import Tools  # noqa: E402
from demcal_study.errors import StudyError, load_json  # noqa: E402
from demcal_study.point_results import read_point_result  # noqa: E402
from demcal_study.searches.bayes_search import global_design  # noqa: E402

TARGETS = ("E_GPa", "nu", "sigma_u_MPa")
TRUTH_SEEDS = (1001, 8)    # first seed, count: the lab's specimens at the truth
FRESH_SEEDS = (2001, 5)    # the 5-specimen mean the predictive is checked against
# The small specimen (the space's largest R_min) and the parameters held: the four searched are the ones a UCS
# with E, nu and sigma_u can speak to (the bond strengths' scatter and the friction are held at the space's
# references, as the Lac du Bonnet example does).
DEFAULT_SPACE = {
    "description": "The synthetic-rock benchmark's prior: Wang & Cao 2017's contact-bond ranges "
                   "(data/spaces/wang2017_rock_cb.json) for Ec, kn/ks and the two bond strengths; the rest held.",
    "parameters": [], "fixed": {}}
SEARCHED = ("Ec_Pa", "kn_ks", "cb_sigma_c_mean_Pa", "cb_tau_c_mean_Pa")


def benchmark_space(shipped):
    """The shipped space's four searched parameters with their ranges; the others fixed at their references, the
    radius at its high end (the smallest specimen the space allows)."""
    space = json.loads(json.dumps(DEFAULT_SPACE))
    for p in shipped["parameters"]:
        if p["name"] in SEARCHED:
            space["parameters"].append(p)
        else:
            space["fixed"][p["name"]] = p["high"] if p["name"] == "R_min_m" else p["reference"]
    missing = set(SEARCHED) - {p["name"] for p in space["parameters"]}
    if missing:
        sys.exit(f"uncertainty_benchmark: the space lacks {', '.join(sorted(missing))}")
    return space


def truths(problem, rocks, seed):
    """`rocks` parameter sets from a Latin hypercube over the coded box (the prior), decoded: [{name: value}]."""
    u = global_design(len(problem.coordinates), rocks, seed)
    return [{c.name: float(c.decode(x)) for c, x in zip(problem.coordinates, row)} for row in u]


def run_truth(build, scene, values, fixed, first_seed, count, folder, jobs):
    """The scene at `values` (with `fixed`) on seeds first_seed.., a resumable demcal-dem batch: the macro
    outputs of each seed that ran."""
    tools = Tools(bin=os.path.join(build, "bin"), jobs=str(jobs), cache=os.path.join(build, "cache"), python="")
    try:
        one_point_batch(tools, scene, folder, dict(fixed, **values), first_seed, count, quiet=True)
    except StudyError as e:
        sys.exit(f"uncertainty_benchmark: {e}")
    return read_macros(folder, first_seed, count)


def read_macros(folder, first_seed, count):
    """The macro outputs of the seeds of a stored batch (one_point_batch's folder) that ran."""
    macros = []
    for seed in range(first_seed, first_seed + count):
        r = read_point_result(os.path.join(folder, "responses.h5"), seed)
        if r is not None and r.get("status") == "ok":
            macros.append(r["macro"])
    return macros


def calibration_files(cal):
    """(posterior, predictive or None, solution) of a finished calibration's folder."""
    predictive = os.path.join(cal, "predictive.json")
    return (load_json(os.path.join(cal, "posterior.json"), "posterior"),
            load_json(predictive, "predictive") if os.path.exists(predictive) else None,
            load_json(os.path.join(cal, "solution.json"), "solution"))


def lab_targets(macros):
    """NAME=MEAN+-SD/n=N of each target output over the specimens that gave it."""
    out = []
    for name in TARGETS:
        x = np.array([m[name] for m in macros if isinstance(m.get(name), (int, float)) and math.isfinite(m[name])])
        if len(x) < 2:
            return None
        out.append(f"{name}={x.mean()!r}+-{x.std(ddof=1)!r}/n={len(x)}")
    return out


def rock_result(truth, posterior, predictive, solution, fresh):
    """One rock's row: per parameter whether its 90 % interval holds the truth (identified ones count), the coded
    width against the prior's 2; per target whether the predictive's interval over the posterior holds the fresh
    seeds' mean at the truth; and per output of every test whether the interval at the exported point holds the
    first verification's mean there (the calibration's own check, `inside` in predictive.json)."""
    row = {"status": solution["status"], "dem_runs": solution["dem_runs"], "parameters": {}, "predictive": {},
           "exported": {}}
    for name, r in (predictive or {}).get("outputs", {}).items():
        if isinstance(r.get("inside"), bool):
            row["exported"][name] = {"verified_mean": r.get("verified_mean"), "interval_95": r["exported"]["interval_95"],
                                     "inside": r["inside"], "targeted": r.get("target") is not None}
    for name, value in truth.items():
        p = posterior["parameters"][name]
        lo, hi = p["credible_90"]
        row["parameters"][name] = {"truth": value, "identified": p["identified"], "inside": bool(lo <= value <= hi),
                                   "width_of_prior": p["coded_width"] / 2.0}
    for name in TARGETS:
        x = [m[name] for m in fresh if isinstance(m.get(name), (int, float))]
        r = (predictive or {}).get("outputs", {}).get(name)
        if r is None or len(x) != FRESH_SEEDS[1]:
            continue
        lo, hi = r["posterior"]["interval_95"]
        mean = float(np.mean(x))
        row["predictive"][name] = {"fresh_mean": mean, "interval_95": [lo, hi], "inside": bool(lo <= mean <= hi)}
    return row


def summary(rows):
    """Coverage of the identified parameters' 90 % intervals (all and per parameter), widths, runs, predictive."""
    held = [p["inside"] for r in rows for p in r["parameters"].values() if p["identified"]]
    per = {}
    for r in rows:
        for name, p in r["parameters"].items():
            e = per.setdefault(name, {"identified": 0, "inside": 0, "widths": []})
            e["widths"].append(p["width_of_prior"])
            if p["identified"]:
                e["identified"] += 1
                e["inside"] += int(p["inside"])
    predictive = [q["inside"] for r in rows for q in r["predictive"].values()]
    exported = [q for r in rows for q in r.get("exported", {}).values()]
    exported_targets = [q["inside"] for q in exported if q["targeted"]]
    runs = [r["dem_runs"] for r in rows]
    return {"rocks": len(rows),
            "coverage_identified": float(np.mean(held)) if held else None, "identified_intervals": len(held),
            "per_parameter": {n: {"identified": e["identified"], "inside": e["inside"],
                                  "median_width_of_prior": float(np.median(e["widths"]))} for n, e in per.items()},
            "dem_runs_median": float(np.median(runs)) if runs else None, "dem_runs_max": max(runs) if runs else None,
            "predictive_inside": float(np.mean(predictive)) if predictive else None,
            "predictive_checks": len(predictive),
            "exported_targets_inside": float(np.mean(exported_targets)) if exported_targets else None,
            "exported_target_checks": len(exported_targets),
            "exported_all_inside": float(np.mean([q["inside"] for q in exported])) if exported else None,
            "exported_all_checks": len(exported),
            "met": sum(r["status"] == "met" for r in rows)}


def write_summary(out, s, rows, header):
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump({"summary": s, "rocks": rows}, f, indent=1)
    lines = [header, "",
             f"{s['rocks']} rocks; {s['met']} met on fresh seeds. Identified parameters' 90 % credible intervals "
             f"holding the truth: {s['identified_intervals']} intervals, "
             + ("-" if s["coverage_identified"] is None else f"{100 * s['coverage_identified']:.0f} %")
             + " (goal 80-97 %). DEM runs per calibration: median "
             + ("-" if s["dem_runs_median"] is None else f"{s['dem_runs_median']:.0f}, most {s['dem_runs_max']}")
             + " (goal at most 100). Predictive 95 % intervals (over the posterior) holding the mean of 5 fresh seeds "
               "at the truth: "
             + ("-" if s["predictive_inside"] is None else f"{100 * s['predictive_inside']:.0f} % of "
                f"{s['predictive_checks']}") + ". At the exported point, the predictive's 95 % interval of a 5-specimen "
               "mean holding the first verification's 5-seed mean: "
             + ("-" if s["exported_targets_inside"] is None else
                f"{100 * s['exported_targets_inside']:.0f} % of {s['exported_target_checks']} targets, "
                f"{100 * s['exported_all_inside']:.0f} % of {s['exported_all_checks']} outputs of the test, "
                "targeted or not") + ".", "",
             "| parameter | identified (rocks) | truth inside, of those | median 90 % width / prior's |",
             "|---|---|---|---|"]
    for name, e in sorted(s["per_parameter"].items()):
        lines.append(f"| {name} | {e['identified']} | {e['inside']} | {e['median_width_of_prior']:.2f} |")
    # Per rock: its truth, what the search made of it, and which checks missed.
    names = sorted({n for r in rows for n in r["parameters"]})
    lines += ["", "| rock | " + " | ".join(names) + " | status | DEM runs | identified: truth inside | "
              "predictive misses (at the truth; at the exported point) |",
              "|---|" + "---|" * (len(names) + 4)]
    for r in rows:
        truth = " | ".join(f"{r['parameters'][n]['truth']:.3g}" if n in r["parameters"] else "-" for n in names)
        held = ", ".join(f"{n} {'yes' if p['inside'] else 'NO'}" for n, p in sorted(r["parameters"].items())
                         if p["identified"]) or "none identified"
        misses = [f"{n} (truth)" for n, q in sorted(r["predictive"].items()) if not q["inside"]]
        misses += [f"{n} (exported)" for n, q in sorted(r.get("exported", {}).items()) if not q["inside"]]
        lines.append(f"| {r['name']} | {truth} | {r['status']} | {r['dem_runs']} | {held} | "
                     f"{', '.join(misses) or 'none'} |")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--scene", default="data/scenes/ucs_rock_cb.json")
    ap.add_argument("--space", default="data/spaces/wang2017_rock_cb.json")
    ap.add_argument("--rocks", type=int, default=20)
    ap.add_argument("--budget", type=int, default=100)
    ap.add_argument("--seed", type=int, default=1, help="the truths' Latin hypercube")
    ap.add_argument("--jobs", default="2")
    ap.add_argument("--out", default="build/uncertainty_benchmark")
    ap.add_argument("--summary-only", action="store_true",
                    help="write the summary of the rocks finished so far (while a run goes on), running nothing")
    a = ap.parse_args()
    if a.rocks < 1 or a.budget < 30:
        sys.exit("uncertainty_benchmark: --rocks must be at least 1 and --budget at least 30")
    os.makedirs(a.out, exist_ok=True)
    with open(a.space) as f:
        space = benchmark_space(json.load(f))
    space_path = os.path.join(a.out, "space.json")
    with open(space_path, "w") as f:
        json.dump(space, f, indent=1)
    describe = subprocess.run([os.path.join(a.build, "bin", "demcal-dem"), "describe", "--scene", a.scene,
                               "--space", space_path], capture_output=True, text=True)
    if describe.returncode != 0:
        sys.exit(f"uncertainty_benchmark: {describe.stderr.strip()}")
    problem = Problem(json.loads(describe.stdout), {t: 1.0 for t in TARGETS}, space=space, where="benchmark")
    rows = []
    env = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(HERE), "python"), BIN=os.path.join(a.build, "bin"),
               JOBS=str(a.jobs), CACHE=os.path.join(a.build, "cache"))
    for k, truth in enumerate(truths(problem, a.rocks, a.seed), start=1):
        name = f"rock{k:02d}"
        if not a.summary_only:
            print(f"uncertainty_benchmark: {name} ({k}/{a.rocks}): " + ", ".join(f"{n} {v:.4g}" for n, v in truth.items()),
                  file=sys.stderr, flush=True)
        cal = os.path.join(a.out, "calibrations", name)
        if a.summary_only:
            fresh_points = os.path.join(a.out, name, "fresh", "responses.h5.points")
            finished = all(os.path.exists(os.path.join(cal, f)) for f in ("solution.json", "posterior.json"))
            if finished and os.path.isdir(fresh_points):
                fresh = read_macros(os.path.join(a.out, name, "fresh"), *FRESH_SEEDS)
                rows.append(dict(rock_result(truth, *calibration_files(cal), fresh), name=name))
            continue
        lab = run_truth(a.build, a.scene, truth, space["fixed"], *TRUTH_SEEDS, os.path.join(a.out, name, "truth"), a.jobs)
        targets = lab_targets(lab)
        if targets is None:
            print(f"uncertainty_benchmark: {name}: fewer than 2 of its specimens gave every target; skipped",
                  file=sys.stderr)
            continue
        cmd = [sys.executable, "-m", "demcal_study", "calibrate", "--scene", a.scene, "--space", space_path,
               "--strategy", "bayes", "--budget", str(a.budget), "--name", name, "--out-root",
               os.path.join(a.out, "calibrations"), "--quiet"] + sum((["--target", t] for t in targets), [])
        done = subprocess.run(cmd, env=env)
        if done.returncode not in (0, 3, 4):
            sys.exit(f"uncertainty_benchmark: {name}: the calibration failed (exit {done.returncode}); rerun to resume")
        fresh = run_truth(a.build, a.scene, truth, space["fixed"], *FRESH_SEEDS, os.path.join(a.out, name, "fresh"),
                          a.jobs)
        rows.append(dict(rock_result(truth, *calibration_files(cal), fresh), name=name))
        write_summary(a.out, summary(rows), rows, f"# The Bayesian search on synthetic rocks ({a.scene})")
    if a.summary_only:
        write_summary(a.out, summary(rows), rows, f"# The Bayesian search on synthetic rocks ({a.scene})")
    print(f"uncertainty_benchmark: {os.path.join(a.out, 'summary.md')}", file=sys.stderr)


if __name__ == "__main__":
    try:
        main()
    except StudyError as e:  # a stored file that cannot be read, named
        sys.exit(f"uncertainty_benchmark: {e}")
