"""plan: a valid study into OUT_DIR/plan.mk, where every stage is a file target, and the stage configs
(OUT_DIR/config/*.json) the targets depend on, each rewritten only when its content changes."""
import json
import os

from . import commands, curve_targets, executables, scatter, schema, strategy
from .commands import IN_MAKE, for_make
from .errors import fail, load_json
from .files import write_if_changed
from .outputs import stem
from .validate import validate
from .values import choose_factors, fixed_values, subspace

PACKAGE = os.path.dirname(os.path.abspath(__file__))

# The code each generated file is made by: a change to it remakes the file.
DESIGN_CODE = ("design.py", "commands.py")
HOLDOUT_CODE = ("holdout.py",)
CANDIDATES_CODE = ("candidates.py",)
REPORT_CODE = ("report.py", "sections.py", "cost.py", "plots.py", "to_html.py")
TRUST_REGION_CODE = ("calibrate.py", "calibrate_report.py", "trust_region.py", "calibration_problem.py", "mohr.py",
                     "plots.py")


def plan(study_path, out):
    study = load_json(study_path, "study")
    cfg = os.path.join(out, "config")
    study = with_test_list(study, study_path, cfg)
    scene, space = validate(study, study_path)
    package = os.path.relpath(PACKAGE)  # plan.mk runs where the plan is made: the source tree
    code = Code(package)
    rules = header(study_path, out, os.path.dirname(package) or ".")
    write_if_changed(os.path.join(cfg, "study.json"), json.dumps(study, indent=1, sort_keys=True) + "\n")
    if strategy.trust_region(study):
        return finish(out, rules + trust_region_rules(study, scene, out))
    if "screening" in study:
        rules += screening_rules(study, scene, space, cfg, code)
    if strategy.screening_only(study):
        rules += [f"$(D)/report.md: $(D)/screening/anova.json $(D)/config/study.json {code.report}",
                  "\t" + for_make(commands.stage(IN_MAKE, "report", "$(D)")), "",
                  "all: $(D)/report.md", ".PHONY: all", ".DEFAULT_GOAL := all", ""]
        return finish(out, rules)
    two_phase = any(surface["factors"] == "auto" for surface in study.get("surfaces", []))
    auto_seeds = strategy.in_the_loop(study) and study.get("seeds_per_point") == "auto"
    first_phase = (["$(D)/screening/anova.json"] if two_phase else []) + (
        ["$(D)/scatter/verification.json"] if auto_seeds else [])
    if auto_seeds:
        rules += scatter_rules(study, scene, space, cfg)
    if first_phase:
        # The factors come from the screening, the specimens per point from the scatter: make always brings
        # those up to date, plans again with what they say now, then runs the other stages.
        rules += ["all: " + " ".join(first_phase),
                  "\t@" + for_make(commands.stage(IN_MAKE, "plan", study_path, "$(D)")) + " > /dev/null",
                  "\t@$(MAKE) --no-print-directory -f $(D)/plan.mk BIN=$(BIN) CACHE=$(CACHE) JOBS=$(JOBS) stages",
                  ".PHONY: all stages", ".DEFAULT_GOAL := all", ""]
        if not all(os.path.exists(f.replace("$(D)", out)) for f in first_phase):
            return finish(out, rules + ["stages: ;", ""])
    if auto_seeds:
        chosen_seeds = scatter.seeds_per_point(load_json(os.path.join(out, "scatter", "verification.json"),
                                                         "scatter verification"),
                                               float(study.get("verification", {}).get("tolerance", 0.05)))
        write_if_changed(os.path.join(cfg, "seeds.json"), json.dumps(chosen_seeds, indent=1) + "\n")
        study["seeds_per_point"] = chosen_seeds["seeds_per_point"]
    if two_phase:
        anova = os.path.join(out, "screening", "anova.json")
        chosen = choose_factors(study, space, load_json(anova, "screening ANOVA"), executables.design_kinds())
        write_if_changed(os.path.join(cfg, "factors.json"), json.dumps(chosen, indent=1) + "\n")
        for k, surface in enumerate(study["surfaces"]):
            if surface["factors"] == "auto":
                surface["factors"] = chosen[f"g{k + 1}"]["factors"]
    models = []
    for k, surface in enumerate(study.get("surfaces", [])):
        rules += surface_rules(study, scene, space, cfg, code, f"g{k + 1}", surface)
        models += [stem(o) for o in surface["outputs"]]
    rules += calibration_rules(study, scene, space, cfg, out, code, models)
    rules += ["stages: $(D)/report.md", ""] if first_phase else ["all: $(D)/report.md", ".PHONY: all",
                                                               ".DEFAULT_GOAL := all", ""]
    return finish(out, rules)


