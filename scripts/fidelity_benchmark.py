#!/usr/bin/python3
"""The PFC fidelity benchmark (docs/explanation/fidelity.md): our DEM at the micro-parameters of published PFC2D and PFC3D
runs, against what PFC gave there.

  l64            the 64 parameter sets of Su et al. 2021's L64 plan (data/literature/su2021_L64_orthogonal.csv)
                 at the default concrete resolution (data/scenes/ucs_concrete.json), 3 seeds each;
  l64_fine       16 of them (every 4th run: 1, 5, ..., 61) at the published resolution
                 (data/scenes/bench/ucs_concrete_fine.json, about 22,000 mortar disks), 2 seeds each;
  reference      the reference set (the concrete scene's defaults) at the default resolution, 5 seeds;
  reference_fine the reference set at the published resolution, 3 seeds;
  rock           Wang & Cao 2017's calibrated sandstone (data/scenes/ucs_rock_cb.json defaults), 5 seeds,
                 against their PFC2D run (data/literature/wang2017_rock_sa.json);
  sandstone_3d   Itasca's published PFC3D parallel-bonded sandstone (data/literature/itasca2016_pfc3d_sandstone_pb.json)
                 in uniaxial compression (data/scenes/ucs_pfc3d_sandstone_pb_3d.json), 5 seeds;
  sandstone_3d_tension  the same material in direct tension (data/scenes/tension_pfc3d_sandstone_pb_3d.json), 5 seeds.

The summary also gives the resolution shift: fine over default for the same parameter set and seed, where both
l64 and l64_fine (or both reference parts) hold it; the default resolution's comparison is judged within it.

Each part is a resumable `demcal-dem batch` under BUILD/fidelity_benchmark/PART (finished points are skipped, so an
interrupted run goes on where it stopped); --only runs some parts. The summary (Markdown: per output the median
ratio ours / PFC2D, its interquartile range, the correlation, our seed CV; the commits the runs were made at; the
machine) goes to BUILD/fidelity_benchmark/summary.md, and the figure of ours against PFC2D to
BUILD/fidelity_benchmark/fidelity_l64.png (--figure copies it elsewhere, e.g. docs/figures/).

    scripts/fidelity_benchmark.py [--build build] [--jobs 2] [--only PART,PART] [--quick] [--summary-only] [--figure PATH]
"""
import argparse
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import time

from measured_on import commit, machine

REPO = os.path.dirname(os.path.abspath(__file__)).rsplit(os.sep, 1)[0]
L64 = os.path.join(REPO, "data", "literature", "su2021_L64_orthogonal.csv")
SU2021 = os.path.join(REPO, "data", "literature", "su2021_concrete.json")
WANG2017 = os.path.join(REPO, "data", "literature", "wang2017_rock_sa.json")
CONCRETE = os.path.join(REPO, "data", "scenes", "ucs_concrete.json")
CONCRETE_FINE = os.path.join(REPO, "data", "scenes", "bench", "ucs_concrete_fine.json")
ROCK = os.path.join(REPO, "data", "scenes", "ucs_rock_cb.json")
ITASCA2016 = os.path.join(REPO, "data", "literature", "itasca2016_pfc3d_sandstone_pb.json")
SANDSTONE_3D = os.path.join(REPO, "data", "scenes", "ucs_pfc3d_sandstone_pb_3d.json")
SANDSTONE_3D_TENSION = os.path.join(REPO, "data", "scenes", "tension_pfc3d_sandstone_pb_3d.json")
OUTPUTS = ["sigma_u_MPa", "E_GPa", "nu"]
# Our output compared with each published one: Su et al. 2021 define nu as the secant at half the peak (our nu50;
# our nu is the tangent there).
OURS = {"sigma_u_MPa": "sigma_u_MPa", "E_GPa": "E_GPa", "nu": "nu50", "sigma_t_direct_MPa": "sigma_t_direct_MPa"}
PARTS = ["l64", "l64_fine", "reference", "reference_fine", "rock", "sandstone_3d", "sandstone_3d_tension"]


