#!/usr/bin/python3
"""Study files: validation, the make plan of a study, design preparation and the report.

    study.py plan STUDY.json OUT_DIR     validate and write OUT_DIR/plan.mk with its stage configs
    study.py design CONFIG.json OUT.csv  a surface's design in natural units, fixed values added
    study.py screen OUT_DIR              range analysis and ANOVA of the screening, main-effects and Pareto plots
    study.py stability OUT_DIR           other optimiser seeds, a target near the edge, too-small designs (each verified)
    study.py refine OUT_DIR              while verification fails: add its DEM runs to the data, refit,
                                         re-invert, re-verify (up to refinement.rounds rounds)
    study.py report OUT_DIR              OUT_DIR/report.md and a self-contained report.html

`make study STUDY=data/studies/NAME.json` runs plan, then make on the plan: every stage is a
file target (design -> DEM responses -> models -> solution -> verification -> report), so an
interrupted study resumes, `make -j2` runs independent stages together, and a change to the study
rewrites only the stage configs it touches (their contents are compared), so only what depends
on them runs again.
"""
import base64
import csv
import html
import json
import os
import re
import subprocess
import sys

KNOWN = {"name", "description", "strategy", "scene", "space", "targets", "fixed", "screening", "surfaces", "factors",
         "surrogate", "inversion", "verification", "refinement", "seeds_per_point", "stability", "compare_with"}
SCREENING_FIELDS = {"design", "factors", "outputs", "seeds", "p_threshold", "max_factors"}
STRATEGIES = {"surrogate", "dem_in_the_loop"}
INVERSION_FIELDS = {"algorithm", "objective", "restarts", "polish", "seed", "population", "budget", "stop_below", "settings"}
SURROGATES = {"quadratic", "linear", "gabp"}
DESIGNS = {"ccd", "bbd", "lhs"}  # the designs a study's surfaces are built from (doe has more)


