"""refine: while the verification fails, its DEM runs join the data, the surrogates are refitted, the
inversion and the verification run again (up to refinement.rounds rounds); refined.json records each round."""
import csv
import json
import os
import subprocess

from . import commands
from .outputs import stem
from .errors import fail, load_json
from .files import write_target
from .surfaces import design_data, factors_of, merged_rows


def refine(out):
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    rounds = int(study.get("refinement", {}).get("rounds", 0))
    inversion = load_json(os.path.join(out, "config", "inversion.json"), "inversion")
    verification = load_json(os.path.join(out, "config", "verification.json"), "verification")
    tools = commands.from_environment()
    surrogate = study.get("surrogate", "quadratic")
    space = os.path.join(out, "config", "space_inversion.json")
    # The verified solution: the inversion's, or the search candidate that verified best (candidates.py).
    first = load_json(os.path.join(out, "verification.json"), "verification").get("solution",
                                                                                os.path.join(out, "solution.json"))
    current = {"solution": first, "verification": os.path.join(out, "verification.json"),
               "runs": os.path.join(os.path.dirname(first), "verification", "runs.csv")}
    record = {"rounds": [], "final": current}
    added = []
    for k in range(1, rounds + 1):
        if load_json(current["verification"], "verification")["passed"]:
            break
        added.append((current["runs"], 100000 * k))
        rd = os.path.join(out, "refine", f"round{k}")
        os.makedirs(os.path.join(rd, "models"), exist_ok=True)
        models = []
        for g, surface in enumerate(study["surfaces"], start=1):
            rows = merged_rows([(design_data(out, g), 0)] + added)
            factors = factors_of(out, g, surface)
            columns = ["run"] + factors + surface["outputs"]
            data = os.path.join(rd, f"data_g{g}.csv")
            with open(data, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(columns)
                for row in rows:
                    w.writerow([row[c] for c in columns])
            for o in surface["outputs"]:
                model = os.path.join(rd, "models", f"{stem(o)}.json")
                cmd = commands.fit(tools, surrogate, data, factors, o, os.path.join(out, "config", f"space_g{g}.json"),
                                   model)
                if subprocess.run(cmd).returncode != 0:
                    fail(f"refinement round {k}: demcal-fit failed for {o}")
                models.append(model)
        solution = os.path.join(rd, "solution.json")
        cmd = commands.invert(tools, inversion, study["targets"], space, solution, models=models, quiet=True)
        if subprocess.run(cmd).returncode not in (0, 3, 4):
            fail(f"refinement round {k}: demcal-invert failed")
        ver = os.path.join(rd, "verification.json")
        cmd = commands.verify(tools, solution, study["scene"], space, verification, os.path.join(rd, "verification"),
                              ver, md=os.path.join(rd, "verification.md"), quiet=True)
        if subprocess.run(cmd).returncode != 0:
            fail(f"refinement round {k}: demcal-verify failed")
        v = load_json(ver, "verification")
        record["rounds"].append({"round": k, "data_points": len(rows), "dem_runs": len(v["seeds"]),
                                 "passed": v["passed"],
                                 "relative_error_pct": {o: r["relative_error_pct"] for o, r in v["outputs"].items()}})
        print(f"refinement round {k}: " + ", ".join(f"{o} {r['relative_error_pct']:+.2f} %" for o, r in v["outputs"].items())
              + (" - passed" if v["passed"] else ""), flush=True)
        current = {"solution": solution, "verification": ver, "runs": os.path.join(rd, "verification", "runs.csv")}
        record["final"] = current
    write_target(os.path.join(out, "refined.json"), json.dumps(record, indent=1) + "\n")
