"""The DEM runs of a calibration: one batch per round on common specimen 1 (demcal-dem batch, resumable: a rerun
repeats no finished point) and the verifications on fresh seeds (demcal-verify). Each returns what the strategy
needs and counts the runs it made, failed ones included."""
import csv
import json
import os
import subprocess

from . import commands, curve_targets
from .errors import fail, load_json
from .files import write_target
from .point_results import read_point_result


# A point computed again on resume may differ from the stored one in its last digits (floating-point sums in another
# order): within this relative difference the stored point is the decision made before, and its results stand.
SAME_POINT_RTOL = 1e-9


def same_values(a, b):
    return set(a) == set(b) and all(abs(float(a[n]) - float(b[n])) <= SAME_POINT_RTOL * max(abs(float(a[n])), 1e-300)
                                    for n in a)


def stored_design(design, names):
    """The points of an existing design.csv with these columns, else None."""
    try:
        with open(design) as f:
            rows = list(csv.DictReader(f))
    except OSError:
        return None
    if not rows or sorted(k for k in rows[0] if k != "run") != names:
        return None
    return [{n: float(r[n]) for n in names} for r in rows]


def run_points(tools, scene, folder, points, quiet):
    """points: list of {parameter: value}. Returns one dict per point: {"status", "outputs"} (outputs empty when
    the run failed), in order."""
    os.makedirs(folder, exist_ok=True)
    names = sorted({name for p in points for name in p})
    design = os.path.join(folder, "design.csv")
    before = stored_design(design, names)
    if before is not None and len(before) == len(points) and all(same_values(a, b) for a, b in zip(before, points)):
        points = before
    text = ",".join(["run"] + names) + "\n" + "".join(
        ",".join([str(k + 1)] + [repr(float(p[n])) for n in names]) + "\n" for k, p in enumerate(points))
    if not (os.path.exists(design) and open(design).read() == text):
        write_target(design, text)
    out, table = os.path.join(folder, "responses.h5"), os.path.join(folder, "responses.csv")
    cmd = commands.dem_batch(tools, scene, design, out, table, 1)
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL if quiet else None)
    if done.returncode not in (0, 4):  # 4: some points failed, recorded as such
        fail(f"{folder}: demcal-dem batch failed (exit {done.returncode})")
    results = {}
    with open(table) as f:
        for row in csv.DictReader(f):
            results[int(row["run"])] = {"status": row["status"], "outputs": outputs_of_row(row, names)}
    missing = [k + 1 for k in range(len(points)) if k + 1 not in results]
    if missing:
        fail(f"{table}: no result for run(s) {missing}")
    return [dict(results[k + 1], **point_file(out, k + 1)) for k in range(len(points))]


def outputs_of_row(row, names):
    """A batch table's row (csv.DictReader) as {output: number}: every column but the design's (`names`), the run,
    the seed and the status; empty for a point that failed."""
    if row["status"] != "ok":
        return {}
    outputs = {}
    for key, value in row.items():
        if key in names or key in ("run", "seed", "status") or value in ("", None):
            continue
        try:
            outputs[key] = float(value)
        except ValueError:
            pass
    return outputs


def point_file(out, run):
    """A point's failure reason and its curve ({column: list}), from its result file beside the batch."""
    r = read_point_result(out, seed=1, run=run)
    return {"reason": "", "curve": None} if r is None else {"reason": r.get("reason", ""), "curve": r.get("curve")}


def one_point_batch(tools, scene, folder, parameters, first_seed, seeds, quiet):
    """demcal-dem batch of one point, `parameters`, on seeds first_seed.. (resumable): folder/design.csv, and the
    (responses.h5, responses.csv) paths it wrote; each seed's result is in responses.h5.points/run1_seedS.json."""
    os.makedirs(folder, exist_ok=True)
    names = sorted(parameters)
    design = os.path.join(folder, "design.csv")
    text = ",".join(["run"] + names) + "\n" + ",".join(["1"] + [repr(float(parameters[n])) for n in names]) + "\n"
    if not (os.path.exists(design) and open(design).read() == text):
        write_target(design, text)
    out, table = os.path.join(folder, "responses.h5"), os.path.join(folder, "responses.csv")
    done = subprocess.run(commands.dem_batch(tools, scene, design, out, table, seeds, first_seed),
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL if quiet else None)
    if done.returncode not in (0, 4):
        fail(f"{folder}: demcal-dem batch failed (exit {done.returncode})")
    return out, table