class Code:
    """The package files the plan's targets depend on, as make sees them."""

    def __init__(self, package):
        self.design = " ".join(os.path.join(package, name) for name in DESIGN_CODE)
        self.report = " ".join(os.path.join(package, name) for name in REPORT_CODE)
        self.holdout = " ".join(os.path.join(package, name) for name in HOLDOUT_CODE)
        self.candidates = " ".join(os.path.join(package, name) for name in CANDIDATES_CODE)


def with_test_list(study, study_path, cfg):
    """A study naming several scenes ("tests") runs them as one test list: OUT_DIR/config/tests.json, which
    every stage then takes as its scene (its paths relative to it)."""
    schema.check(study, study_path)
    if "tests" not in study:
        return study
    if "scene" in study:
        fail(f"{study_path}: give either \"scene\" (one lab test) or \"tests\" (several, sharing each point's "
             "parameters), not both")
    for k, path in enumerate(study["tests"]):
        if not os.path.isfile(path):
            fail(f"{study_path}: tests[{k}]: {path} is not a scene file")
    list_path = os.path.join(cfg, "tests.json")
    content = {"name": study["name"] + "_tests", "description": f"the lab tests of the study {study['name']}",
               "tests": [os.path.relpath(os.path.abspath(p), os.path.abspath(cfg)) for p in study["tests"]]}
    write_if_changed(list_path, json.dumps(content, indent=1) + "\n")
    converted = {k: v for k, v in study.items() if k != "tests"}
    converted["scene"] = list_path
    return converted


def scene_files(scene):
    """What a stage that runs the scene depends on: the scene file, and a test list's scenes too."""
    listed = load_json(scene, "scene file").get("tests")
    if not isinstance(listed, list):
        return scene
    base = os.path.dirname(scene)
    return " ".join([scene] + [os.path.relpath(os.path.join(base, p)) for p in listed])


def trust_region_rules(study, scene, out):
    """One stage: `make calibrate`'s command into the study's own folder, which then holds the calibration's
    report.md. Its exits 3 (unreachable) and 4 (budget spent) are results the report states, not failures of the
    study; any other non-zero exit stops make (rerunning resumes)."""
    files = ([study["scene"]] + ([study["space"]] if "space" in study else []) + study.get("check_tests", [])
             + ([study["lab_specimens"]] if "lab_specimens" in study else [])
             + [curve_targets.parse_spec(c)[1] for c in study.get("curves", [])])
    args = commands.calibrate(IN_MAKE, study["scene"], study.get("targets", {}),
                              study.get("verification", {}).get("tolerance", 0.05), study["budget"],
                              os.path.dirname(os.path.normpath(out)) or ".", os.path.basename(os.path.normpath(out)),
                              space=study.get("space"), fixed=study.get("fixed"),
                              scale_parameter=study.get("scale_parameter"),
                              check_resolution=study.get("check_resolution"),
                              check_tests=study.get("check_tests", []), search=study.get("search"),
                              target_scatter=study.get("target_scatter"), lab_specimens=study.get("lab_specimens"),
                              curves=study.get("curves", []), curve_window=study.get("curve_window"),
                              model_discrepancy=study.get("model_discrepancy"))
    code = " ".join(os.path.join(os.path.relpath(PACKAGE), name) for name in TRUST_REGION_CODE)
    return [f"$(D)/report.md: $(D)/config/study.json {scene_files(files[0])} {' '.join(files[1:])} {code}",
            "\t" + for_make(args) + "; code=$$?; [ $$code -eq 0 ] || [ $$code -eq 3 ] || [ $$code -eq 4 ]",
            "", "all: $(D)/report.md", ".PHONY: all", ".DEFAULT_GOAL := all", ""]


