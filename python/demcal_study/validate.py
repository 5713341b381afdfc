"""A study file checked in full: its structure against the schema (schema.py), then what a schema cannot say:
which fields its strategy takes, its names against the scene and the space (through demcal-dem describe), the
scene's outputs, the factor limits of each design kind (demcal-doe) and the algorithms (demcal-invert). The
first problem stops it with one line naming the file and the field."""
import os

from . import curve_targets, executables, lab_targets, schema, strategy
from .errors import Problems, StudyError, fail, load_json
from .outputs import is_output, tests_per_point


def validate(study, path):
    """Returns (scene as demcal-dem describes it, space file) of a valid study read from `path`."""
    schema.check(study, path)
    where = path
    if ("scene" in study) == ("tests" in study):
        fail(f"{where}: give either \"scene\" (one lab test) or \"tests\" (several, sharing each point's parameters)")
    check_strategy_fields(study, where)
    if strategy.trust_region(study):
        return validate_trust_region(study, where)
    if "space" not in study:
        fail(f"{where}: missing \"space\" (the parameter space file)")
    for key in ("budget", "scale_parameter", "check_resolution", "check_tests", "search", "target_scatter",
                "lab_specimens", "curves", "curve_window", "model_discrepancy"):
        if key in study:
            fail(f"{where}: \"{key}\" applies to strategy trust_region only")
    if study.get("seeds_per_point") == "auto" and not strategy.in_the_loop(study):
        fail(f"{where}: seeds_per_point \"auto\" chooses the specimens per DEM-in-the-loop evaluation; "
             "give a number for designs")
    ver = study.get("verification", {})
    if ver.get("max_seeds", 10**9) < ver.get("seeds", 5):
        fail(f"{where}: verification.max_seeds ({ver['max_seeds']}) must be at least verification.seeds "
             f"({ver.get('seeds', 5)})")
    try:
        scene = executables.describe(study["scene"], study["space"])
    except executables.ToolError as e:  # demcal-dem names the scene or space file: name the study's field too
        fail(f"{where}: {'space' if study['space'] in str(e) else 'scene'}: {e}")
    space = load_json(study["space"], "parameter space")
    names = Names(study, scene, space)
    for name in study.get("targets", {}):
        if not is_output(names.outputs, name, f"{where}: targets"):
            fail(f"{where}: targets.{name}: not a DEM output, nor a ratio A/B of two (outputs of {study['scene']}: "
                 f"{', '.join(sorted(names.outputs))})")
    if isinstance(study.get("fixed"), dict):
        for name in study["fixed"]:
            if name not in names.scene_parameters:
                fail(f"{where}: fixed.{name}: not a parameter of {study['scene']}")
    for name in study.get("factors", []):
        names.check_factor(f"{where}: factor {name}", name)
    if "screening" in study:
        check_screening(study["screening"], names, f"{where}: screening")
    covered = set(study["targets"]) if strategy.in_the_loop(study) else set()
    for k, surface in enumerate(study.get("surfaces", [])):
        check_surface(surface, study.get("screening"), names, covered, f"{where}: surfaces[{k}]")
    if strategy.screening_only(study):
        return scene, space
    missing = sorted(set(study["targets"]) - covered)
    if missing:
        fail(f"{where}: target {missing[0]} has no surface (add it to a surfaces[].outputs)")
    check_inversion(study, where)
    if "stability" in study and strategy.in_the_loop(study):
        fail(f"{where}: stability repeats the calibration with 5 seeds; with the DEM in the loop that is 5 whole "
             "calibrations: run the study with other inversion.seed values instead")
    for other in study.get("compare_with", []):
        if not os.path.exists(other):
            fail(f"{where}: compare_with: {other} is not a study file")
    return scene, space


