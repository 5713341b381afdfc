"""What a study cost: its DEM runs and the wall time of `make study` (make_wall_s.csv, kept by
scripts/run_study.sh), with, for a calibration, the largest verified error it ended with (or, for a minimisation,
the verified value of the output it drove down)."""
import csv
import os

from .errors import load_json
from .outputs import tests_per_point


def count_rows(path):
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        return sum(1 for _ in csv.DictReader(f))


def make_wall_s(out):
    """Seconds of `make study` summed over the runs that changed the report; None when not recorded."""
    timings = os.path.join(out, "make_wall_s.csv")
    if not os.path.exists(timings):
        return None
    with open(timings) as f:
        return sum(float(r["wall_s"]) for r in csv.DictReader(f))


def study_cost(out):
    """What a calibration cost and gave: DEM runs (screening, designs, DEM in the loop,
    verification, refinement; not the stability checks; each test of a test list counted), wall time of make study, and the
    largest verified relative error of the final solution."""
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    solution = load_json(refined["final"]["solution"], "solution")
    runs = count_rows(os.path.join(out, "screening", "responses.csv"))
    for k in range(1, len(study.get("surfaces", [])) + 1):
        runs += count_rows(os.path.join(out, f"g{k}", "responses.csv"))
    first_solution = load_json(os.path.join(out, "solution.json"), "solution")
    runs += first_solution.get("dem", {}).get("runs", 0)
    candidates = os.path.join(out, "candidates.json")
    if os.path.exists(candidates):  # a search's candidates, each verified (candidates.py)
        for c in load_json(candidates, "candidates")["candidates"]:
            runs += len(load_json(os.path.join(c["folder"], "verification.json"), "verification")["seeds"])
    else:
        runs += len(load_json(os.path.join(out, "verification.json"), "verification")["seeds"])
    scatter = os.path.join(out, "scatter", "verification.json")
    if os.path.exists(scatter):  # seeds_per_point "auto" measured the scatter first
        runs += len(load_json(scatter, "scatter verification")["seeds"])
    runs += sum(r["dem_runs"] for r in refined["rounds"])
    runs *= tests_per_point(study["scene"])  # a point of a test list runs each of its tests
    final = load_json(refined["final"]["verification"], "verification")
    errors = [abs(r["relative_error_pct"]) for r in final["outputs"].values()]
    minimised = None
    if final.get("objective_kind") == "minimise":
        # What it achieved is the verified value of the output it drove down (errors are against its own claim).
        (output, row), = final["outputs"].items()
        minimised = {"output": output, "mean": row["mean"], "ci95": [row["ci95_low"], row["ci95_high"]],
                     "reference": final["references"][output]}
    if study.get("strategy") == "dem_in_the_loop":
        label = f"DEM in the loop ({solution['algorithm']})"
    else:
        label = {"quadratic": "response surface", "linear": "linear surface", "gabp": "GA-BP network"}[
            study.get("surrogate", "quadratic")] + f" + {solution['algorithm']}"
    return {"name": study["name"], "strategy": label, "dem_runs": runs, "wall_s": make_wall_s(out),
            "max_error_pct": max(errors) if errors else None, "passed": final["passed"],
            "tolerance_pct": 100 * final.get("tolerance", 0), "minimised": minimised}