def fail(message):
    raise SystemExit(f"fidelity_benchmark: {message}")


def read_json(path, what):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read {what}: {e}")


def l64_rows():
    """The published plan: run number, the 13 micro-parameters, PFC2D's sigma_u, E, nu."""
    with open(L64) as f:
        rows = list(csv.DictReader(f))
    if len(rows) != 64:
        fail(f"{L64}: expected 64 runs, found {len(rows)}")
    return rows


def scene_parameters(scene_path, bin_dir):
    """The scene's parameters and their defaults, from `demcal-dem describe`."""
    done = subprocess.run([os.path.join(bin_dir, "demcal-dem"), "describe", "--scene", scene_path],
                          capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"demcal-dem describe {scene_path}: {done.stderr.strip()}")
    return {name: p["value"] for name, p in json.loads(done.stdout)["parameters"].items()}


def reference_values():
    """PFC's responses at the reference sets: the concrete (Su 2021) and the sandstone (Wang & Cao 2017) in PFC2D,
    Itasca's sandstone in PFC3D (compression, and direct tension)."""
    ref = read_json(SU2021, "Su et al. 2021").get("reference_result_pfc2d", {})
    concrete = {o: ref.get(o) for o in OUTPUTS}
    if any(v is None for v in concrete.values()):
        fail(f"{SU2021}: reference_result_pfc2d lacks one of {', '.join(OUTPUTS)}")
    macro = read_json(WANG2017, "Wang & Cao 2017").get("detailed_example", {}).get("result_macro", {})
    if "ucs_MPa" not in macro or "E_GPa" not in macro:
        fail(f"{WANG2017}: detailed_example.result_macro lacks ucs_MPa or E_GPa")
    itasca = read_json(ITASCA2016, "Itasca's PFC3D sandstone").get("macro_results", {})
    if any(k not in itasca for k in ("ucs_Pa", "E_Pa", "direct_tensile_strength_Pa")):
        fail(f"{ITASCA2016}: macro_results lacks ucs_Pa, E_Pa or direct_tensile_strength_Pa")
    return (concrete, {"sigma_u_MPa": macro["ucs_MPa"], "E_GPa": macro["E_GPa"]},
            {"sigma_u_MPa": itasca["ucs_Pa"] / 1e6, "E_GPa": itasca["E_Pa"] / 1e9,
             "sigma_t_direct_MPa": itasca["direct_tensile_strength_Pa"] / 1e6})


def part_plan(part, bin_dir, quick=False):
    """(scene, design rows as {run, parameters...}, seeds) of a part. Quick: both L64 parts on the published
    resolution's 16 points at seed 1 only (about an hour; a later full run resumes from them)."""
    if part in ("l64", "l64_fine"):
        scene = CONCRETE if part == "l64" else CONCRETE_FINE
        names = scene_parameters(scene, bin_dir)
        rows = l64_rows()
        if part == "l64_fine" or quick:
            rows = [r for r in rows if (int(r["run"]) - 1) % 4 == 0]
        design = [{"run": r["run"], **{n: r[n] for n in names}} for r in rows]
        return scene, design, 1 if quick else (3 if part == "l64" else 2)
    if part in ("reference", "reference_fine"):
        scene = CONCRETE if part == "reference" else CONCRETE_FINE
        return scene, [{"run": "1", **scene_parameters(scene, bin_dir)}], 5 if part == "reference" else 3
    scene = {"rock": ROCK, "sandstone_3d": SANDSTONE_3D, "sandstone_3d_tension": SANDSTONE_3D_TENSION}[part]
    return scene, [{"run": "1", **scene_parameters(scene, bin_dir)}], 5