def validate_trust_region(study, where):
    """A "strategy": "trust_region" study: what `make calibrate` takes, as fields. Returns (scene described, space
    file or None)."""
    space_path = study.get("space")
    try:
        scene = executables.describe(study["scene"], space_path)
    except executables.ToolError as e:
        fail(f"{where}: {'space' if space_path and space_path in str(e) else 'scene'}: {e}")
    outputs = set(scene["outputs"])
    measured = check_lab_scatter(study, where, outputs)
    for name in sorted(measured):
        if not is_output(outputs, name, f"{where}: lab_specimens"):
            fail(f"{where}: lab_specimens: {name}: not a DEM output, nor a ratio A/B of two (outputs of "
                 f"{study['scene']}: {', '.join(sorted(outputs))})")
    check_curves(study, where, scene)
    for name in study.get("targets", {}):
        if not is_output(outputs, name, f"{where}: targets"):
            fail(f"{where}: targets.{name}: not a DEM output, nor a ratio A/B of two (outputs of {study['scene']}: "
                 f"{', '.join(sorted(outputs))})")
    if "fixed" in study and not isinstance(study["fixed"], dict):
        fail(f"{where}: fixed: strategy trust_region takes an object of parameter: value (it starts from the "
             "scene's values, or the space's references, anyway)")
    for name in study.get("fixed", {}):
        if name not in scene["parameters"]:
            fail(f"{where}: fixed.{name}: not a parameter of {study['scene']}")
    scale = study.get("scale_parameter")
    if scale is not None and scale not in scene["parameters"]:
        fail(f"{where}: scale_parameter: {scale} is not a parameter of {study['scene']}")
    for k, path in enumerate(study.get("check_tests", [])):
        if not os.path.isfile(path):
            fail(f"{where}: check_tests[{k}]: {path} is not a scene file")
        have = executables.describe(path)["parameters"]
        missing = sorted(set(scene["parameters"]) - set(have))
        if missing:
            fail(f"{where}: check_tests[{k}]: {path} lacks the calibrated parameter(s) {', '.join(missing)}")
    ver = study.get("verification", {})
    for key in ("seeds", "max_seeds"):
        if key in ver:
            fail(f"{where}: verification.{key}: the trust region starts its verifications at 5 seeds and adds up "
                 "to 20 itself; give verification.tolerance only")
    tolerance = ver.get("tolerance", 0.05)
    if not 0 < tolerance < 1:
        fail(f"{where}: verification.tolerance: {tolerance} must lie in (0, 1)")
    tests = tests_per_point(study["scene"])
    if study["budget"] < 10 * tests:
        fail(f"{where}: budget: {study['budget']} DEM runs cannot hold a design and a verification (at least 10 "
             f"points of {tests} test(s): {10 * tests} test runs)")
    return scene, space_path


def check_curves(study, where, scene):
    """Each curve file reads, holds the window and belongs to a uniaxial test of the scene (or, with a confining
    stress, to a confined series that runs it); the bayes search needs its scatter (a specimen or an sd_MPa column);
    a discrepancy needs the bayes search. The first problem fails, naming the field."""
    if "curve_window" in study and "curves" not in study:
        fail(f"{where}: curve_window: give the curves it applies to (\"curves\")")
    if "model_discrepancy" in study and study.get("search") != "bayes":
        fail(f"{where}: model_discrepancy: only the bayes search weighs the targets by their uncertainty "
             "(\"search\": \"bayes\")")
    if "curves" not in study:
        return
    problems = Problems()
    curves = curve_targets.read_curves(study["curves"], study.get("curve_window"), problems, "curves", "curve_window",
                                       each_where=lambda k: f"curves[{k}]", description=scene)
    if study.get("search") == "bayes":
        for c in curves:
            if curve_targets.without_scatter(c):
                problems.add(f"curves: {c['spec']}: the bayes search weighs each point by the lab's scatter: give it "
                             "a specimen column (several specimens' curves), or an sd_MPa column and no lateral_strain "
                             "column")
    if problems:
        fail(f"{where}: {problems.messages[0]}")