def check(tools, scene, folder, parameters, first_seed, seeds, quiet):
    """Another test at the calibrated parameters, not calibrated on (a prediction): a batch of one point over
    `seeds` fresh seeds. Returns {"runs", "ok", "outputs": {name: {"mean", "sd", "n"}}} and leaves responses.csv and
    responses.h5 in `folder` for the report's curves and Mohr circles."""
    _, table = one_point_batch(tools, scene, folder, parameters, first_seed, seeds, quiet)
    values, runs, ok = {}, 0, 0
    with open(table) as f:
        for row in csv.DictReader(f):
            runs += 1
            ok += row["status"] == "ok"
            for key, value in outputs_of_row(row, set(parameters)).items():
                values.setdefault(key, []).append(value)
    summary = {}
    for key, xs in values.items():
        mean = sum(xs) / len(xs)
        sd = (sum((x - mean) ** 2 for x in xs) / (len(xs) - 1)) ** 0.5 if len(xs) > 1 else None
        summary[key] = {"mean": mean, "sd": sd, "n": len(xs)}
    return {"runs": runs, "ok": ok, "outputs": summary}


def verify(tools, scene, folder, parameters, targets, predicted, first_seed, seeds, max_seeds, tolerance, quiet,
           intervals=None, scale_resolution=None, curves=None):
    """demcal-verify at absolute `parameters` on seeds first_seed.. (seeds to start with, up to max_seeds);
    `intervals` ({output: [low, high]}, the local model's 95 % prediction interval) is shown beside the DEM's.
    The points of measured curves (`curves`) are not demcal-verify's outputs: it runs the other targets, and their
    rows are added from the seeds' curves (curve_targets.add_to_verification)."""
    curves = curves or []
    all_targets, all_predicted, all_intervals = targets, predicted, intervals
    on_curve = set(curve_targets.names(curves))
    targets = {o: t for o, t in targets.items() if o not in on_curve}
    predicted = {o: t for o, t in (predicted or {}).items() if o not in on_curve}
    intervals = {o: t for o, t in intervals.items() if o not in on_curve} if intervals else intervals
    os.makedirs(folder, exist_ok=True)
    solution = os.path.join(folder, "solution.json")
    stored_x = load_json(solution, "verified solution").get("x") if os.path.exists(solution) else None
    # The point verified before (see SAME_POINT_RTOL), when some of its runs are stored; a point demcal-verify
    # refused before running anything has nothing to keep, and the new one (a bound snapped, say) takes its place.
    started = os.path.isdir(os.path.join(folder, "runs"))
    if isinstance(stored_x, dict) and started and same_values(stored_x, parameters):
        parameters = stored_x
    content = {"status": "ok", "x": parameters, "targets": targets, "predicted": predicted}
    if intervals:
        content["prediction_interval_95"] = intervals
    text = json.dumps(content, indent=1) + "\n"
    if not (os.path.exists(solution) and open(solution).read() == text):
        write_target(solution, text)
    out = os.path.join(folder, "verification.json")
    while True:
        cmd = [tools.program("demcal-verify"), "--solution", solution, "--scene", scene, "--seeds", str(seeds),
               "--max-seeds", str(max_seeds), "--first-seed", str(first_seed), "--tolerance", repr(tolerance),
               "--jobs", tools.jobs, "--cache", tools.cache, "--work", os.path.join(folder, "runs"),
               "--md", os.path.join(folder, "verification.md"), "--out", out]
        if scale_resolution:
            cmd += ["--scale-resolution", repr(scale_resolution)]
        if quiet:
            cmd.append("--quiet")
        done = subprocess.run(cmd, stdout=subprocess.DEVNULL)
        if done.returncode != 0:
            fail(f"{folder}: demcal-verify failed (exit {done.returncode})")
        v = load_json(out, "verification")
        if not curves:
            return v
        seed_curves = curve_targets.read_seed_curves(os.path.join(folder, "runs"), [s["seed"] for s in v["seeds"]])
        v = curve_targets.add_to_verification(v, seed_curves, curves, all_targets, all_predicted or {}, all_intervals,
                                              tolerance)
        write_target(out, json.dumps(v, indent=1) + "\n")
        # demcal-verify chose its seeds by the scalar targets: the curve's points may want more (it resumes).
        if scale_resolution:  # the finer check of a met point: its seeds were chosen before
            if "finer" in v:
                finer_seeds = [x["seed"] for x in v["finer"].get("seeds", [])]
                finer_curves = curve_targets.read_seed_curves(os.path.join(folder, "runs"), finer_seeds,
                                                              "finer_runs.h5")
                v = curve_targets.add_finer_shifts(v, finer_curves, curves)
                write_target(out, json.dumps(v, indent=1) + "\n")
            return v
        more = curve_targets.seeds_wanted(v, curves, tolerance, max_seeds)
        if more is None:
            return v
        seeds = more