def run_part(part, build, jobs, quick):
    bin_dir = os.path.join(build, "bin")
    folder = os.path.join(build, "fidelity_benchmark", part)
    os.makedirs(folder, exist_ok=True)
    scene, design, seeds = part_plan(part, bin_dir, quick)
    design_path = os.path.join(folder, "design.csv")
    with open(design_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(design[0]))
        writer.writeheader()
        writer.writerows(design)
    # Which commit made which runs: a resumed batch may finish at another one.
    with open(os.path.join(folder, "commits.txt"), "a") as f:
        f.write(f"{time.strftime('%Y-%m-%dT%H:%M:%S')} {commit()}\n")
    cmd = [os.path.join(bin_dir, "demcal-dem"), "batch", "--scene", scene, "--design", design_path,
           "--out", os.path.join(folder, "responses.h5"), "--csv", os.path.join(folder, "responses.csv"),
           "--seeds", str(seeds), "--jobs", str(jobs), "--cache", os.path.join(build, "cache")]
    print(f"== {part}: {len(design)} points x {seeds} seeds ({os.path.relpath(scene, REPO)})", flush=True)
    code = subprocess.run(cmd, cwd=REPO).returncode
    if code not in (0, 4):  # 4: some points failed, recorded with their reason
        fail(f"{part}: demcal-dem batch failed (exit {code})")


def stored_runs(part, build):
    """{(run, seed): {output: finite value}} of a part's ok runs, in CSV order, and its failures [(run, seed,
    reason)]; None for the runs when the part has no CSV yet."""
    path = os.path.join(build, "fidelity_benchmark", part, "responses.csv")
    if not os.path.exists(path):
        return None, []
    ok, failed = {}, []
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["status"] != "ok":  # "failed: <reason>"
                failed.append((row["run"], row["seed"], row["status"].removeprefix("failed: ")))
                continue
            values = {o: float(row[ours]) for o, ours in OURS.items() if row.get(ours) not in (None, "")}
            ok[(row["run"], row["seed"])] = {o: v for o, v in values.items() if math.isfinite(v)}
    return ok, failed


def results(part, build):
    """{run: [macro dict per ok seed]}, failures [(run, seed, reason)] of a part's stored runs."""
    ok, failed = stored_runs(part, build)
    if ok is None:
        return None, failed
    by_run = {}
    for (run, _), values in ok.items():
        by_run.setdefault(run, []).append(values)
    return by_run, failed


def quartiles(values):
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[0], statistics.median(values), q[2]