def fail(message):
    print(f"study.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def load_json(path, what):
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        fail(f"{path}: cannot open {what} ({e.strerror})")
    except ValueError as e:
        fail(f"{path}: not valid JSON ({e})")


_ASKED = {}


def ask(program, *args):
    """The JSON an executable prints about itself (scenes, design kinds, algorithms): the executables are the
    one source of truth, the study layer keeps no copy. Cached per call."""
    key = (program,) + args
    if key not in _ASKED:
        cmd = [os.path.join(os.environ.get("BIN", "build/bin"), program)] + list(args)
        try:
            done = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as e:
            fail(f"cannot run {cmd[0]} ({e.strerror}): build first (make build) or set BIN")
        if done.returncode != 0:
            fail(done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"{' '.join(cmd)} failed")
        _ASKED[key] = json.loads(done.stdout)
    return _ASKED[key]


def describe(scene_path, space_path=None):
    """What the scene has (parameters, outputs, ...); with a space, demcal-dem also checks that it narrows the scene."""
    return ask("demcal-dem", "describe", "--scene", scene_path, *(["--space", space_path] if space_path else []))


def design_kind(kind):
    """A design kind's factor limits and options, from demcal-doe --list-kinds."""
    return ask("demcal-doe", "--list-kinds")["kinds"][kind]


def write_if_changed(path, text):
    """Writes only when the content differs, so make sees a change only where there is one."""
    if os.path.exists(path) and open(path).read() == text:
        return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_target(path, text):
    """A make target: always rewritten, so it is newer than what it was made from."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def validate(study, path):
    where = path
    unknown = sorted(set(study) - KNOWN)
    if unknown:
        fail(f"{where}: unknown field \"{unknown[0]}\" (allowed: {', '.join(sorted(KNOWN))})")
    strategy = study.get("strategy", "surrogate")
    if strategy not in STRATEGIES:
        fail(f"{where}: strategy must be one of {', '.join(sorted(STRATEGIES))}")
    loop = strategy == "dem_in_the_loop"
    for key in ("name", "scene", "space", "targets") + (("factors",) if loop else ("surfaces",)):
        if key not in study:
            fail(f"{where}: missing \"{key}\"")
    for key in (("surfaces", "surrogate", "refinement") if loop else ("factors",)):
        if key in study:
            fail(f"{where}: \"{key}\" does not apply to strategy {strategy}")
    if not re.fullmatch(r"[A-Za-z0-9_.-]+", study["name"]):
        fail(f"{where}: name \"{study['name']}\" must be letters, digits, '_', '-' or '.'")
    scene = describe(study["scene"], study["space"])
    space = load_json(study["space"], "parameter space")
    scene_params = set(scene["parameters"])
    scene_outputs = set(scene["outputs"])
    space_params = {p["name"]: p for p in space.get("parameters", [])}
    targets = study["targets"]
    if not isinstance(targets, dict) or not targets:
        fail(f"{where}: targets must be an object of output: value")
    for name, value in targets.items():
        if name not in scene_outputs:
            fail(f"{where}: targets.{name}: not a DEM output (outputs of {study['scene']}: {', '.join(sorted(scene_outputs))})")
        if not isinstance(value, (int, float)) or value == 0:
            fail(f"{where}: targets.{name} must be a non-zero number")
    fixed = study.get("fixed", "reference")
    if fixed != "reference" and not isinstance(fixed, dict):
        fail(f"{where}: fixed must be \"reference\" or an object of parameter: value")
    if isinstance(fixed, dict):
        for name, value in fixed.items():
            if name not in scene_params:
                fail(f"{where}: fixed.{name}: not a parameter of {study['scene']}")
            if not isinstance(value, (int, float)):
                fail(f"{where}: fixed.{name} must be a number")
    if loop:
        if not isinstance(study["factors"], list) or not study["factors"]:
            fail(f"{where}: factors must be a non-empty list of the parameters to calibrate")
        for f in study["factors"]:
            if f not in space_params:
                fail(f"{where}: factor {f} is not a parameter of {study['space']} (parameters: {', '.join(space_params)})")
            if f not in scene_params:
                fail(f"{where}: factor {f} is not a parameter of {study['scene']}")
    screening = study.get("screening")
    if screening is not None:
        w = f"{where}: screening"
        if not isinstance(screening, dict):
            fail(f"{w} must be an object")
        extra = sorted(set(screening) - SCREENING_FIELDS)
        if extra:
            fail(f"{w}: unknown field \"{extra[0]}\" (allowed: {', '.join(sorted(SCREENING_FIELDS))})")
        for key in ("design", "outputs"):
            if key not in screening:
                fail(f"{w}: missing \"{key}\"")
        if screening["design"].get("kind") != "oa":
            fail(f"{w}: design.kind must be \"oa\" (range analysis and ANOVA need an orthogonal plan)")
        extra = sorted(set(screening["design"]) - {"kind", "runs", "blank", "levels"})
        if extra:
            fail(f"{w}: design: unknown field \"{extra[0]}\" (allowed: kind, runs, blank, levels)")
        for o in screening["outputs"]:
            if o not in scene_outputs:
                fail(f"{w}: output {o} is not a DEM output")
        for name in screening.get("factors", list(space_params)):
            if name not in space_params:
                fail(f"{w}: factor {name} is not a parameter of {study['space']}")
            if name not in scene_params:
                fail(f"{w}: the space's parameter {name} is not a parameter of {study['scene']}")
        p = screening.get("p_threshold", 0.05)
        if not isinstance(p, (int, float)) or not 0 < p < 1:
            fail(f"{w}: p_threshold must lie in (0, 1)")
        if int(screening.get("max_factors", 6)) < 2:
            fail(f"{w}: max_factors must be at least 2")
    covered = set(targets) if loop else set()
    for k, surface in enumerate(study.get("surfaces", [])):
        w = f"{where}: surfaces[{k}]"
        extra = sorted(set(surface) - {"outputs", "factors", "design"})
        if extra:
            fail(f"{w}: unknown field \"{extra[0]}\" (allowed: outputs, factors, design)")
        for key in ("outputs", "factors", "design"):
            if key not in surface:
                fail(f"{w}: missing \"{key}\"")
        for o in surface["outputs"]:
            if o not in scene_outputs:
                fail(f"{w}: output {o} is not a DEM output")
            if o in covered:
                fail(f"{w}: output {o} has a surface already")
            covered.add(o)
        if surface["factors"] == "auto":
            if screening is None:
                fail(f"{w}: factors \"auto\" are chosen from the screening ANOVA: add a \"screening\" stage")
            missing_out = [o for o in surface["outputs"] if o not in screening["outputs"]]
            if missing_out:
                fail(f"{w}: factors \"auto\" needs output {missing_out[0]} in screening.outputs")
        elif not isinstance(surface["factors"], list) or not surface["factors"]:
            fail(f"{w}: factors must be a list of parameters or \"auto\"")
        for f in (surface["factors"] if isinstance(surface["factors"], list) else []):
            if f not in space_params:
                fail(f"{w}: factor {f} is not a parameter of {study['space']} (parameters: {', '.join(space_params)})")
            if f not in scene_params:
                fail(f"{w}: factor {f} is not a parameter of {study['scene']}")
        d = surface["design"]
        if d.get("kind") not in DESIGNS:
            fail(f"{w}: design.kind must be one of {', '.join(sorted(DESIGNS))}")
        extra = sorted(set(d) - {"kind", "center", "alpha", "runs", "criterion"})
        if extra:
            fail(f"{w}: design: unknown field \"{extra[0]}\"")
        if surface["factors"] == "auto":
            continue  # the design is checked once the screening has chosen the factors
        k_factors = len(surface["factors"])
        limits = design_kind(d["kind"])
        if k_factors < limits["min_factors"] or (limits["max_factors"] and k_factors > limits["max_factors"]):
            most = f"to {limits['max_factors']}" if limits["max_factors"] else "or more"
            fail(f"{w}: a {limits['title']} design needs {limits['min_factors']} {most} factors, not {k_factors}")
        if d["kind"] == "lhs" and int(d.get("runs", 0)) < (k_factors + 1) * (k_factors + 2) // 2 + 1:
            fail(f"{w}: an LHS for a quadratic in {k_factors} factors needs at least "
                 f"{(k_factors + 1) * (k_factors + 2) // 2 + 1} runs (design.runs)")
    missing = sorted(set(targets) - covered)
    if missing:
        fail(f"{where}: target {missing[0]} has no surface (add it to a surfaces[].outputs)")
    if study.get("surrogate", "quadratic") not in SURROGATES:
        fail(f"{where}: surrogate must be one of {', '.join(sorted(SURROGATES))}")
    inv = study.get("inversion", {})
    extra = sorted(set(inv) - INVERSION_FIELDS)
    if extra:
        fail(f"{where}: inversion: unknown field \"{extra[0]}\" (allowed: {', '.join(sorted(INVERSION_FIELDS))})")
    if not isinstance(inv.get("settings", {}), dict) or not all(
            isinstance(v, (int, float)) for v in inv.get("settings", {}).values()):
        fail(f"{where}: inversion.settings must be an object of optimiser setting: number")
    if loop and inv.get("polish"):
        fail(f"{where}: inversion.polish needs a smooth surrogate; it does not apply to dem_in_the_loop")
    if loop and inv.get("algorithm", "sa") == "search":
        fail(f"{where}: inversion.algorithm search samples thousands of points; use an optimiser for dem_in_the_loop")
    known = ask("demcal-invert", "--list-algorithms")
    if inv.get("algorithm", "ga") not in known["algorithms"]:
        fail(f"{where}: inversion.algorithm must be one of {', '.join(known['algorithms'])}")
    if inv.get("objective", "sum-rel") not in known["objectives"]:
        fail(f"{where}: inversion.objective must be one of {', '.join(known['objectives'])}")
    ver = study.get("verification", {})
    if int(ver.get("seeds", 5)) < 2:
        fail(f"{where}: verification.seeds must be at least 2 (a spread needs two runs)")
    ref = study.get("refinement", {"rounds": 0})
    if not isinstance(ref, dict) or set(ref) - {"rounds"} or not isinstance(ref.get("rounds", 0), int) or ref.get("rounds", 0) < 0:
        fail(f"{where}: refinement must be {{\"rounds\": N}} with N >= 0")
    stab = study.get("stability")
    if stab is not None:
        if loop:
            fail(f"{where}: stability repeats the calibration with 5 seeds; with the DEM in the loop that is 5 whole "
                 "calibrations: run the study with other inversion.seed values instead")
        if not isinstance(stab, dict) or set(stab) - {"seeds", "edge_fraction", "small_design_runs"}:
            fail(f"{where}: stability must be an object with seeds, edge_fraction, small_design_runs")
        if int(stab.get("seeds", 5)) < 2:
            fail(f"{where}: stability.seeds must be at least 2")
    for other in study.get("compare_with", []):
        if not isinstance(other, str) or not os.path.exists(other):
            fail(f"{where}: compare_with: {other} is not a study file")
    if int(inv.get("budget", 1)) < 1:
        fail(f"{where}: inversion.budget must be at least 1 evaluation")
    if int(study.get("seeds_per_point", 1)) < 1:
        fail(f"{where}: seeds_per_point must be at least 1")
    return scene, space


def fixed_values(study, scene, space, varied):
    """Every scene parameter not varied: the study's fixed value or the space's reference."""
    values = {}
    refs = {p["name"]: p.get("reference") for p in space.get("parameters", [])}
    for name, spec in scene["parameters"].items():
        if name in varied:
            continue
        if isinstance(study.get("fixed"), dict) and name in study["fixed"]:
            values[name] = study["fixed"][name]
        elif refs.get(name) is not None:
            values[name] = refs[name]
        else:
            values[name] = spec["value"]
    values.update(space.get("fixed", {}))
    return values


def subspace(space, factors, fixed):
    params = [p for p in space["parameters"] if p["name"] in factors]
    return {"parameters": params, "fixed": {k: v for k, v in fixed.items()}}


def screening_rules(study, scene, space, cfg):
    """The screening stages: the orthogonal plan over the whole space, its DEM batch, its analysis."""
    screening = study["screening"]
    # The listed factors, or every parameter of the space except those the study fixes.
    study_fixed = study.get("fixed") if isinstance(study.get("fixed"), dict) else {}
    varied = screening.get("factors") or [p["name"] for p in space["parameters"] if p["name"] not in study_fixed]
    # The screening's own fixed values: a factor it varies is not fixed here, even if later stages fix it.
    study = dict(study, fixed={k: v for k, v in study_fixed.items() if k not in varied})
    fixed = fixed_values(study, scene, space, varied)
    screening_space = os.path.join(cfg, "screening_space.json")
    write_if_changed(screening_space, json.dumps(subspace(space, varied, fixed), indent=1) + "\n")
    write_if_changed(os.path.join(cfg, "screening_design.json"), json.dumps(
        {"space": screening_space, "design": screening["design"], "fixed": fixed}, indent=1) + "\n")
    seeds = int(screening.get("seeds", 1))
    write_if_changed(os.path.join(cfg, "screening_batch.json"), json.dumps({"scene": study["scene"], "seeds": seeds}) + "\n")
    write_if_changed(os.path.join(cfg, "screening.json"), json.dumps(
        {"space": screening_space, "outputs": screening["outputs"], "p_threshold": screening.get("p_threshold", 0.05)}) + "\n")
    return [
        "$(D)/screening/design.csv: $(D)/config/screening_design.json $(D)/config/screening_space.json scripts/study.py",
        "\t$(PY) scripts/study.py design $< $@",
        f"$(D)/screening/responses.csv: $(D)/screening/design.csv $(D)/config/screening_batch.json {study['scene']}",
        f"\t$(BIN)/demcal-dem batch --scene {study['scene']} --design $< --out $(D)/screening/responses.h5 "
        f"--csv $(D)/screening/responses.partial.csv --seeds {seeds} --jobs $(JOBS) --cache $(CACHE) || [ $$? -eq 4 ]",
        "\tmv $(D)/screening/responses.partial.csv $@",
        "$(D)/screening/anova.json: $(D)/screening/responses.csv $(D)/config/screening.json",
        "\t$(PY) scripts/study.py screen $(D)", ""]


def choose_factors(study, space, anova):
    """Factors of each "auto" surface: the parameters whose screening ANOVA p lies below the
    threshold for any of its outputs, strongest (largest F) first, at most max_factors; when
    fewer pass than the design needs, the next strongest are added and the report says so."""
    screening = study["screening"]
    threshold = float(screening.get("p_threshold", 0.05))
    limit = int(screening.get("max_factors", 6))
    names = {p["name"] for p in space["parameters"]}
    chosen = {}
    for k, surface in enumerate(study["surfaces"]):
        if surface["factors"] != "auto":
            continue
        best = {}
        for o in surface["outputs"]:
            for name, row in anova.get(o, {}).items():
                if name in names and isinstance(row.get("F"), (int, float)) and isinstance(row.get("p"), (int, float)):
                    f, p = row["F"], row["p"]
                    if name not in best or f > best[name][0]:
                        best[name] = (f, p)
        ranked = sorted(best, key=lambda n: -best[n][0])
        significant = [n for n in ranked if best[n][1] < threshold]
        factors = significant[:limit]
        limits = design_kind(surface["design"]["kind"])
        need = limits["min_factors"]
        note = ""
        if len(significant) > limit:
            note = f"{len(significant)} parameters pass p < {threshold}; the {limit} strongest are kept (max_factors)"
        if len(factors) < need:
            added = [n for n in ranked if n not in factors][:need - len(factors)]
            note = (f"only {len(factors)} parameter(s) pass p < {threshold}; a {surface['design']['kind']} needs {need}, "
                    f"so {', '.join(added)} (the next strongest) joined")
            factors += added
        if len(factors) < need:
            fail(f"surfaces[{k}]: the screening ANOVA ranks only {len(factors)} parameter(s) for "
                 f"{', '.join(surface['outputs'])}; a {surface['design']['kind']} needs {need}")
        most = limits["max_factors"]
        if most and len(factors) > most:
            factors = factors[:most]
            note += f"; a {limits['title']} design takes at most {most}: the {most} strongest are kept"
        chosen[f"g{k + 1}"] = {"outputs": surface["outputs"], "factors": factors, "threshold": threshold,
                               "p": {n: best[n][1] for n in ranked}, "F": {n: best[n][0] for n in ranked}, "note": note}
    return chosen


def analyze_screening(design_csv, responses_csv, factors, outputs, folder, extra_outputs=False):
    """Range analysis and ANOVA of a screening batch, with main-effects and Pareto plots, into
    folder/: screening.csv (design, blank columns joined from the design by run, responses; with
    extra_outputs every other DEM output after them), range and anova as md and json. Returns the
    (run, status) of the points that failed."""
    bin_dir = os.environ.get("BIN", "build/bin")
    with open(design_csv) as f:
        design_rows = {row["run"]: row for row in csv.DictReader(f)}
    blanks = [c for c in next(iter(design_rows.values())) if c.startswith("blank")]
    table = os.path.join(folder, "screening.csv")
    failed = []
    with open(responses_csv) as f, open(table + ".tmp", "w", newline="") as o:
        reader = csv.DictReader(f)
        skip = set(factors) | set(outputs) | {"run", "seed", "status"}
        columns = list(outputs) + ([c for c in reader.fieldnames if c not in skip] if extra_outputs else [])
        writer = csv.writer(o)
        writer.writerow(["run", "seed", "status"] + factors + blanks + columns)
        for row in reader:
            if row["status"] != "ok":
                failed.append((row["run"], row["status"]))
            writer.writerow([row["run"], row["seed"], row["status"]] + [row[c] for c in factors] +
                            [design_rows[row["run"]][c] for c in blanks] + [row.get(x, "nan") for x in columns])
    os.replace(table + ".tmp", table)
    # Blank columns enter as terms and the error is the residual (Minitab's GLM), unless the plan is
    # saturated (3 levels: 2 degrees of freedom a column): then the first blank column is the error.
    error = []
    if blanks and len(design_rows) - 1 - 2 * (len(factors) + len(blanks)) <= 0:
        error = ["--error", f"column:{blanks[0]}"]
    for kind in ("range", "anova"):
        for fmt in ("md", "json"):
            code = subprocess.run([os.path.join(bin_dir, "demcal-analyze"), kind, "--data", table, "--factors",
                                   ",".join(factors + blanks), "--responses", ",".join(outputs), "--format", fmt,
                                   "--out", os.path.join(folder, f"{kind}.{fmt}")] + (error if kind == "anova" else [])).returncode
            if code != 0:
                fail(f"demcal-analyze {kind} failed on {table}")
    plot = ["/usr/bin/python3", "scripts/plot_analysis.py"]
    subprocess.run(plot + ["main-effects", os.path.join(folder, "range.json"), "--out",
                           os.path.join(folder, "main_effects.png")], stdout=subprocess.DEVNULL)
    subprocess.run(plot + ["pareto", os.path.join(folder, "anova.json"), "--out", os.path.join(folder, "pareto.png")],
                   stdout=subprocess.DEVNULL)
    return failed


def screen(out):
    """The screening stage of a study: analyze_screening on its batch."""
    cfg = load_json(os.path.join(out, "config", "screening.json"), "screening config")
    d = os.path.join(out, "screening")
    factors = [p["name"] for p in load_json(cfg["space"], "space")["parameters"]]
    analyze_screening(os.path.join(d, "design.csv"), os.path.join(d, "responses.csv"), factors, cfg["outputs"], d)


def plan(study_path, out):
    study = load_json(study_path, "study")
    scene, space = validate(study, study_path)
    cfg = os.path.join(out, "config")
    seeds = int(study.get("seeds_per_point", 1))
    surrogate = study.get("surrogate", "quadratic")
    loop = study.get("strategy", "surrogate") == "dem_in_the_loop"
    rules = [f"# Generated by scripts/study.py from {study_path}; do not edit.",
             "BIN ?= build/bin", "CACHE ?= build/cache", "JOBS ?= 2", "PY := /usr/bin/python3", f"D := {out}",
             "# study.py's own stages call the tools too: they read these from the environment.",
             "export BIN CACHE JOBS", ""]
    write_if_changed(os.path.join(cfg, "study.json"), json.dumps(study, indent=1, sort_keys=True) + "\n")
    if "screening" in study:
        rules += screening_rules(study, scene, space, cfg)
    two_phase = any(surface["factors"] == "auto" for surface in study.get("surfaces", []))
    if two_phase:
        # The factors come from the screening: make always brings the screening up to date,
        # plans again with what its ANOVA says now, then runs the other stages.
        rules += ["all: $(D)/screening/anova.json",
                  f"\t@$(PY) scripts/study.py plan {study_path} $(D) > /dev/null",
                  "\t@$(MAKE) --no-print-directory -f $(D)/plan.mk BIN=$(BIN) CACHE=$(CACHE) JOBS=$(JOBS) stages",
                  ".PHONY: all stages", ".DEFAULT_GOAL := all", ""]
        anova = os.path.join(out, "screening", "anova.json")
        if not os.path.exists(anova):
            rules += ["stages: ;", ""]
            write_if_changed(os.path.join(out, "plan.mk"), "\n".join(rules))
            print(os.path.join(out, "plan.mk"))
            return
        chosen = choose_factors(study, space, load_json(anova, "screening ANOVA"))
        write_if_changed(os.path.join(cfg, "factors.json"), json.dumps(chosen, indent=1) + "\n")
        for k, surface in enumerate(study["surfaces"]):
            if surface["factors"] == "auto":
                surface["factors"] = chosen[f"g{k + 1}"]["factors"]
    varied_all = study["factors"] if loop else [f for s in study["surfaces"] for f in s["factors"]]
    varied_all = list(dict.fromkeys(varied_all))
    models = []
    for k, surface in enumerate(study.get("surfaces", [])):
        g = f"g{k + 1}"
        fixed = fixed_values(study, scene, space, surface["factors"])
        write_if_changed(os.path.join(cfg, f"space_{g}.json"), json.dumps(subspace(space, surface["factors"], fixed), indent=1) + "\n")
        write_if_changed(os.path.join(cfg, f"design_{g}.json"), json.dumps(
            {"space": os.path.join(cfg, f"space_{g}.json"), "design": surface["design"], "fixed": fixed}, indent=1) + "\n")
        write_if_changed(os.path.join(cfg, f"batch_{g}.json"), json.dumps({"scene": study["scene"], "seeds": seeds}) + "\n")
        rules += [
            f"$(D)/{g}/design.csv: $(D)/config/design_{g}.json $(D)/config/space_{g}.json scripts/study.py",
            "\t$(PY) scripts/study.py design $< $@",
            f"$(D)/{g}/responses.csv: $(D)/{g}/design.csv $(D)/config/batch_{g}.json {study['scene']}",
            f"\t$(BIN)/demcal-dem batch --scene {study['scene']} --design $< --out $(D)/{g}/responses.h5 "
            f"--csv $(D)/{g}/responses.partial.csv --seeds {seeds} --jobs $(JOBS) --cache $(CACHE) || [ $$? -eq 4 ]",
            f"\tmv $(D)/{g}/responses.partial.csv $@", ""]
        for output in surface["outputs"]:
            fit = {"kind": surrogate, "x": surface["factors"], "y": output}
            write_if_changed(os.path.join(cfg, f"fit_{output}.json"), json.dumps(fit) + "\n")
            coding = f" --space $(D)/config/space_{g}.json" if surrogate != "gabp" else " --seed 1"
            rules += [
                f"$(D)/models/{output}.json: $(D)/{g}/responses.csv $(D)/config/fit_{output}.json",
                "\t@mkdir -p $(D)/models",
                f"\t$(BIN)/demcal-fit {surrogate} --data $< --x {','.join(surface['factors'])} --y {output}{coding} "
                f"--out $@ --report $(D)/models/{output}.md --residuals $(D)/models/{output}_residuals.csv --quiet",
                f"\t$(PY) scripts/plot_analysis.py fit $(D)/models/{output}_residuals.csv --out $(D)/models/{output}_fit.png > /dev/null",
                ""]
            models.append(output)
    inv = study.get("inversion", {})
    fixed_inv = fixed_values(study, scene, space, varied_all)
    write_if_changed(os.path.join(cfg, "space_inversion.json"), json.dumps(subspace(space, varied_all, fixed_inv), indent=1) + "\n")
    inversion = {"targets": study["targets"], "algorithm": inv.get("algorithm", "sa" if loop else "ga"),
                 "objective": inv.get("objective", "max-rel" if loop else "sum-rel"),
                 "restarts": int(inv.get("restarts", 1 if loop else 5)),
                 "polish": bool(inv.get("polish", not loop)), "seed": int(inv.get("seed", 1))}
    extra_args = []
    if "population" in inv:
        extra_args += ["--set", f"population={int(inv['population'])}"]
    for name, value in inv.get("settings", {}).items():
        extra_args += ["--set", f"{name}={value}"]
    if "budget" in inv:
        extra_args += ["--budget", str(int(inv["budget"]))]
    if "stop_below" in inv:
        extra_args += ["--stop-below", str(float(inv["stop_below"]))]
    if loop:
        inversion["dem_seeds"] = seeds
    inversion["extra"] = extra_args
    write_if_changed(os.path.join(cfg, "inversion.json"), json.dumps(inversion, indent=1) + "\n")
    targets = " ".join(f"--target {k}={v}" for k, v in study["targets"].items())
    if loop:
        # Every evaluation is a DEM run, stored under solution.json.dem/: an
        # interrupted calibration resumes without repeating a finished run.
        model_args = f"--dem-scene {study['scene']} --dem-seeds {seeds} --jobs $(JOBS) --cache $(CACHE)"
        model_files = study["scene"]
    else:
        model_args = " ".join(f"--model $(D)/models/{m}.json" for m in models)
        model_files = " ".join(f"$(D)/models/{m}.json" for m in models)
    rules += [
        f"$(D)/solution.json: {model_files} $(D)/config/inversion.json $(D)/config/space_inversion.json",
        f"\t$(BIN)/demcal-invert {model_args} {targets} --space $(D)/config/space_inversion.json "
        f"--algo {inversion['algorithm']} --objective {inversion['objective']} --restarts {inversion['restarts']} "
        f"--seed {inversion['seed']}{' --polish' if inversion['polish'] else ''} {' '.join(extra_args)} --out $@ "
        "--history $(D)/inversion_history.csv "
        "|| case $$? in 3|4) ;; *) exit 1 ;; esac", ""]
    ver = study.get("verification", {})
    # In the loop the optimiser saw specimens 1..n: verify on others.
    verification = {"seeds": int(ver.get("seeds", 5)), "tolerance": float(ver.get("tolerance", 0.05)), "scene": study["scene"],
                    "first_seed": seeds + 1 if loop else 1}
    write_if_changed(os.path.join(cfg, "verification.json"), json.dumps(verification) + "\n")
    rules += [
        f"$(D)/verification.json: $(D)/solution.json $(D)/config/verification.json {study['scene']}",
        f"\t$(BIN)/demcal-verify --solution $< --scene {study['scene']} --space $(D)/config/space_inversion.json "
        f"--seeds {verification['seeds']} --first-seed {verification['first_seed']} --tolerance {verification['tolerance']} "
        "--jobs $(JOBS) --cache $(CACHE) "
        f"--work $(D)/verification --md $(D)/verification.md --csv $(D)/verification.csv --out $@", ""]
    write_if_changed(os.path.join(cfg, "refinement.json"), json.dumps(study.get("refinement", {"rounds": 0})) + "\n")
    report_inputs = "$(D)/refined.json $(D)/config/study.json scripts/study.py"
    if "screening" in study:
        report_inputs += " $(D)/screening/anova.json"
    if "stability" in study:
        write_if_changed(os.path.join(cfg, "stability.json"), json.dumps(study["stability"]) + "\n")
        rules += ["$(D)/stability.json: $(D)/refined.json $(D)/config/stability.json",
                  "\t$(PY) scripts/study.py stability $(D)", ""]
        report_inputs += " $(D)/stability.json"
    # Other strategies' results, when they have been run, join the speed-versus-accuracy chart.
    for other in study.get("compare_with", []):
        other_dir = os.path.join(os.path.dirname(out), os.path.splitext(os.path.basename(other))[0])
        report_inputs += f" $(wildcard {os.path.join(other_dir, 'report.md')})"
    rules += [
        "$(D)/refined.json: $(D)/verification.json $(D)/config/refinement.json",
        "\t$(PY) scripts/study.py refine $(D)", "",
        f"$(D)/report.md: {report_inputs}",
        "\t$(PY) scripts/study.py report $(D)", "",
        ] + (["stages: $(D)/report.md", ""] if two_phase else ["all: $(D)/report.md", ".PHONY: all", ".DEFAULT_GOAL := all", ""])
    write_if_changed(os.path.join(out, "plan.mk"), "\n".join(rules))
    print(os.path.join(out, "plan.mk"))


def design(config_path, out_csv):
    cfg = load_json(config_path, "design config")
    d = cfg["design"]
    os.makedirs(os.path.dirname(out_csv) or ".", exist_ok=True)
    cmd = ["build/bin/demcal-doe", d["kind"], "--space", cfg["space"], "--out", out_csv + ".tmp.csv", "--quiet"]
    for key in ("center", "alpha", "runs", "criterion", "blank", "levels"):
        if key in d:
            cmd += [f"--{key}", str(d[key])]
    if subprocess.run(cmd).returncode != 0:
        fail(f"demcal-doe failed for {config_path}")
    with open(out_csv + ".tmp.csv") as f:
        rows = list(csv.reader(f))
    header = rows[0] + list(cfg["fixed"])
    os.makedirs(os.path.dirname(out_csv) or ".", exist_ok=True)
    with open(out_csv + ".tmp2", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in rows[1:]:
            w.writerow(row + [repr(float(v)) for v in cfg["fixed"].values()])
    os.replace(out_csv + ".tmp2", out_csv)
    os.remove(out_csv + ".tmp.csv")


def merged_rows(paths):
    """Rows of several DEM response CSVs (different column orders), status ok only."""
    rows = []
    for path, run_offset in paths:
        with open(path) as f:
            for row in csv.DictReader(f):
                if row.get("status") != "ok":
                    continue
                row["run"] = str(int(row["run"]) + run_offset + int(row.get("seed", 1)))
                rows.append(row)
    return rows


def fit_command(out, g, kind, data, factors, output, model):
    """demcal-fit for one output of surface g: surfaces coded on the surface's space, GA-BP with its seed."""
    coding = ["--seed", "1"] if kind == "gabp" else ["--space", os.path.join(out, "config", f"space_g{g}.json")]
    return ([os.path.join(os.environ.get("BIN", "build/bin"), "demcal-fit"), kind, "--data", data, "--x", ",".join(factors),
             "--y", output] + coding + ["--out", model, "--quiet"])


def invert_command(out, models, targets, seed, solution):
    """demcal-invert on `models` with the study's inversion settings."""
    inversion = load_json(os.path.join(out, "config", "inversion.json"), "inversion")
    cmd = [os.path.join(os.environ.get("BIN", "build/bin"), "demcal-invert")] + models
    for t, v in targets.items():
        cmd += ["--target", f"{t}={v}"]
    return cmd + ["--space", os.path.join(out, "config", "space_inversion.json"), "--algo", inversion["algorithm"],
                  "--objective", inversion["objective"], "--restarts", str(inversion["restarts"]), "--seed", str(seed),
                  "--out", solution, "--quiet"] + (["--polish"] if inversion["polish"] else []) + inversion.get("extra", [])


def verify_command(out, solution, work, ver, md=None):
    """demcal-verify of a solution with the study's verification settings."""
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    verification = load_json(os.path.join(out, "config", "verification.json"), "verification")
    return ([os.path.join(os.environ.get("BIN", "build/bin"), "demcal-verify"), "--solution", solution, "--scene",
             study["scene"], "--space", os.path.join(out, "config", "space_inversion.json"), "--seeds",
             str(verification["seeds"]), "--first-seed", str(verification.get("first_seed", 1)), "--tolerance",
             str(verification["tolerance"]), "--jobs", os.environ.get("JOBS", "2"), "--cache",
             os.environ.get("CACHE", "build/cache"), "--work", work, "--out", ver, "--quiet"]
            + (["--md", md] if md else []))


def run_quiet(cmd):
    """Runs a stage tool; returns (exit code, its last error line)."""
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = [x for x in r.stderr.splitlines() if ": error: " in x]
    return r.returncode, (lines[-1].split(": error: ", 1)[1] if lines else "")


def invert_and_verify(out, name, models, targets, seed, where):
    """One inversion on the study's models with its settings (other seed or targets), verified in DEM."""
    os.makedirs(where, exist_ok=True)
    solution = os.path.join(where, f"{name}_solution.json")
    ver = os.path.join(where, f"{name}_verification.json")
    for stale in (solution, ver):  # never report an earlier run's file as this one's
        if os.path.exists(stale):
            os.remove(stale)
    code, message = run_quiet(invert_command(out, models, targets, seed, solution))
    case = {"case": name, "seed": seed, "targets": targets, "invert_exit": code, "message": message}
    if code not in (0, 3, 4):
        return case
    sol = load_json(solution, "solution")
    case.update({"status": sol["status"], "x": sol["x"], "predicted": sol["predicted"]})
    if code == 3:
        return case  # unreachable: nothing to verify
    code, message = run_quiet(verify_command(out, solution, os.path.join(where, f"{name}_runs"), ver))
    if code == 0 and os.path.exists(ver):
        v = load_json(ver, "verification")
        case.update({"verified": {o: r["relative_error_pct"] for o, r in v["outputs"].items()}, "passed": v["passed"]})
    else:
        case["verify_message"] = message
    return case


def stability(out):
    """The same calibration with other optimiser seeds, a target near the edge of what the
    surrogates reach, and a deliberately too-small design: where each breaks, and what the
    program says."""
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    stab = study["stability"]
    where = os.path.join(out, "stability")
    # The surrogates the calibration ended with (after its refinement rounds, if any).
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    models_dir = os.path.join(os.path.dirname(refined["final"]["solution"]), "models")
    models = []
    for surface in study["surfaces"]:
        for o in surface["outputs"]:
            models += ["--model", os.path.join(models_dir, f"{o}.json")]
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

    # The first surface refitted on the first n runs of its design.
    surface = study["surfaces"][0]
    factors = factors_of(out, 1, surface)
    with open(os.path.join(out, "g1", "responses.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    k = len(factors)
    terms = (k + 1) * (k + 2) // 2 if study.get("surrogate", "quadratic") == "quadratic" else None
    sizes = stab.get("small_design_runs") or ([terms - 1, terms + 2] if terms else [max(4, len(rows) // 4)])
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
            model = os.path.join(where, f"small{n}_{o}.json")
            code, message = run_quiet(fit_command(out, 1, study.get("surrogate", "quadratic"), data, factors, o, model))
            if code != 0:
                case.update({"fit_exit": code, "message": message})
                ok = False
                break
            m = load_json(model, "model")
            case.setdefault("r2_pred", {})[o] = m.get("r2_pred")
            small_models += ["--model", model]
        if ok:
            others = [m for s2 in study["surfaces"][1:] for o in s2["outputs"]
                      for m in ("--model", os.path.join(models_dir, f"{o}.json"))]
            case.update(invert_and_verify(out, f"small{n}", small_models + others, study["targets"], 1, where))
            case["case"] = f"first {n} of {len(rows)} design runs"
        record["small_design"].append(case)
        print(f"stability: design of {n} runs done", flush=True)
    write_target(os.path.join(out, "stability.json"), json.dumps(record, indent=1) + "\n")


def count_rows(path):
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        return sum(1 for _ in csv.DictReader(f))


def study_cost(out):
    """What a calibration cost and gave: DEM runs (screening, designs, DEM in the loop,
    verification, refinement; not the stability checks), wall time of make study, and the
    largest verified relative error of the final solution."""
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    solution = load_json(refined["final"]["solution"], "solution")
    runs = count_rows(os.path.join(out, "screening", "responses.csv"))
    for k in range(1, len(study.get("surfaces", [])) + 1):
        runs += count_rows(os.path.join(out, f"g{k}", "responses.csv"))
    first_solution = load_json(os.path.join(out, "solution.json"), "solution")
    runs += first_solution.get("dem", {}).get("runs", 0)
    runs += len(load_json(os.path.join(out, "verification.json"), "verification")["seeds"])
    runs += sum(r["dem_runs"] for r in refined["rounds"])
    final = load_json(refined["final"]["verification"], "verification")
    errors = [abs(r["relative_error_pct"]) for r in final["outputs"].values()]
    wall = None
    timings = os.path.join(out, "make_wall_s.csv")
    if os.path.exists(timings):
        with open(timings) as f:
            wall = sum(float(r["wall_s"]) for r in csv.DictReader(f))
    if study.get("strategy") == "dem_in_the_loop":
        label = f"DEM in the loop ({solution['algorithm']})"
    else:
        label = {"quadratic": "response surface", "linear": "linear surface", "gabp": "GA-BP network"}[
            study.get("surrogate", "quadratic")] + f" + {solution['algorithm']}"
    return {"name": study["name"], "strategy": label, "dem_runs": runs, "wall_s": wall,
            "max_error_pct": max(errors) if errors else None, "passed": final["passed"],
            "tolerance_pct": 100 * final.get("tolerance", 0)}


def comparison_png(rows, out_png):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        return f"(no chart: {e})"
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for r in rows:
        if r["max_error_pct"] is None:
            continue
        axes[0].scatter(r["dem_runs"], r["max_error_pct"], s=40)
        axes[0].annotate(r["strategy"], (r["dem_runs"], r["max_error_pct"]), fontsize=8, xytext=(4, 4),
                         textcoords="offset points")
        if r["wall_s"] is not None:
            axes[1].scatter(r["wall_s"] / 60, r["max_error_pct"], s=40)
            axes[1].annotate(r["strategy"], (r["wall_s"] / 60, r["max_error_pct"]), fontsize=8, xytext=(4, 4),
                             textcoords="offset points")
    tol = rows[0]["tolerance_pct"]
    largest = [max([r["dem_runs"] for r in rows] + [1]),
               max([r["wall_s"] / 60 for r in rows if r["wall_s"] is not None] + [1])]
    top = max([r["max_error_pct"] for r in rows if r["max_error_pct"] is not None] + [tol])
    for ax, xlabel, right in zip(axes, ("DEM runs", "wall time of make study (min)"), largest):
        ax.axhline(tol, color="grey", linestyle="--", linewidth=1, label=f"tolerance {tol:g} %")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("largest verified relative error (%)")
        ax.set_xlim(0, 1.45 * right)  # room for the labels
        ax.set_ylim(0, 1.15 * top)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Speed versus accuracy of the calibration strategies")
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)
    return None


def comparison_section(study, out):
    rows = [study_cost(out)]
    missing = []
    for other in study.get("compare_with", []):
        d = os.path.join(os.path.dirname(out), os.path.splitext(os.path.basename(other))[0])
        if os.path.exists(os.path.join(d, "refined.json")):
            rows.append(study_cost(d))
        else:
            missing.append(other)
    lines = ["## Cost and accuracy", "",
             "DEM runs of the calibration (screening, designs, DEM in the loop, verification and refinement; not the "
             "stability checks), wall time of `make study` summed over its runs, and the largest relative error of the "
             "final verification:", "",
             "| study | strategy | DEM runs | wall time (min) | largest verified error (%) | passed |", "|---|---|---|---|---|---|"]
    for r in rows:
        wall = f"{r['wall_s'] / 60:.1f}" if r["wall_s"] is not None else "not recorded"
        lines.append(f"| {r['name']} | {r['strategy']} | {r['dem_runs']} | {wall} | {number(r['max_error_pct'], 2)} | "
                     f"{'yes' if r['passed'] else 'no'} |")
    if len(rows) > 1 and comparison_png(rows, os.path.join(out, "speed_accuracy.png")) is None:
        lines += ["", "![DEM runs and wall time against the verified error](speed_accuracy.png)"]
    if missing:
        lines += ["", "Not run yet (run `make study STUDY=...` on them for the comparison): " + ", ".join(missing) + "."]
    return lines + [""]


def stability_section(out):
    path = os.path.join(out, "stability.json")
    if not os.path.exists(path):
        return []
    st = load_json(path, "stability record")

    def errors(case):
        if "verified" in case:
            return ", ".join(f"{o} {e:+.1f} %" for o, e in case["verified"].items())
        return case.get("verify_message", "not verified")

    lines = ["## Stability", "",
             "The same calibration repeated with other optimiser seeds, on the surrogates it ended with (the design is "
             "kept: another design seed would mean a new DEM batch), each solution verified in DEM:",
             "", "| seed | status | solution | verified relative errors | passed |", "|---|---|---|---|---|"]
    for c in st["seeds"]:
        x = ", ".join(f"{k} {v:.4g}" for k, v in c.get("x", {}).items())
        lines.append(f"| {c['seed']} | {c.get('status', c['message'])} | {x} | {errors(c)} | "
                     f"{'yes' if c.get('passed') else 'no'} |")
    e = st.get("edge")
    if e:
        lines += ["", f"A target near the edge: {e['output']} = {e['targets'][e['output']]:.4g}, at {100 * e['fraction']:.0f} % "
                  f"of its attainable range [{e['attainable'][0]:.4g}, {e['attainable'][1]:.4g}] (the other targets "
                  f"unchanged): inversion status **{e.get('status', '-')}**"
                  + (f" ({e['message']})" if e.get("message") else "") + "; verified: " + errors(e) + "."]
    lines += ["", "Deliberately small designs (the first runs of the first surface's design, refitted):", "",
              "| design | fit | predicted R^2 | inversion | verified relative errors |", "|---|---|---|---|---|"]
    for c in st["small_design"]:
        if "fit_exit" in c:
            lines.append(f"| {c['case']} | refused: {c['message']} | - | - | - |")
            continue
        r2 = ", ".join(f"{o} {number(v, 3)}" for o, v in c.get("r2_pred", {}).items())
        lines.append(f"| {c['case']} | ok | {r2} | {c.get('status', c.get('message', '-'))} | {errors(c)} |")
    return lines + [""]


def factors_of(out, g, surface):
    """A surface's factors: listed in the study, or chosen by the screening (config/factors.json)."""
    if surface["factors"] != "auto":
        return surface["factors"]
    return load_json(os.path.join(out, "config", "factors.json"), "chosen factors")[f"g{g}"]["factors"]


def refine(out):
    """Adds each verification's DEM runs to the data, refits, re-inverts and re-verifies."""
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    rounds = int(study.get("refinement", {}).get("rounds", 0))
    inversion = load_json(os.path.join(out, "config", "inversion.json"), "inversion")
    verification = load_json(os.path.join(out, "config", "verification.json"), "verification")
    current = {"solution": os.path.join(out, "solution.json"), "verification": os.path.join(out, "verification.json"),
               "runs": os.path.join(out, "verification", "runs.csv")}
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
            rows = merged_rows([(os.path.join(out, f"g{g}", "responses.csv"), 0)] + added)
            columns = ["run"] + factors_of(out, g, surface) + surface["outputs"]
            data = os.path.join(rd, f"data_g{g}.csv")
            with open(data, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(columns)
                for row in rows:
                    w.writerow([row[c] for c in columns])
            for o in surface["outputs"]:
                model = os.path.join(rd, "models", f"{o}.json")
                code = subprocess.run(fit_command(out, g, study.get("surrogate", "quadratic"), data,
                                                  factors_of(out, g, surface), o, model)).returncode
                if code != 0:
                    fail(f"refinement round {k}: demcal-fit failed for {o}")
                models += ["--model", model]
        solution = os.path.join(rd, "solution.json")
        if subprocess.run(invert_command(out, models, study["targets"], inversion["seed"], solution)).returncode not in (0, 3, 4):
            fail(f"refinement round {k}: demcal-invert failed")
        ver = os.path.join(rd, "verification.json")
        if subprocess.run(verify_command(out, solution, os.path.join(rd, "verification"), ver,
                                         os.path.join(rd, "verification.md"))).returncode != 0:
            fail(f"refinement round {k}: demcal-verify failed")
        v = load_json(ver, "verification")
        record["rounds"].append({"round": k, "data_points": len(rows), "dem_runs": verification["seeds"],
                                 "passed": v["passed"],
                                 "relative_error_pct": {o: r["relative_error_pct"] for o, r in v["outputs"].items()}})
        print(f"refinement round {k}: " + ", ".join(f"{o} {r['relative_error_pct']:+.2f} %" for o, r in v["outputs"].items())
              + (" - passed" if v["passed"] else ""), flush=True)
        current = {"solution": solution, "verification": ver, "runs": os.path.join(rd, "verification", "runs.csv")}
        record["final"] = current
    write_target(os.path.join(out, "refined.json"), json.dumps(record, indent=1) + "\n")


def curves_png(runs_h5, out_png):
    try:
        import h5py
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        return f"(no curve plot: {e})"
    fig, ax = plt.subplots(figsize=(6, 4))
    with h5py.File(runs_h5, "r") as f:
        for name in sorted(f["points"]):
            g = f["points"][name]
            if "curve_axial_strain" in g and "curve_stress_MPa" in g:
                ax.plot(g["curve_axial_strain"][:] * 100, g["curve_stress_MPa"][:], label=name.replace("run1_", ""))
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("axial stress (MPa)")
    ax.set_title("Verification runs at the calibrated parameters")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    return None


def convergence_png(history_csv, out_png, objective_kind):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        return f"(no convergence plot: {e})"
    with open(history_csv) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return "(empty history)"
    fig, ax = plt.subplots(figsize=(6, 4))
    for restart in sorted({r["restart"] for r in rows}):
        pts = [(int(r["evaluations"]), float(r["best_objective"])) for r in rows if r["restart"] == restart]
        ax.step([p[0] for p in pts], [p[1] for p in pts], where="post", label=f"run {restart}")
    ax.set_yscale("log")
    ax.set_xlabel("evaluations (DEM runs asked for)")
    ax.set_ylabel(f"best {objective_kind}")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(out_png, dpi=150)
    plt.close(fig)
    return None


def md_to_html(md, base):
    """Enough Markdown for the report: headings, tables, images (inlined), paragraphs, code."""
    out, table, code = [], [], False
    def flush_table():
        if not table:
            return
        out.append("<table>")
        for i, row in enumerate(table):
            if i == 1 and set(row.replace("|", "").strip()) <= set("-: "):
                continue
            cells = [c.strip() for c in row.strip().strip("|").split("|")]
            tag = "th" if i == 0 else "td"
            out.append("<tr>" + "".join(f"<{tag}>{html.escape(c)}</{tag}>" for c in cells) + "</tr>")
        out.append("</table>")
        table.clear()
    for line in md.split("\n"):
        if line.startswith("```"):
            flush_table()
            out.append("</pre>" if code else "<pre>")
            code = not code
            continue
        if code:
            out.append(html.escape(line))
            continue
        if line.startswith("|"):
            table.append(line)
            continue
        flush_table()
        m = re.match(r"!\[(.*)\]\((.*)\)", line.strip())
        if m:
            path = os.path.join(base, m.group(2))
            if os.path.exists(path):
                data = base64.b64encode(open(path, "rb").read()).decode()
                out.append(f'<p><img alt="{html.escape(m.group(1))}" src="data:image/png;base64,{data}" style="max-width:100%"></p>')
            continue
        h = re.match(r"(#+) (.*)", line)
        if h:
            n = len(h.group(1))
            out.append(f"<h{n}>{html.escape(h.group(2))}</h{n}>")
        elif line.strip():
            out.append(f"<p>{html.escape(line)}</p>")
    flush_table()
    style = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}table{border-collapse:collapse;"
             "margin:1em 0}td,th{border:1px solid #bbb;padding:.2em .5em;text-align:left}th{background:#eee}")
    return f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>demcal report</title><style>{style}</style></head><body>\n" + \
        "\n".join(out) + "\n</body></html>\n"


def number(value, digits=4):
    """A statistic for the report: fixed digits, or a dash when the tool wrote null."""
    return f"{value:.{digits}f}" if isinstance(value, (int, float)) else "-"


def screening_section(study, out):
    if "screening" not in study:
        return []
    d = os.path.join(out, "screening")
    sc = study["screening"]
    with open(os.path.join(d, "screening.csv")) as f:
        rows = list(csv.DictReader(f))
    failed = [r for r in rows if r["status"] != "ok"]
    lines = ["## Screening", "",
             f"Orthogonal plan of {sc['design'].get('runs', '?')} runs over the whole space "
             f"({sc['design'].get('blank', 0)} blank column(s)), {sc.get('seeds', 1)} seed(s) per point: "
             f"{len(rows)} DEM runs, {len(failed)} failed" + (" (left out of the analysis)" if failed else "") + ".", ""]
    lines += open(os.path.join(d, "range.md")).read().rstrip().split("\n")
    for o in sc["outputs"]:
        if os.path.exists(os.path.join(d, f"main_effects_{o}.png")):
            lines += ["", f"![main effects on {o}](screening/main_effects_{o}.png)"]
    lines += [""] + open(os.path.join(d, "anova.md")).read().rstrip().split("\n")
    for o in sc["outputs"]:
        if os.path.exists(os.path.join(d, f"pareto_{o}.png")):
            lines += ["", f"![Pareto chart of F for {o}](screening/pareto_{o}.png)"]
    lines += ["", "### Factors kept for the response surfaces", "",
              "| surface | outputs | factors | how chosen |", "|---|---|---|---|"]
    chosen_path = os.path.join(out, "config", "factors.json")
    chosen = load_json(chosen_path, "chosen factors") if os.path.exists(chosen_path) else {}
    for k, surface in enumerate(study.get("surfaces", []), start=1):
        c = chosen.get(f"g{k}")
        if c:
            how = (f"screening ANOVA, p < {c['threshold']}: " +
                   ", ".join(f"{n} (p = {c['p'][n]:.2g})" for n in c["factors"]) + (f"; {c['note']}" if c["note"] else ""))
            factors = c["factors"]
        else:
            how, factors = "listed in the study", surface["factors"]
        lines.append(f"| g{k} | {', '.join(surface['outputs'])} | {', '.join(factors)} | {how} |")
    return lines + [""]


def report(out):
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    final = refined["final"]
    first = load_json(os.path.join(out, "verification.json"), "verification")
    solution = load_json(final["solution"], "solution")
    lines = [f"# Calibration report: {study['name']}", "", study.get("description", ""), "",
             f"Scene `{study['scene']}`, space `{study['space']}`.", "", "## Targets and parameter space", "",
             "| output | target |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in study["targets"].items()]
    space = load_json(os.path.join(out, "config", "space_inversion.json"), "space")
    lines += ["", "| varied parameter | low | high |", "|---|---|---|"]
    lines += [f"| {p['name']} | {p['low']} | {p['high']} |" for p in space["parameters"]]
    lines += ["", "Fixed: " + ", ".join(f"{k} = {v}" for k, v in space.get("fixed", {}).items()), ""]
    lines += screening_section(study, out)
    loop = study.get("strategy", "surrogate") == "dem_in_the_loop"
    if loop:
        dem = solution.get("dem", {})
        lines += ["## DEM in the loop", "",
                  f"No surrogate: every evaluation of {solution['algorithm']} was a DEM run of `{study['scene']}` "
                  f"({dem.get('seeds_per_point', 1)} specimen(s) per point, {dem.get('jobs', 1)} at once). "
                  f"{solution['evaluations']} evaluations asked for {dem.get('points', 0)} distinct points: "
                  f"**{dem.get('runs', 0)} DEM runs** ({dem.get('runs_failed', 0)} failed), "
                  f"{dem.get('dem_wall_s', 0) / 60:.1f} min of DEM wall time"
                  + (f"; {dem['runs_reused']} of them were made by an interrupted earlier attempt and reused"
                     if dem.get("runs_reused") else "") + ". The verification below uses other specimens (seeds "
                  f"{dem.get('seeds_per_point', 1) + 1} onwards) than the one(s) the optimiser saw.", ""]
        history = os.path.join(out, "inversion_history.csv")
        if os.path.exists(history) and convergence_png(history, os.path.join(out, "convergence.png"),
                                                       solution.get("objective_kind", "")) is None:
            lines += ["![best objective against DEM evaluations](convergence.png)", ""]
        lines += ["## Inversion", "",
                  f"{solution['algorithm']}, objective {solution['objective_kind']}, {len(solution['restarts'])} run(s), "
                  f"status **{solution['status']}**" + (f": {solution.get('reason', '')}" if solution['status'] != 'ok' else "")
                  + ".", "", "| parameter | value | spread over restarts (min - max) | identified |", "|---|---|---|---|"]
    else:
        lines += ["## Surrogates", "",
                  "| output | model | runs | R^2 | adjusted R^2 | predicted R^2 |", "|---|---|---|---|---|---|"]
        figures = []
        for surface in study["surfaces"]:
            for o in surface["outputs"]:
                m = load_json(os.path.join(out, "models", f"{o}.json"), "model")
                if m["kind"] == "gabp":
                    # Training R^2 and the hold-out R^2 of the rows it never trained on.
                    t, v = m.get("training", {}), m.get("validation", {})
                    lines.append(f"| {o} | gabp | {t.get('rows', 0) + v.get('rows', 0)} | {number(t.get('r2', {}).get(o))} | "
                                 f"- | {number(v.get('r2', {}).get(o))} (hold-out, {v.get('rows', 0)} rows) |")
                    continue
                r = m["responses"][0] if "responses" in m else {}
                lines.append(f"| {o} | {m['kind']} | {r.get('runs', '')} | {number(m.get('r2'))} | "
                             f"{number(m.get('r2_adj'))} | {number(m.get('r2_pred'))} |")
                figures.append(f"![fit of {o}](models/{o}_fit.png)")
        lines += [""] + figures + ["", "## Inversion", "",
                  f"{solution['algorithm']}, objective {solution['objective_kind']}, {len(solution['restarts'])} restarts, "
                  f"{solution['evaluations']} evaluations, status **{solution['status']}**"
                  + (f": {solution.get('reason', '')}" if solution['status'] != 'ok' else "") + ".", "",
                  "| parameter | value | spread over restarts (min - max) | identified |", "|---|---|---|---|"]
    if refined["rounds"]:
        lines.insert(len(lines) - 3, f"(The solution of the last refinement round, {len(refined['rounds'])}; its surrogates "
                                     "were refitted with the verification runs added.)")
        lines.insert(len(lines) - 3, "")
    for name, value in solution["x"].items():
        s = solution.get("spread", {}).get(name)
        spread = f"{s['min']:.4g} - {s['max']:.4g}" if s else ""
        ident = ("yes" if s["identified"] else "no") if s else ""
        lines.append(f"| {name} | {value:.4g} | {spread} | {ident} |")
    source = "DEM run at the solution" if loop else "surrogate at the solution"
    lines += ["", f"| output | target | {source} | attainable range |", "|---|---|---|---|"]
    for o, t in solution["targets"].items():
        a = solution["attainable"].get(o)
        attainable = f"{a['min']:.4g} - {a['max']:.4g}" if a else "not assessed"
        predicted = solution["predicted"].get(o)
        lines.append(f"| {o} | {t} | {number(predicted, 4) if predicted is None else f'{predicted:.4g}'} | {attainable} |")
    if solution.get("unidentified"):
        lines += ["", "Not identified by these targets (restarts that meet them spread over more than half the range): "
                  + ", ".join(solution["unidentified"]) + "."]
    lines += ["", "## Verification in DEM", ""]
    if refined["rounds"]:
        lines += ["The first verification " + ("passed" if first["passed"] else "failed") + ": " +
                  ", ".join(f"{o} {r['relative_error_pct']:+.2f} %" for o, r in first["outputs"].items()) +
                  ". Refinement (its DEM runs added to the data, surrogates refitted, inverted and verified again):", "",
                  "| round | data points | DEM runs | relative errors | passed |", "|---|---|---|---|---|"]
        for r in refined["rounds"]:
            errors = ", ".join(f"{o} {e:+.2f} %" for o, e in r["relative_error_pct"].items())
            lines.append(f"| {r['round']} | {r['data_points']} | {r['dem_runs']} | {errors} | {'yes' if r['passed'] else 'no'} |")
        lines += ["", "The final round:", ""]
    lines += open(final["verification"].replace(".json", ".md")).read().rstrip().split("\n")
    runs = os.path.join(os.path.dirname(final["verification"]), "verification", "runs.h5")
    if os.path.exists(runs) and curves_png(runs, os.path.join(out, "verification_curves.png")) is None:
        lines += ["", "![stress-strain curves](verification_curves.png)"]
    lines += [""] + stability_section(out) + comparison_section(study, out)
    text = "\n".join(lines) + "\n"
    write_if_changed(os.path.join(out, "report.md"), text)
    write_if_changed(os.path.join(out, "report.html"), md_to_html(text, out))
    print(os.path.join(out, "report.md"))
    print(os.path.join(out, "report.html"))


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("plan", "design", "screen", "refine", "stability", "report"):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    command = sys.argv[1]
    if command == "plan" and len(sys.argv) == 4:
        plan(sys.argv[2], sys.argv[3])
    elif command == "design" and len(sys.argv) == 4:
        design(sys.argv[2], sys.argv[3])
    elif command == "screen" and len(sys.argv) == 3:
        screen(sys.argv[2])
    elif command == "stability" and len(sys.argv) == 3:
        stability(sys.argv[2])
    elif command == "refine" and len(sys.argv) == 3:
        refine(sys.argv[2])
    elif command == "report" and len(sys.argv) == 3:
        report(sys.argv[2])
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
