"""Held-out design points (a surface's "holdout"): split keeps a seeded choice of design points out of the fit
(every seed of a point goes the same way, so no specimen of a held-out point trains the model); score predicts
them with the fitted model and gives R^2 and RMSE on points that took no part in any choice of the fit (its
training, its early stopping, its hidden size)."""
import csv
import json
import os
import random
import subprocess

from . import commands
from .errors import fail, load_json
from .files import write_target


def split(config_path, responses, out_json):
    """responses.csv into train.csv and holdout.csv beside out_json, and out_json: which points went where."""
    cfg = load_json(config_path, "holdout config")
    with open(responses) as f:
        reader = csv.reader(f)
        header = next(reader)
        rows = list(reader)
    run = header.index("run")
    points = sorted({int(r[run]) for r in rows})
    n = int(cfg["points"])
    if n >= len(points):
        fail(f"{config_path}: holdout asks for {n} design points but the design has {len(points)}; "
             "some must be left to train on")
    held = set(random.Random(int(cfg.get("seed", 1))).sample(points, n))
    folder = os.path.dirname(out_json)
    for name, keep in (("train.csv", lambda p: p not in held), ("holdout.csv", lambda p: p in held)):
        with open(os.path.join(folder, name + ".tmp"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(r for r in rows if keep(int(r[run])))
        os.replace(os.path.join(folder, name + ".tmp"), os.path.join(folder, name))
    status = header.index("status") if "status" in header else None
    ok = lambda r: status is None or r[status] == "ok"  # noqa: E731
    record = {"seed": int(cfg.get("seed", 1)), "held_out_points": sorted(held),
              "train_points": len(points) - n, "held_out": n,
              "train_rows_ok": sum(1 for r in rows if int(r[run]) not in held and ok(r)),
              "held_out_rows_ok": sum(1 for r in rows if int(r[run]) in held and ok(r))}
    write_target(out_json, json.dumps(record, indent=1) + "\n")


def score(model, holdout_csv, output, out_json):
    """The model's R^2 and RMSE on the held-out rows that ran (status ok), and each row's prediction."""
    with open(holdout_csv) as f:
        rows = [r for r in csv.DictReader(f) if r.get("status", "ok") == "ok"]
    if len(rows) < 2:
        fail(f"{holdout_csv}: {len(rows)} held-out rows ran; R^2 needs at least 2")
    # The model's inputs of the rows that ran, in order: the predictions come back in the same order.
    inputs = [i["name"] for i in load_json(model, "model")["inputs"]]
    points, predictions = out_json + ".points.csv", out_json + ".predictions.csv"
    with open(points, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(inputs)
        w.writerows([r[name] for name in inputs] for r in rows)
    cmd = commands.predict(commands.from_environment(), model, points, predictions)
    if subprocess.run(cmd).returncode != 0:
        fail(f"demcal-predict failed on the held-out rows of {holdout_csv}")
    with open(predictions) as f:
        predicted = [float(r[output]) for r in csv.DictReader(f)]
    os.remove(points)
    os.remove(predictions)
    observed = [float(r[output]) for r in rows]
    mean = sum(observed) / len(observed)
    ss_res = sum((o - p) ** 2 for o, p in zip(observed, predicted))
    ss_tot = sum((o - mean) ** 2 for o in observed)
    record = {"output": output, "rows": len(rows), "r2": 1.0 - ss_res / ss_tot if ss_tot > 0 else None,
              "rmse": (ss_res / len(rows)) ** 0.5,
              "points": [{"run": int(r["run"]), "observed": o, "predicted": p}
                         for r, o, p in zip(rows, observed, predicted)]}
    write_target(out_json, json.dumps(record, indent=1) + "\n")