def correlation(x, y):
    mx, my = statistics.fmean(x), statistics.fmean(y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else float("nan")


def seed_cv_pct(samples):
    """Mean over points of the seed-to-seed coefficient of variation, %."""
    cvs = [statistics.stdev(s) / abs(statistics.fmean(s)) * 100 for s in samples if len(s) > 1 and statistics.fmean(s)]
    return statistics.fmean(cvs) if cvs else float("nan")


def plan_table(part, build, published):
    """Rows of the per-output comparison for an L64 part, plus the points for the figure."""
    by_run, failed = results(part, build)
    if by_run is None:
        return [f"| {part} | not run | | | | | |"], None, failed
    lines, points = [], {}
    for o in OUTPUTS:
        runs = [r for r in sorted(by_run, key=int) if all(o in m for m in by_run[r])]
        ours = [statistics.fmean(m[o] for m in by_run[r]) for r in runs]
        pfc = [published[r][o] for r in runs]
        if len(runs) < 4:
            lines.append(f"| {part} | {o} | {len(runs)} points | | | | |")
            continue
        ratios = [a / b for a, b in zip(ours, pfc)]
        q1, med, q3 = quartiles(ratios)
        cv = seed_cv_pct([[m[o] for m in by_run[r]] for r in runs])
        lines.append(f"| {part} | {o} | {len(runs)} | {med:.3f} | {q1:.3f}-{q3:.3f} | {correlation(ours, pfc):.3f} | "
                     f"{cv:.1f} |")
        points[o] = (pfc, ours)
    return lines, points, failed


def resolution_rows(build):
    """The resolution shift: fine over default for the same parameter set and seed (the same packing seed at two disk
    sizes), where both parts hold it; the L64 comparison at the default resolution is judged within this shift."""
    lines = []
    for coarse, fine in (("l64", "l64_fine"), ("reference", "reference_fine")):
        a, b = stored_runs(coarse, build)[0] or {}, stored_runs(fine, build)[0] or {}
        pairs = sorted(set(a) & set(b), key=lambda k: (int(k[0]), int(k[1])))
        for o in OUTPUTS:
            ratios = [b[k][o] / a[k][o] for k in pairs if o in a[k] and o in b[k] and a[k][o]]
            if len(ratios) < 2:
                lines.append(f"| {fine} / {coarse} | {o} | {len(ratios)} | | |")
                continue
            lines.append(f"| {fine} / {coarse} | {o} | {len(ratios)} | {statistics.median(ratios):.3f} | "
                         f"{min(ratios):.3f}-{max(ratios):.3f} |")
    return lines


def reference_row(part, build, pfc, outputs):
    by_run, failed = results(part, build)
    if not by_run:
        return [f"| {part} | not run | | | |"], failed
    samples = by_run.get("1", [])
    lines = []
    for o in outputs:
        values = [m[o] for m in samples if o in m]
        if not values:
            lines.append(f"| {part} | {o} | 0 | | {pfc[o]:.4g} | |")
            continue
        mean = statistics.fmean(values)
        cv = statistics.stdev(values) / mean * 100 if len(values) > 1 else float("nan")
        lines.append(f"| {part} | {o} | {len(values)} | {mean:.4g} ({cv:.1f}) | {pfc[o]:.4g} | {mean / pfc[o]:.3f} |")
    return lines, failed


def specimen_facts(part, build):
    """Mean porosity, bonds per particle (disk or sphere) and locked-in stress of a part's runs (from the point
    files)."""
    folder = os.path.join(build, "fidelity_benchmark", part, "responses.h5.points")
    if not os.path.isdir(folder):
        return None
    facts = {"porosity": [], "bonds_per_disk": [], "locked_in_stress_MPa": [], "particles": []}
    for name in os.listdir(folder):
        if not name.endswith(".json"):
            continue
        with open(os.path.join(folder, name)) as f:
            r = json.load(f)
        if r.get("status") != "ok":
            continue
        if "porosity" in r:
            facts["porosity"].append(r["porosity"])
        if "particles" in r:
            facts["particles"].append(r["particles"])
        for k in ("bonds_per_disk", "locked_in_stress_MPa"):
            if k in r.get("specimen", {}):
                facts[k].append(r["specimen"][k])
        if "bonds_per_sphere" in r.get("specimen", {}):  # a 3D specimen's
            facts["bonds_per_disk"].append(r["specimen"]["bonds_per_sphere"])
    return {k: statistics.fmean(v) for k, v in facts.items() if v}


def figure(points, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(12, 4))
    labels = {"sigma_u_MPa": "sigma_u (MPa)", "E_GPa": "E (GPa)", "nu": "nu"}
    for ax, o in zip(axes, OUTPUTS):
        for part, marker in (("l64", "o"), ("l64_fine", "s")):
            if points.get(part) and o in points[part]:
                pfc, ours = points[part][o]
                ax.scatter(pfc, ours, marker=marker, s=18, label=part, alpha=0.75)
        lo, hi = ax.get_xlim()
        ax.plot([lo, hi], [lo, hi], "k--", lw=0.8, label="ours = PFC2D")
        ax.set_xlabel(f"PFC2D {labels[o]}")
        ax.set_ylabel(f"ours {labels[o]}")
        ax.legend(fontsize=8)
    fig.suptitle("Our DEM at the L64 parameter sets of Su et al. 2021 against PFC2D (seed means)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def summary(build, figure_copy):
    published = {r["run"]: {o: float(r[o]) for o in OUTPUTS} for r in l64_rows()}
    concrete_ref, rock_ref, sandstone_3d_ref = reference_values()
    root = os.path.join(build, "fidelity_benchmark")
    commits = {}
    for part in PARTS:
        path = os.path.join(root, part, "commits.txt")
        if os.path.exists(path):
            with open(path) as f:
                commits[part] = sorted({line.split()[1] for line in f if line.strip()})
    lines = [f"Summary written {time.strftime('%Y-%m-%d')} on {machine()}. Runs made at: " +
             "; ".join(f"{p} {', '.join(c)}" for p, c in commits.items()) + ".", "",
             "At the L64 parameter sets (ratio = our seed mean / PFC2D's published value; nu is our secant nu50, "
             "as Su et al. 2021 define theirs):", "",
             "| part | output | points | median ratio | IQR of the ratio | correlation | our seed CV % |",
             "|---|---|---|---|---|---|---|"]
    points, failures = {}, {}
    for part in ("l64", "l64_fine"):
        rows, pts, failed = plan_table(part, build, published)
        lines += rows
        points[part] = pts
        failures[part] = failed
    lines += ["", "At the reference sets (mean over seeds, CV % in brackets; nu is our nu50 again):", "",
              "| part | output | seeds ok | ours | PFC (2D, or 3D for the _3d parts) | ratio |", "|---|---|---|---|---|---|"]
    for part, ref, outs in (("reference", concrete_ref, OUTPUTS), ("reference_fine", concrete_ref, OUTPUTS),
                            ("rock", rock_ref, ["sigma_u_MPa", "E_GPa"]),
                            ("sandstone_3d", sandstone_3d_ref, ["sigma_u_MPa", "E_GPa"]),
                            ("sandstone_3d_tension", sandstone_3d_ref, ["sigma_t_direct_MPa"])):
        rows, failed = reference_row(part, build, ref, outs)
        lines += rows
        failures[part] = failed
    lines += ["", "The resolution shift (published over default resolution, the same parameter set and seed; nu is nu50):",
              "", "| parts | output | pairs | median | range |", "|---|---|---|---|---|"]
    lines += resolution_rows(build)
    lines += ["", "The specimens (means over the stored runs):", "",
              "| part | particles | porosity | bonds per particle | locked-in stress MPa |", "|---|---|---|---|---|"]
    for part in PARTS:
        f = specimen_facts(part, build)
        if f:
            lines.append(f"| {part} | {f.get('particles', float('nan')):.0f} | {f.get('porosity', float('nan')):.4f} | "
                         f"{f.get('bonds_per_disk', float('nan')):.2f} | {f.get('locked_in_stress_MPa', float('nan')):.3g} |")
    failed_lines = [f"- {part} run {r} seed {s}: {why}" for part, lst in failures.items() for r, s, why in lst]
    if failed_lines:
        lines += ["", "Failed runs:", ""] + failed_lines
    text = "\n".join(lines) + "\n"
    os.makedirs(root, exist_ok=True)
    with open(os.path.join(root, "summary.md"), "w") as f:
        f.write(text)
    print(text)
    if any(points.values()):
        png = os.path.join(root, "fidelity_l64.png")
        figure(points, png)
        if figure_copy:
            shutil.copyfile(png, figure_copy)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default="build")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--only", help="comma-separated parts: " + ", ".join(PARTS))
    p.add_argument("--summary-only", action="store_true")
    p.add_argument("--quick", action="store_true",
                   help="the L64 parts on the 16 points of l64_fine at seed 1 only (about an hour)")
    p.add_argument("--figure", help="also copy the figure here")
    args = p.parse_args()
    only = args.only.split(",") if args.only else PARTS
    unknown = sorted(set(only) - set(PARTS))
    if unknown:
        fail(f"--only: unknown part(s) {', '.join(unknown)} (known: {', '.join(PARTS)})")
    build = os.path.abspath(args.build)
    if not args.summary_only:
        for part in PARTS:
            if part in only:
                run_part(part, build, args.jobs, args.quick)
    summary(build, args.figure)


if __name__ == "__main__":
    main()
