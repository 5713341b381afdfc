#!/usr/bin/python3
"""A finished calibration's folder as a replay fixture: every DEM result it used (the points on specimen 1 and each
verification as demcal-verify returned it), the scene's description, its settings and the decisions it made. The
test python/tests/test_replay.py runs the calibration again on these stored results alone: a change to the search,
the runner or the verifier that asks for another DEM point, or decides otherwise, fails it.

    scripts/replay_fixture.py build/calibrations/NAME python/tests/data/replay_NAME.json --build build

The calibration must have run with the current executables (the description is taken now)."""
import argparse
import csv
import glob
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from demcal_study.calibrate_runs import outputs_of_row  # noqa: E402

# What the replay compares: the decisions, not the wall times or the paths of the machine that made them.
DECISIONS = ("status", "exit_code", "dem_runs", "x", "scale_factor", "coordinates", "ratios", "predicted",
             "prediction_interval_95", "offset", "rounds", "verifications", "crn", "bounded_scale", "reachable")


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("calibration", help="the calibration's folder")
    ap.add_argument("out", help="the fixture file to write")
    ap.add_argument("--build", default="build")
    a = ap.parse_args()
    with open(os.path.join(a.calibration, "calibration.json")) as f:
        config = json.load(f)
    with open(os.path.join(a.calibration, "solution.json")) as f:
        solution = json.load(f)
    cmd = [os.path.join(a.build, "bin", "demcal-dem"), "describe", "--scene", config["scene"]]
    if config.get("space"):
        cmd += ["--space", config["space"]]
    description = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    points = []
    for table in sorted(glob.glob(os.path.join(a.calibration, "rounds", "*", "responses.csv"))):
        names = rows_of(os.path.join(os.path.dirname(table), "design.csv"))[0].keys() - {"run"}
        for row in rows_of(table):
            points.append({"parameters": {n: float(row[n]) for n in sorted(names)}, "status": row["status"],
                           "outputs": outputs_of_row(row, names)})
    verifications = []
    for folder in sorted(glob.glob(os.path.join(a.calibration, "verify", "v*"))):
        with open(os.path.join(folder, "solution.json")) as f:
            asked = json.load(f)
        with open(os.path.join(folder, "verification.json")) as f:
            verifications.append({"x": asked["x"], "verification": json.load(f)})
    design = os.path.join(a.calibration, "rounds", "design_lhs.csv")
    fixture = {"source": os.path.basename(os.path.normpath(a.calibration)), "config": config,
               "description": description, "design_lhs": open(design).read() if os.path.exists(design) else None,
               "points": points, "verifications": verifications,
               "decisions": {k: solution[k] for k in DECISIONS if k in solution}}
    with open(a.out, "w") as f:
        json.dump(fixture, f, indent=0, sort_keys=True)
        f.write("\n")
    print(f"{a.out}: {len(points)} points, {len(verifications)} verifications", file=sys.stderr)


if __name__ == "__main__":
    main()