def header(study_path, out, pythonpath):
    return [f"# Generated by python -m demcal_study plan from {study_path}; do not edit.",
            "BIN ?= build/bin", "CACHE ?= $(BIN)/../cache", "JOBS ?= 2", f"PY := {commands.PYTHON}", f"D := {out}",
            "# The study layer's own stages call the tools too: they read these from the environment.",
            "export BIN CACHE JOBS",
            "# The study layer's stages are the package demcal_study, run as $(PY) -m demcal_study.",
            f"export PYTHONPATH := {pythonpath}", ""]


def finish(out, rules):
    write_if_changed(os.path.join(out, "plan.mk"), "\n".join(rules))
    print(os.path.join(out, "plan.mk"))


def design_and_batch_rules(folder, config, space_config, batch_config, scene, seeds, code):
    """A design (demcal-doe, fixed values added) and its DEM batch, which keeps its finished points: an
    interrupted batch resumes; exit 4 (some points failed) still gives the responses of the others."""
    return [f"{folder}/design.csv: {config} {space_config} {code.design}",
            "\t" + for_make(commands.stage(IN_MAKE, "design", "$<", "$@")),
            f"{folder}/responses.csv: {folder}/design.csv {batch_config} {scene_files(scene)}",
            "\t" + for_make(commands.dem_batch(IN_MAKE, scene, "$<", f"{folder}/responses.h5",
                                               f"{folder}/responses.partial.csv", seeds)) + " || [ $$? -eq 4 ]",
            f"\tmv {folder}/responses.partial.csv $@"]


def screening_rules(study, scene, space, cfg, code):
    """The screening stages: the orthogonal plan over the whole space, its DEM batch, its analysis."""
    screening = study["screening"]
    # The listed factors, or every parameter of the space except those the study fixes.
    study_fixed = study.get("fixed") if isinstance(study.get("fixed"), dict) else {}
    varied = screening.get("factors") or [p["name"] for p in space["parameters"] if p["name"] not in study_fixed]
    # The screening's own fixed values: a factor it varies is not fixed here, even if later stages fix it.
    fixed = fixed_values(dict(study, fixed={k: v for k, v in study_fixed.items() if k not in varied}), scene, space,
                         varied)
    screening_space = os.path.join(cfg, "screening_space.json")
    write_if_changed(screening_space, json.dumps(subspace(space, varied, fixed), indent=1) + "\n")
    write_if_changed(os.path.join(cfg, "screening_design.json"), json.dumps(
        {"space": screening_space, "scene": study["scene"], "design": screening["design"], "fixed": fixed},
        indent=1) + "\n")
    seeds = int(screening.get("seeds", 1))
    write_if_changed(os.path.join(cfg, "screening_batch.json"), json.dumps({"scene": study["scene"], "seeds": seeds}) + "\n")
    analysis = {"space": screening_space, "outputs": screening["outputs"], "p_threshold": screening.get("p_threshold", 0.05)}
    if strategy.screening_only(study):
        analysis["all_outputs"] = True  # the screening is the result: its table keeps every DEM output
    write_if_changed(os.path.join(cfg, "screening.json"), json.dumps(analysis) + "\n")
    return design_and_batch_rules("$(D)/screening", "$(D)/config/screening_design.json",
                                  "$(D)/config/screening_space.json", "$(D)/config/screening_batch.json",
                                  study["scene"], seeds, code) + [
        "$(D)/screening/anova.json: $(D)/screening/responses.csv $(D)/config/screening.json",
        "\t" + for_make(commands.stage(IN_MAKE, "screen", "$(D)")), ""]


