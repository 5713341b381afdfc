#!/usr/bin/python3
"""Resolution of the concrete UCS scene: the reference parameter set of Su et al. (2021) over
several seeds at several mortar disk sizes (the 100 x 200 mm specimen and its aggregates stay
the same), with the wall time of each run. Writes docs/explanation/concrete_resolution_study.csv and the table of
docs/explanation/concrete_resolution_study.md (between its marker lines, with the date, commit and machine; the prose
around it stays).

    /usr/bin/python3 scripts/concrete_resolution_study.py [--build build] [--jobs 2] [--seeds 5]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

from measured_on import commit, machine, write_block
from seed_statistics import macro_mean_cv

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from demcal_study.point_results import stored_point_results  # noqa: E402

SCRIPT = "scripts/concrete_resolution_study.py"

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build")
parser.add_argument("--jobs", default="2")
parser.add_argument("--seeds", type=int, default=5)
parser.add_argument("--radii-mm", default="1.4,1.0,0.7,0.5", help="mean mortar radii to run")
parser.add_argument("--fine-seeds", type=int, default=3, help="seeds for radii below 0.6 mm (slow)")
parser.add_argument("--out", default="docs/explanation/concrete_resolution_study")
args = parser.parse_args()
write_block(args.out + ".md", SCRIPT, None)  # before hours of runs: refuse a doc it could not write into
started = time.strftime("%Y-%m-%d")

base = json.load(open("data/scenes/ucs_concrete.json"))
work = os.path.join(args.build, "concrete_resolution_study")
os.makedirs(work, exist_ok=True)
ratio = 2.5  # R_max / R_min, as in su2021_concrete.json
published = {"sigma_u_MPa": 32.23, "E_GPa": 28.37, "nu": 0.197}


def scene_for(r_mean_mm):
    r_min = 2 * r_mean_mm / 1000 / (1 + ratio)
    scene = json.loads(json.dumps(base))
    scene["name"] = "concrete_r%g" % r_mean_mm
    scene["specimen"]["radius_min_m"] = round(r_min, 7)
    scene["specimen"]["radius_max_m"] = round(ratio * r_min, 7)
    path = os.path.join(work, scene["name"] + ".json")
    json.dump(scene, open(path, "w"), indent=1)
    return path


design = os.path.join(work, "reference.csv")
with open(design, "w") as f:
    names = list(base["parameters"])
    f.write("run," + ",".join(names) + "\n1," + ",".join("%g" % base["parameters"][n]["value"] for n in names) + "\n")

rows = []
for r_mean in [float(r) for r in args.radii_mm.split(",")]:
    seeds = args.seeds if r_mean >= 0.6 else min(args.seeds, args.fine_seeds)
    scene = scene_for(r_mean)
    out = os.path.join(work, "r%g.h5" % r_mean)
    start = time.time()
    subprocess.run([os.path.join(args.build, "bin", "demcal-dem"), "batch", "--scene", scene, "--design", design,
                    "--out", out, "--seeds", str(seeds), "--jobs", args.jobs, "--cache",
                    os.path.join(args.build, "cache"), "--quiet"], check=False)
    batch_wall = time.time() - start
    points = stored_point_results(out, range(1, seeds + 1), "concrete_resolution_study")
    ok = [p for p in points if p["status"] == "ok"]
    row = {"r_mean_mm": r_mean, "seeds": seeds, "runs_ok": len(ok),
           "disks": statistics.mean(p["particles"] for p in ok) if ok else float("nan"),
           "aggregate_disks": statistics.mean(p["specimen"]["aggregate_disks"] for p in ok) if ok else float("nan"),
           "porosity": statistics.mean(p["porosity"] for p in ok) if ok else float("nan"),
           "loading_s_per_run": statistics.mean(p["test_wall_s"] for p in ok) if ok else float("nan"),
           "wall_s_per_run": statistics.mean(p["wall_s"] for p in ok) if ok else float("nan"),
           "mps_per_s": statistics.mean(p["particle_steps_per_s"] for p in ok) / 1e6 if ok else float("nan"),
           "batch_wall_s": batch_wall}
    row.update(macro_mean_cv(ok, keys=("sigma_u_MPa", "E_GPa", "nu", "nu50")))
    rows.append(row)
    print("R %.1f mm  %6.0f disks  sigma_u %.2f (CV %.1f %%)  E %.2f (CV %.1f %%)  nu %.3f (CV %.1f %%)  %.1f s/run" % (
        r_mean, row["disks"], row["sigma_u_MPa_mean"], row["sigma_u_MPa_cv_pct"], row["E_GPa_mean"], row["E_GPa_cv_pct"],
        row["nu_mean"], row["nu_cv_pct"], row["wall_s_per_run"]), flush=True)

keys = list(rows[0])
with open(args.out + ".csv", "w") as f:
    f.write(",".join(keys) + "\n")
    for row in rows:
        f.write(",".join("%.6g" % row[k] if isinstance(row[k], float) else str(row[k]) for k in keys) + "\n")
# PFC2D's nu is Su et al.'s secant at half the peak: our nu50; our nu is the tangent there.
lines = ["Scene `data/scenes/ucs_concrete.json` at its reference set, mortar radii scaled (R_max / R_min = 2.5), "
         "`/usr/bin/python3 %s` on %s, %s, engine of commit %s, runs at a time: %s. Wall time per run: one run with "
         "its packed specimen loaded from the cache (loading alone in brackets)." % (SCRIPT, machine(), started, commit(),
                                                                                     args.jobs),
         "",
         "| mean mortar radius | seeds ok | disks | porosity | sigma_u MPa (CV %) | E GPa (CV %) | nu (CV %) | "
         "nu50 (CV %) | s per run (loading) | M particle-steps/s |",
         "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append("| %.1f mm | %d/%d | %.0f | %.3f | %.2f (%.1f) | %.2f (%.1f) | %.3f (%.1f) | %.3f (%.1f) | %.1f (%.1f) | "
                 "%.1f |" % (r["r_mean_mm"], r["runs_ok"], r["seeds"], r["disks"], r["porosity"], r["sigma_u_MPa_mean"],
                             r["sigma_u_MPa_cv_pct"], r["E_GPa_mean"], r["E_GPa_cv_pct"], r["nu_mean"], r["nu_cv_pct"],
                             r["nu50_mean"], r["nu50_cv_pct"], r["wall_s_per_run"], r["loading_s_per_run"],
                             r["mps_per_s"]))
lines.append("| published PFC2D (Su et al. 2021) | | ~22,000 mortar | 0.12 | %.2f | %.2f | | %.3f | | |" % (
    published["sigma_u_MPa"], published["E_GPa"], published["nu"]))
write_block(args.out + ".md", SCRIPT, "\n".join(lines))
print("wrote", args.out + ".md", args.out + ".csv")
