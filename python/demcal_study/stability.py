"""stability: the same calibration with other optimiser seeds, a target near the edge of what the surrogates
reach, and deliberately too-small designs: where each breaks, and what the program says (stability.json)."""
import csv
import json
import os
import subprocess

from . import commands
from .outputs import stem
from .errors import load_json
from .files import write_target
from .surfaces import design_data, factors_of


def run_quiet(cmd):
    """Runs a stage tool; returns (exit code, its last error line)."""
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = [x for x in r.stderr.splitlines() if ": error: " in x]
    return r.returncode, (lines[-1].split(": error: ", 1)[1] if lines else "")


def invert_and_verify(out, name, models, targets, seed, where):
    """One inversion on `models` with the study's settings (other seed or targets), verified in DEM."""
    tools = commands.from_environment()
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    inversion = load_json(os.path.join(out, "config", "inversion.json"), "inversion")
    verification = load_json(os.path.join(out, "config", "verification.json"), "verification")
    space = os.path.join(out, "config", "space_inversion.json")
    os.makedirs(where, exist_ok=True)
    solution = os.path.join(where, f"{name}_solution.json")
    ver = os.path.join(where, f"{name}_verification.json")
    for stale in (solution, ver):  # never report an earlier run's file as this one's
        if os.path.exists(stale):
            os.remove(stale)
    code, message = run_quiet(commands.invert(tools, inversion, targets, space, solution, models=models, seed=seed,
                                              quiet=True))
    case = {"case": name, "seed": seed, "targets": targets, "invert_exit": code, "message": message}
    if code not in (0, 3, 4):
        return case
    sol = load_json(solution, "solution")
    case.update({"status": sol["status"], "x": sol["x"], "predicted": sol["predicted"]})
    if code == 3:
        return case  # unreachable: nothing to verify
    code, message = run_quiet(commands.verify(tools, solution, study["scene"], space, verification,
                                              os.path.join(where, f"{name}_runs"), ver, quiet=True))
    if code == 0 and os.path.exists(ver):
        v = load_json(ver, "verification")
        case.update({"verified": {o: r["relative_error_pct"] for o, r in v["outputs"].items()}, "passed": v["passed"]})
    else:
        case["verify_message"] = message
    return case


def stability(out):
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    stab = study["stability"]
    where = os.path.join(out, "stability")
    # The surrogates the calibration ended with (after its refinement rounds, if any).
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    models_dir = os.path.join(os.path.dirname(refined["final"]["solution"]), "models")
    models = [os.path.join(models_dir, f"{stem(o)}.json") for surface in study["surfaces"] for o in surface["outputs"]]
    record = {"seeds": [], "edge": None, "small_design": []}
    for seed in range(1, int(stab.get("seeds", 5)) + 1):
        record["seeds"].append(invert_and_verify(out, f"seed{seed}", models, study["targets"], 100 + seed, where))
        print(f"stability: seed {100 + seed} done", flush=True)

    # A target near (fraction < 1) or beyond (> 1) the top of the first output's attainable range.
    solution = load_json(refined["final"]["solution"], "solution")
    first = next(iter(study["targets"]))
    reach = solution["attainable"].get(first)
    if reach:
        fraction = float(stab.get("edge_fraction", 0.98))
        edge = dict(study["targets"])
        edge[first] = round(reach["min"] + fraction * (reach["max"] - reach["min"]), 6)
        record["edge"] = invert_and_verify(out, "edge", models, edge, 1, where)
        record["edge"].update({"output": first, "attainable": [reach["min"], reach["max"]], "fraction": fraction})

    record["small_design"] = small_designs(out, study, stab, models_dir, where)
    write_target(os.path.join(out, "stability.json"), json.dumps(record, indent=1) + "\n")


def small_designs(out, study, stab, models_dir, where):
    """The first surface refitted on the first n runs of its design (by default one run fewer than a
    quadratic's terms and two more), then inverted and verified with the other surfaces as they were."""
    tools = commands.from_environment()
    surrogate = study.get("surrogate", "quadratic")
    surface = study["surfaces"][0]
    factors = factors_of(out, 1, surface)
    with open(design_data(out, 1)) as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    k = len(factors)
    terms = (k + 1) * (k + 2) // 2 if surrogate == "quadratic" else None
    sizes = stab.get("small_design_runs") or ([terms - 1, terms + 2] if terms else [max(4, len(rows) // 4)])
    others = [os.path.join(models_dir, f"{stem(o)}.json") for s2 in study["surfaces"][1:] for o in s2["outputs"]]
    cases = []
    for n in sizes:
        n = min(int(n), len(rows))
        data = os.path.join(where, f"small{n}_data.csv")
        with open(data, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows[:n])
        small_models = []
        case = {"case": f"first {n} of {len(rows)} design runs", "runs": n, "terms": terms}
        ok = True
        for o in surface["outputs"]:
            model = os.path.join(where, f"small{n}_{stem(o)}.json")
            code, message = run_quiet(commands.fit(tools, surrogate, data, factors, o,
                                                   os.path.join(out, "config", "space_g1.json"), model))
            if code != 0:
                case.update({"fit_exit": code, "message": message})
                ok = False
                break
            m = load_json(model, "model")
            case.setdefault("r2_pred", {})[o] = m.get("r2_pred")
            small_models.append(model)
        if ok:
            case.update(invert_and_verify(out, f"small{n}", small_models + others, study["targets"], 1, where))
            case["case"] = f"first {n} of {len(rows)} design runs"
        cases.append(case)
        print(f"stability: design of {n} runs done", flush=True)
    return cases
