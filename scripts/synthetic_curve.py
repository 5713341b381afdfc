#!/usr/bin/python3
"""A synthetic lab curve from our own DEM: the mean stress-strain curve of K specimens at a known parameter set, in
the format `make calibrate CURVES=...` reads (axial_strain,axial_stress_MPa,lateral_strain,sd_MPa; compression
positive), and the specimens' mean scalar outputs beside it (OUT.json). A calibration to it has a known answer.

    scripts/synthetic_curve.py --build build --scene data/scenes/ucs_rock_cb.json \
        --set Ec_Pa=3e10 --set kn_ks=2.2 --seeds 8 --first-seed 101 --out build/synthetic/ucs_curve.csv

Resumable: the runs are a demcal-dem batch under OUT's folder. Fresh seeds by default (101 on): a calibration
searches on specimen 1, so a curve from specimen 1 would be easier than a lab's."""
import argparse
import csv
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from demcal_study.calibrate_runs import one_point_batch  # noqa: E402
from demcal_study.commands import Tools  # noqa: E402
from demcal_study.errors import StudyError  # noqa: E402
from demcal_study.point_results import stored_point_results  # noqa: E402

ROWS = 60            # strains the mean curve is written at
SPAN_OF_PEAK = 1.25  # up to this multiple of the mean peak strain


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="a scene parameter's value (the truth); the others keep the scene's")
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--first-seed", type=int, default=101)
    ap.add_argument("--jobs", default="2")
    ap.add_argument("--out", required=True, help="the curve CSV; OUT.json gets the scalar means")
    a = ap.parse_args()
    values = {}
    for item in a.set:
        name, _, text = item.partition("=")
        try:
            values[name] = float(text)
        except ValueError:
            sys.exit(f"synthetic_curve: --set {item}: not NAME=NUMBER")
    if a.seeds < 2:
        sys.exit("synthetic_curve: --seeds must be at least 2 (the curve's SD)")
    work = os.path.splitext(a.out)[0] + "_runs"
    tools = Tools(bin=os.path.join(a.build, "bin"), jobs=a.jobs, cache=os.path.join(a.build, "cache"), python="")
    try:
        out, _ = one_point_batch(tools, a.scene, work, values, a.first_seed, a.seeds, quiet=False)
    except StudyError as e:
        sys.exit(f"synthetic_curve: {e}; rerun to resume")
    results = stored_point_results(out, range(a.first_seed, a.first_seed + a.seeds), "synthetic_curve")
    curves, macros = [r["curve"] for r in results], [r["macro"] for r in results]
    peak = float(np.mean([c["axial_strain"][int(np.argmax(c["stress_MPa"]))] for c in curves]))
    strain = np.linspace(0.0, SPAN_OF_PEAK * peak, ROWS)
    # Past a specimen's last point its last value stands (it failed there), as the calibration reads a DEM curve.
    stress = np.array([np.interp(strain, c["axial_strain"], c["stress_MPa"]) for c in curves])
    lateral = -np.array([np.interp(strain, c["axial_strain"], c["lateral_strain"]) for c in curves])
    with open(a.out + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["axial_strain", "axial_stress_MPa", "lateral_strain", "sd_MPa"])
        for k, e in enumerate(strain):
            # The first row's SD is zero (every curve starts at zero stress); a file's SD must be positive.
            sd = max(float(stress[:, k].std(ddof=1)), 1e-6 * float(stress.mean(axis=0).max()))
            w.writerow([repr(float(e)), repr(float(stress[:, k].mean())), repr(float(lateral[:, k].mean())), repr(sd)])
    os.replace(a.out + ".tmp", a.out)
    summary = {"scene": a.scene, "truth": values, "seeds": list(range(a.first_seed, a.first_seed + a.seeds)),
               "mean": {k: float(np.mean([m[k] for m in macros])) for k in macros[0]},
               "sd": {k: float(np.std([m[k] for m in macros], ddof=1)) for k in macros[0]}}
    with open(os.path.splitext(a.out)[0] + ".json", "w") as f:
        json.dump(summary, f, indent=1)
    print(f"{a.out}: the mean of {a.seeds} specimens' curves; scalar means in {os.path.splitext(a.out)[0]}.json")


if __name__ == "__main__":
    main()
