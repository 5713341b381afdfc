#!/usr/bin/python3
"""Model no more than the test needs: macro values of the default parallel-bond
UCS scene over 5 seeds against particle count and platen velocity, with the wall
time of each run. Writes docs/explanation/resolution_study.csv and the measured table of docs/explanation/resolution_study.md (between its
marker lines; the prose around them stays).

    /usr/bin/python3 scripts/resolution_study.py [--build build] [--jobs 2]

With --velocities V1,V2,... it runs only the loading-rate cases, on the scene's own specimen: that is how a 3D
scene is checked (the disk-count cases size a 2D specimen), e.g.

    /usr/bin/python3 scripts/resolution_study.py --scene data/scenes/ucs_rock_pb_3d.json \
        --velocities 0.01,0.02,0.04 --out docs/explanation/loading_rate_3d
"""
import argparse, json, math, os, statistics, subprocess, sys, time

from measured_on import commit, machine, write_block
from seed_statistics import macro_mean_cv

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from demcal_study.point_results import stored_point_results  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build")
parser.add_argument("--jobs", default="2")
parser.add_argument("--seeds", type=int, default=5)
parser.add_argument("--out", default="docs/explanation/resolution_study")
parser.add_argument("--scene", default="data/scenes/ucs_rock_pb.json")
parser.add_argument("--velocities", help="comma-separated platen velocities (m/s): only these, at the scene's size")
args = parser.parse_args()

# The doc must take the table before hours of runs are spent on it (a doc without its markers is not written over).
write_block(args.out + ".md", "scripts/resolution_study.py", None)

base = json.load(open(args.scene))
scene_dir = os.path.dirname(os.path.abspath(args.scene))
work = os.path.join(args.build, "resolution_study")
os.makedirs(work, exist_ok=True)
r_mean = 0.5 * (base["specimen"]["radius_min_m"] + base["specimen"]["radius_max_m"])
porosity = base["specimen"]["porosity"]

def scene_for(disks, velocity):
    scene = json.loads(json.dumps(base))
    scene["name"] = "study_%s_%g" % (disks or "own", velocity)
    if "extends" in scene:  # relative to the scene's own folder, not to the study's
        scene["extends"] = os.path.join(scene_dir, scene["extends"])
    if disks:
        # H = 2 W and N = W H (1 - n) / (pi R^2)  ->  W = sqrt(N pi R^2 / (2 (1 - n)))
        width = math.sqrt(disks * math.pi * r_mean ** 2 / (2 * (1 - porosity)))
        scene["specimen"]["width_m"] = round(width, 5)
        scene["specimen"]["height_m"] = round(2 * width, 5)
    scene["loading"]["platen_velocity_m_s"] = velocity
    path = os.path.join(work, scene["name"] + ".json")
    json.dump(scene, open(path, "w"), indent=1)
    return path

design = os.path.join(work, "design.csv")
with open(design, "w") as f:
    f.write("run,Ec_GPa\n1,%g\n" % base["parameters"]["Ec_GPa"]["value"])

if args.velocities:
    cases = [(None, float(v)) for v in args.velocities.split(",")]
else:
    cases = [(n, 0.02) for n in (1000, 2000, 5000, 10000, 20000)] + [(5000, v) for v in (0.01, 0.05, 0.1)]
rows = []
for disks, velocity in cases:
    scene = scene_for(disks, velocity)
    out = os.path.join(work, "study_%s_%g.h5" % (disks or "own", velocity))
    start = time.time()
    subprocess.run([os.path.join(args.build, "bin", "demcal-dem"), "batch", "--scene", scene, "--design", design,
                    "--out", out, "--seeds", str(args.seeds), "--jobs", args.jobs, "--cache",
                    os.path.join(args.build, "cache"), "--quiet"], check=False)
    points = stored_point_results(out, range(1, args.seeds + 1), "resolution_study")
    ok = [p for p in points if p["status"] == "ok"]
    row = {"disks_planned": disks or 0, "platen_velocity_m_s": velocity, "runs_ok": len(ok),
           "disks": statistics.mean(p["particles"] for p in ok) if ok else float("nan"),
           "wall_s_per_run": statistics.mean(p["wall_s"] for p in ok) if ok else float("nan"),
           "mps_per_s": statistics.mean(p["particle_steps_per_s"] for p in ok) / 1e6 if ok else float("nan")}
    row.update(macro_mean_cv(ok))
    rows.append(row)
    print("%6d particles  v %.3f m/s  sigma_u %.2f (CV %.1f %%)  E %.2f (CV %.1f %%)  nu %.3f (CV %.1f %%)  %.1f s/run" % (
        row["disks"], velocity, row["sigma_u_MPa_mean"], row["sigma_u_MPa_cv_pct"], row["E_GPa_mean"],
        row["E_GPa_cv_pct"], row["nu_mean"], row["nu_cv_pct"], row["wall_s_per_run"]), flush=True)

keys = list(rows[0].keys())
with open(args.out + ".csv", "w") as f:
    f.write(",".join(keys) + "\n")
    for row in rows:
        f.write(",".join(("%.6g" % row[k]) if isinstance(row[k], float) else str(row[k]) for k in keys) + "\n")
command = " ".join(["/usr/bin/python3 scripts/resolution_study.py"] + sys.argv[1:])
size = ("its own specimen" if args.velocities else "specimen H = 2 W scaled to the disk count")
lines = ["Scene `%s` at its default parameters, %s, "
         "%d seeds per case, `%s` (%s points at once, one thread each), "
         "measured %s at commit %s on %s. Wall time per run: one run with its packed specimen loaded from the cache; "
         "packing, once per seed, comes on top." % (args.scene, size, args.seeds, command, args.jobs,
                                                     time.strftime("%Y-%m-%d"), commit(), machine()),
         "", "| particles | platen velocity (m/s) | sigma_u (MPa) | CV % | E (GPa) | CV % | nu | CV % | wall s/run | "
         "M particle-steps/s |", "|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    lines.append("| %.0f | %g | %.2f | %.1f | %.2f | %.1f | %.3f | %.1f | %.1f | %.1f |" % (
        r["disks"], r["platen_velocity_m_s"], r["sigma_u_MPa_mean"], r["sigma_u_MPa_cv_pct"], r["E_GPa_mean"],
        r["E_GPa_cv_pct"], r["nu_mean"], r["nu_cv_pct"], r["wall_s_per_run"], r["mps_per_s"]))
write_block(args.out + ".md", "scripts/resolution_study.py", "\n".join(lines))
print("wrote", args.out + ".md", file=sys.stderr)