def surface_rules(study, scene, space, cfg, code, g, surface):
    """Surface g: its design over its factors, the DEM batch, one model per output with its fit plot."""
    seeds = int(study.get("seeds_per_point", 1))
    surrogate = study.get("surrogate", "quadratic")
    fixed = fixed_values(study, scene, space, surface["factors"])
    write_if_changed(os.path.join(cfg, f"space_{g}.json"),
                     json.dumps(subspace(space, surface["factors"], fixed), indent=1) + "\n")
    write_if_changed(os.path.join(cfg, f"design_{g}.json"), json.dumps(
        {"space": os.path.join(cfg, f"space_{g}.json"), "scene": study["scene"], "design": surface["design"],
         "fixed": fixed}, indent=1) + "\n")
    write_if_changed(os.path.join(cfg, f"batch_{g}.json"), json.dumps({"scene": study["scene"], "seeds": seeds}) + "\n")
    rules = design_and_batch_rules(f"$(D)/{g}", f"$(D)/config/design_{g}.json", f"$(D)/config/space_{g}.json",
                                   f"$(D)/config/batch_{g}.json", study["scene"], seeds, code) + [""]
    data, data_rule = f"$(D)/{g}/responses.csv", f"$(D)/{g}/responses.csv"
    if "holdout" in surface:
        # Points kept out of every choice of the fit, for an R^2 nothing was tuned on (holdout.py).
        write_if_changed(os.path.join(cfg, f"holdout_{g}.json"),
                         json.dumps({"points": surface["holdout"], "seed": 1}) + "\n")
        data, data_rule = f"$(D)/{g}/train.csv", f"$(D)/{g}/split.json"
        rules += [f"$(D)/{g}/split.json: $(D)/{g}/responses.csv $(D)/config/holdout_{g}.json {code.holdout}",
                  "\t" + for_make(commands.stage(IN_MAKE, "split", f"$(D)/config/holdout_{g}.json", "$<", "$@")), ""]
    for output in surface["outputs"]:
        fit = {"kind": surrogate, "x": surface["factors"], "y": output}
        name = stem(output)  # a ratio A/B as a file name
        write_if_changed(os.path.join(cfg, f"fit_{name}.json"), json.dumps(fit) + "\n")
        rules += [
            f"$(D)/models/{name}.json: {data_rule} $(D)/config/fit_{name}.json",
            "\t@mkdir -p $(D)/models",
            "\t" + for_make(commands.fit(IN_MAKE, surrogate, data, surface["factors"], output,
                                         f"$(D)/config/space_{g}.json", "$@", report=f"$(D)/models/{name}.md",
                                         residuals=f"$(D)/models/{name}_residuals.csv")),
            "\t" + for_make(commands.plot(IN_MAKE, "fit", f"$(D)/models/{name}_residuals.csv",
                                          f"$(D)/models/{name}_fit.png")) + " > /dev/null",
            ""]
        if "holdout" in surface:
            rules += [f"$(D)/models/{name}_holdout.json: $(D)/models/{name}.json $(D)/{g}/split.json {code.holdout}",
                      "\t" + for_make(commands.stage(IN_MAKE, "score", "$<", f"$(D)/{g}/holdout.csv", output, "$@")),
                      ""]
        if surrogate == "gabp":
            # Which parameters drive the output (He et al.'s sensitivity), from the network over its domain.
            rules += [f"$(D)/models/{name}_sobol.json: $(D)/models/{name}.json",
                      "\t" + for_make(commands.sobol(IN_MAKE, "$<", "$@")), ""]
    return rules


