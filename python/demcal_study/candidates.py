"""candidates: a search's candidates (mean-shift cluster centres, largest cluster first), each verified in DEM
over the verification's seeds, as He et al. 2019 verify theirs; the best verified one becomes the study's answer
(OUT_DIR/verification.json names its solution file, which refinement and the report then read).

Best: an interval inside the band before a mean inside it before neither, then the fewest failed seeds (a
candidate judged on fewer specimens is judged on less, and a failed seed is itself a finding against it: a heap that
never settles, a run that bursts), then the smallest largest relative error. Each candidate keeps its own folder
(candidates/cK), so an interrupted stage resumes where it stopped."""
import csv
import json
import os
import shutil
import statistics
import subprocess

from . import commands
from .errors import fail, load_json
from .files import write_if_changed, write_target

VERDICT_RANK = {"interval_inside_band": 0, "mean_inside_band": 1, "outside": 2}


def verify_candidates(out):
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    verification = load_json(os.path.join(out, "config", "verification.json"), "verification")
    solution_path = os.path.join(out, "solution.json")
    solution = load_json(solution_path, "solution")
    candidates = solution.get("candidates", [])[:int(verification["candidates"])]
    if not candidates:
        fail(f"{solution_path}: the search kept no point within its tolerance of the targets, so there is no "
             "candidate to verify (see its attainable range; widen inversion.search_tolerance or change the targets)")
    tools = commands.from_environment()
    space = os.path.join(out, "config", "space_inversion.json")
    rows = []
    for k, c in enumerate(candidates, start=1):
        folder = os.path.join(out, "candidates", f"c{k}")
        os.makedirs(folder, exist_ok=True)
        # The solution as if the search had answered with this candidate; the interval the inversion gave
        # belongs to its own answer, so it is left out.
        own = {key: value for key, value in solution.items() if key not in ("prediction_interval_95", "candidates")}
        own.update(x=c["x"], predicted=c["predicted"], candidate={"rank": k, "cluster_size": c.get("size", 1)})
        path = os.path.join(folder, "solution.json")
        write_if_changed(path, json.dumps(own, indent=1, sort_keys=True) + "\n")
        result = os.path.join(folder, "verification.json")
        if not (os.path.exists(result) and os.path.getmtime(result) >= os.path.getmtime(path)):
            print(f"candidates: verifying candidate {k} of {len(candidates)} (cluster of {c.get('size', 1)} points)",
                  flush=True)
            cmd = commands.verify(tools, path, study["scene"], space, verification, os.path.join(folder, "verification"),
                                  result, md=os.path.join(folder, "verification.md"),
                                  csv=os.path.join(folder, "verification.csv"), quiet=True)
            if subprocess.run(cmd).returncode != 0:
                fail(f"demcal-verify failed for candidate {k} ({path})")
        v = load_json(result, "verification")
        worst = max(abs(o["relative_error_pct"]) for o in v["outputs"].values())
        failed = sum(1 for seed in v["seeds"] if seed.get("status", "ok") != "ok")
        rows.append({"rank": k, "cluster_size": c.get("size", 1), "x": c["x"], "predicted": c["predicted"],
                     "verdict": v["verdict"], "passed": v["passed"], "max_abs_relative_error_pct": worst,
                     "seeds_run": len(v["seeds"]), "seeds_failed": failed,
                     "outputs": v["outputs"], "other_outputs": other_outputs(os.path.join(folder, "verification", "runs.csv"),
                                                                            v["outputs"]),
                     "folder": folder})
    best = choose(rows)
    for r in rows:
        r["chosen"] = r is best
    for ext in ("json", "md", "csv"):
        shutil.copyfile(os.path.join(best["folder"], f"verification.{ext}"), os.path.join(out, f"verification.{ext}.tmp"))
    for ext in ("md", "csv"):
        os.replace(os.path.join(out, f"verification.{ext}.tmp"), os.path.join(out, f"verification.{ext}"))
    write_target(os.path.join(out, "candidates.json"), json.dumps({"candidates": rows}, indent=1) + "\n")
    os.replace(os.path.join(out, "verification.json.tmp"), os.path.join(out, "verification.json"))
    print(f"candidates: {len(rows)} verified; chosen: candidate {best['rank']} ({best['verdict']}, "
          f"{best['seeds_failed']} of {best['seeds_run']} seeds failed, largest error "
          f"{best['max_abs_relative_error_pct']:.2f} %)", flush=True)


def choose(rows):
    """The best verified candidate (the module's docstring says in what order)."""
    return min(rows, key=lambda r: (VERDICT_RANK.get(r["verdict"], 3), r["seeds_failed"], r["max_abs_relative_error_pct"]))


def other_outputs(runs_csv, judged):
    """Mean and SD over the seeds that ran of every numeric DEM output the verification did not judge (the
    heap's flow time beside its angle, say)."""
    if not os.path.exists(runs_csv):
        return {}
    with open(runs_csv) as f:
        reader = csv.DictReader(f)
        runs = [r for r in reader if r.get("status") == "ok"]
        # The parameters come before the status column, the DEM's outputs after it.
        outputs = reader.fieldnames[reader.fieldnames.index("status") + 1:]
    values = {}
    for r in runs:
        for name in outputs:
            if name in judged:
                continue
            try:
                values.setdefault(name, []).append(float(r[name]))
            except (TypeError, ValueError):
                pass
    # Only outputs every seed that ran reported (a number missing from one run would skew its mean).
    return {name: {"mean": statistics.mean(v), "sd": statistics.stdev(v) if len(v) > 1 else 0.0, "runs": len(v)}
            for name, v in values.items() if len(v) == len(runs)}