def check_lab_scatter(study, where, outputs):
    """target_scatter names targets; lab_specimens is a readable CSV of outputs not also in targets; the bayes search
    has a scatter for every target."""
    scatter, targets = study.get("target_scatter", {}), study.get("targets", {})
    for name in scatter:
        if name not in targets:
            fail(f"{where}: target_scatter.{name}: not one of the targets ({', '.join(sorted(targets)) or 'none'})")
    measured = set()
    if "lab_specimens" in study:
        try:
            by_name, _, _ = lab_targets.named_as_outputs(lab_targets.read_specimens(study["lab_specimens"]), outputs)
        except StudyError as e:  # the CSV's own line names its file and row: add the study's field
            fail(f"{where}: lab_specimens: {e}")
        for name in by_name:
            if name in targets:
                fail(f"{where}: lab_specimens: {name} is also in targets: give it once")
        measured = set(by_name)
    if study.get("search") == "bayes":
        for name in sorted(targets):
            if name not in scatter:
                fail(f"{where}: target_scatter.{name}: missing: the bayes search weighs each target by the lab's "
                     "scatter (give {\"sd\": ..., \"n\": ...}, or the output's specimens in lab_specimens)")
    return measured


def check_strategy_fields(study, where):
    """The fields each shape of study needs and those it refuses (strategy.py)."""
    if strategy.trust_region(study):
        if "targets" not in study and "lab_specimens" not in study:
            fail(f"{where}: missing \"targets\" (strategy trust_region; or \"lab_specimens\", the lab's measurements)")
        if "budget" not in study:
            fail(f"{where}: missing \"budget\" (strategy trust_region)")
        for key in strategy.NOT_TRUST_REGION:
            if key in study:
                fail(f"{where}: \"{key}\" does not apply to strategy trust_region (it chooses its own designs; "
                     "docs/explanation/calibration_method.md)")
        return
    if strategy.screening_only(study):
        for key in strategy.CALIBRATION_ONLY:
            if key in study:
                fail(f"{where}: \"{key}\" does not apply to a screening alone (a study without \"surfaces\")")
        return
    loop = strategy.in_the_loop(study)
    kind = study.get("strategy", "surrogate")
    for key in ("targets",) + (("factors",) if loop else ("surfaces",)):
        if key not in study:
            fail(f"{where}: missing \"{key}\"")
    for key in (("surfaces", "surrogate", "refinement") if loop else ("factors",)):
        if key in study:
            fail(f"{where}: \"{key}\" does not apply to strategy {kind}")


class Names:
    """The parameters and outputs a study may name: the scene's, and the space's varied parameters."""

    def __init__(self, study, scene, space):
        self.scene_path, self.space_path = study["scene"], study["space"]
        self.scene_parameters = set(scene["parameters"])
        self.outputs = set(scene["outputs"])
        self.space_parameters = [p["name"] for p in space.get("parameters", [])]

    def check_factor(self, what, name):
        """A parameter to vary: the space gives its range, the scene must have it."""
        if name not in self.space_parameters:
            fail(f"{what} is not a parameter of {self.space_path} (parameters: {', '.join(self.space_parameters)})")
        if name not in self.scene_parameters:
            fail(f"{what} is not a parameter of {self.scene_path}")

    def check_output(self, what, name):
        if not is_output(self.outputs, name, what):
            fail(f"{what} is not a DEM output, nor a ratio A/B of two")


def check_screening(screening, names, w):
    if screening["design"]["kind"] != "oa":
        fail(f"{w}: design.kind must be \"oa\" (range analysis and ANOVA need an orthogonal plan)")
    for output in screening["outputs"]:
        names.check_output(f"{w}: output {output}", output)
    for name in screening.get("factors", names.space_parameters):
        if name not in names.space_parameters:
            fail(f"{w}: factor {name} is not a parameter of {names.space_path}")
        if name not in names.scene_parameters:
            fail(f"{w}: the space's parameter {name} is not a parameter of {names.scene_path}")