def model_products(study):
    """The files beside each model the report reads: held-out scores and a network's Sobol indices."""
    files = []
    for surface in study.get("surfaces", []):
        for output in surface["outputs"]:
            if "holdout" in surface:
                files.append(f"$(D)/models/{stem(output)}_holdout.json")
            if study.get("surrogate", "quadratic") == "gabp":
                files.append(f"$(D)/models/{stem(output)}_sobol.json")
    return files


def inversion_config(study):
    """config/inversion.json: the optimiser and its settings, with the strategy's defaults."""
    inv = study.get("inversion", {})
    loop = strategy.in_the_loop(study)
    objective = inv.get("objective", "max-rel" if loop else "sum-rel")
    inversion = {"targets": study["targets"], "algorithm": inv.get("algorithm", "sa" if loop else "ga"),
                 "objective": objective, "restarts": int(inv.get("restarts", 1 if loop else 5)),
                 # Polishing fits outputs to targets by least squares: a minimisation has none to fit.
                 "polish": bool(inv.get("polish", not loop and objective != "minimise" and inv.get("algorithm") != "search")),
                 "seed": int(inv.get("seed", 1))}
    extra = []
    if "population" in inv:
        extra += ["--set", f"population={int(inv['population'])}"]
    for name, value in inv.get("settings", {}).items():
        extra += ["--set", f"{name}={value}"]
    if "samples" in inv:
        extra += ["--samples", str(int(inv["samples"]))]
    if "search_tolerance" in inv:
        extra += ["--tolerance", repr(float(inv["search_tolerance"]))]
    if "budget" in inv:
        extra += ["--budget", str(int(inv["budget"]))]
    if "stop_below" in inv:
        extra += ["--stop-below", str(float(inv["stop_below"]))]
    if loop:
        inversion["dem_seeds"] = int(study.get("seeds_per_point", 1))
    inversion["extra"] = extra
    return inversion


def scatter_rules(study, scene, space, cfg):
    """seeds_per_point "auto": the targets over scatter.SCATTER_SEEDS specimens at the reference point."""
    fixed = fixed_values(study, scene, space, study["factors"])
    write_if_changed(os.path.join(cfg, "space_scatter.json"),
                     json.dumps(subspace(space, study["factors"], fixed), indent=1) + "\n")
    point = {"status": "ok", "x": scatter.reference_point(study, scene, space), "targets": study["targets"]}
    write_if_changed(os.path.join(cfg, "scatter_point.json"), json.dumps(point, indent=1) + "\n")
    n = scatter.SCATTER_SEEDS
    verification = {"seeds": n, "max_seeds": n, "first_seed": 1,
                    "tolerance": float(study.get("verification", {}).get("tolerance", 0.05))}
    return [f"$(D)/scatter/verification.json: $(D)/config/scatter_point.json $(D)/config/space_scatter.json "
            f"{scene_files(study['scene'])}",
            "\t@mkdir -p $(D)/scatter",
            "\t" + for_make(commands.verify(IN_MAKE, "$<", study["scene"], "$(D)/config/space_scatter.json",
                                            verification, "$(D)/scatter/runs", "$@", md="$(D)/scatter/verification.md")),
            ""]


def calibration_rules(study, scene, space, cfg, out, code, models):
    """Inversion, verification, refinement, stability and the report."""
    loop = strategy.in_the_loop(study)
    seeds = int(study.get("seeds_per_point", 1))
    varied = study["factors"] if loop else [f for s in study["surfaces"] for f in s["factors"]]
    varied = list(dict.fromkeys(varied))
    fixed = fixed_values(study, scene, space, varied)
    write_if_changed(os.path.join(cfg, "space_inversion.json"), json.dumps(subspace(space, varied, fixed), indent=1) + "\n")
    inversion = inversion_config(study)
    write_if_changed(os.path.join(cfg, "inversion.json"), json.dumps(inversion, indent=1) + "\n")
    if loop:
        # Every evaluation is a DEM run, stored under solution.json.dem/: an
        # interrupted calibration resumes without repeating a finished run.
        invert = commands.invert(IN_MAKE, inversion, study["targets"], "$(D)/config/space_inversion.json", "$@",
                                 dem={"scene": study["scene"], "seeds": seeds}, history="$(D)/inversion_history.csv")
        model_files = scene_files(study["scene"])
    else:
        invert = commands.invert(IN_MAKE, inversion, study["targets"], "$(D)/config/space_inversion.json", "$@",
                                 models=[f"$(D)/models/{m}.json" for m in models], history="$(D)/inversion_history.csv")
        model_files = " ".join(f"$(D)/models/{m}.json" for m in models)
    rules = [f"$(D)/solution.json: {model_files} $(D)/config/inversion.json $(D)/config/space_inversion.json",
             "\t" + for_make(invert) + " || case $$? in 3|4) ;; *) exit 1 ;; esac", ""]
    ver = study.get("verification", {})
    # In the loop the optimiser saw specimens 1..n: verify on others.
    # Seeds are added up to max_seeds until every 95 % interval is as narrow as the tolerance.
    verification = {"seeds": int(ver.get("seeds", 5)), "tolerance": float(ver.get("tolerance", 0.05)),
                    "scene": study["scene"], "first_seed": seeds + 1 if loop else 1}
    verification["max_seeds"] = int(ver.get("max_seeds", max(20, verification["seeds"])))
    if "candidates" in ver:
        verification["candidates"] = int(ver["candidates"])
    write_if_changed(os.path.join(cfg, "verification.json"), json.dumps(verification) + "\n")
    if "candidates" in ver:
        # A search's candidates, each verified in DEM; the best verified one is the study's answer.
        rules += [f"$(D)/verification.json: $(D)/solution.json $(D)/config/verification.json "
                  f"{scene_files(study['scene'])} {code.candidates}",
                  "\t" + for_make(commands.stage(IN_MAKE, "candidates", "$(D)")), ""]
    else:
        rules += [f"$(D)/verification.json: $(D)/solution.json $(D)/config/verification.json {scene_files(study['scene'])}",
                  "\t" + for_make(commands.verify(IN_MAKE, "$<", study["scene"], "$(D)/config/space_inversion.json",
                                                  verification, "$(D)/verification", "$@", md="$(D)/verification.md",
                                                  csv="$(D)/verification.csv")), ""]
    write_if_changed(os.path.join(cfg, "refinement.json"), json.dumps(study.get("refinement", {"rounds": 0})) + "\n")
    report_inputs = " ".join([f"$(D)/refined.json $(D)/config/study.json {code.report}"] + model_products(study))
    if "screening" in study:
        report_inputs += " $(D)/screening/anova.json"
    if "stability" in study:
        write_if_changed(os.path.join(cfg, "stability.json"), json.dumps(study["stability"]) + "\n")
        rules += ["$(D)/stability.json: $(D)/refined.json $(D)/config/stability.json",
                  "\t" + for_make(commands.stage(IN_MAKE, "stability", "$(D)")), ""]
        report_inputs += " $(D)/stability.json"
    # Other strategies' results, when they have been run, join the speed-versus-accuracy chart.
    for other in study.get("compare_with", []):
        other_dir = os.path.join(os.path.dirname(out), os.path.splitext(os.path.basename(other))[0])
        report_inputs += f" $(wildcard {os.path.join(other_dir, 'report.md')})"
    return rules + [
        "$(D)/refined.json: $(D)/verification.json $(D)/config/refinement.json",
        "\t" + for_make(commands.stage(IN_MAKE, "refine", "$(D)")), "",
        f"$(D)/report.md: {report_inputs}",
        "\t" + for_make(commands.stage(IN_MAKE, "report", "$(D)")), ""]