def check_surface(surface, screening, names, covered, w):
    """One surface: its outputs (each fitted once), its factors and whether its design kind takes that many."""
    for output in surface["outputs"]:
        names.check_output(f"{w}: output {output}", output)
        if output in covered:
            fail(f"{w}: output {output} has a surface already")
        covered.add(output)
    if surface["factors"] == "auto":
        if screening is None:
            fail(f"{w}: factors \"auto\" are chosen from the screening ANOVA: add a \"screening\" stage")
        missing = [o for o in surface["outputs"] if o not in screening["outputs"]]
        if missing:
            fail(f"{w}: factors \"auto\" needs output {missing[0]} in screening.outputs")
        return  # the design is checked once the screening has chosen the factors
    for name in surface["factors"]:
        names.check_factor(f"{w}: factor {name}", name)
    design = surface["design"]
    k = len(surface["factors"])
    limits = executables.design_kinds()[design["kind"]]
    if k < limits["min_factors"] or (limits["max_factors"] and k > limits["max_factors"]):
        most = f"to {limits['max_factors']}" if limits["max_factors"] else "or more"
        fail(f"{w}: a {limits['title']} design needs {limits['min_factors']} {most} factors, not {k}")
    quadratic_terms = (k + 1) * (k + 2) // 2
    if design["kind"] == "lhs" and design.get("runs", 0) < quadratic_terms + 1:
        fail(f"{w}: an LHS for a quadratic in {k} factors needs at least {quadratic_terms + 1} runs (design.runs)")


def check_inversion(study, where):
    """The optimiser: one demcal-invert knows, and one that suits the strategy."""
    inv = study.get("inversion", {})
    loop = strategy.in_the_loop(study)
    algorithm = inv.get("algorithm", "sa" if loop else "ga")
    if loop and inv.get("polish"):
        fail(f"{where}: inversion.polish needs a smooth surrogate; it does not apply to dem_in_the_loop")
    if loop and algorithm == "search":
        fail(f"{where}: inversion.algorithm search samples thousands of points; use an optimiser for dem_in_the_loop")
    known = executables.inversion_choices()
    if algorithm not in known["algorithms"]:
        fail(f"{where}: inversion.algorithm must be one of {', '.join(known['algorithms'])}")
    objective = inv.get("objective", "max-rel" if loop else "sum-rel")
    if objective == "minimise":
        # The targets are then references (the output over its reference is driven down), and the verification
        # judges what the optimiser saw at its answer (README, study files).
        if len(study.get("targets", {})) != 1:
            fail(f"{where}: inversion.objective minimise drives one output down: give exactly one target, the "
                 "reference it is divided by (e.g. its value with a fixed boundary)")
        if inv.get("polish"):
            fail(f"{where}: inversion.polish fits outputs to targets by least squares; it does not apply to "
                 "objective minimise")
    if objective not in known["objectives"]:
        fail(f"{where}: inversion.objective must be one of {', '.join(known['objectives'])}")
    for key in ("samples", "search_tolerance"):
        if key in inv and algorithm != "search":
            fail(f"{where}: inversion.{key} is a setting of the search; inversion.algorithm is {algorithm}")
    if "candidates" in study.get("verification", {}) and algorithm != "search":
        fail(f"{where}: verification.candidates verifies a search's mean-shift candidates; inversion.algorithm is "
             f"{algorithm}, whose answer is verified as it stands")
    for surface in study.get("surfaces", []):
        if "holdout" in surface and surface["design"].get("runs") is not None \
                and surface["holdout"] >= surface["design"]["runs"]:
            fail(f"{where}: a surface holds out {surface['holdout']} of its {surface['design']['runs']} design points; "
                 "some must be left to fit on")
