"""Study files: a bad one stops `python -m demcal_study plan` with exit 2 and one line that names the file and
the field; a good one plans. Structure errors come from the schema before any executable is asked."""
import glob
import json
import os

import pytest

from conftest import REPO, run_study_layer
from demcal_study import schema
from demcal_study.errors import StudyError


def demo():
    with open(os.path.join(REPO, "data", "studies", "demo.json")) as f:
        return json.load(f)


def loop():
    with open(os.path.join(REPO, "data", "studies", "rock_dem_in_the_loop.json")) as f:
        return json.load(f)


def edited(base, change):
    study = base()
    change(study)
    return study


def plan_error(tmp_path, study, bin_dir=""):
    """The one error line of planning `study`, after checking it is one line and the exit code is 2."""
    path = tmp_path / "bad.json"
    path.write_text(study if isinstance(study, str) else json.dumps(study))
    done = run_study_layer(["plan", str(path), str(tmp_path / "out")], bin_dir)
    lines = done.stderr.splitlines()
    assert done.returncode == 2, done.stderr
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith(f"demcal_study: error: {path}: "), lines[0]
    return lines[0]


# Structure: the schema alone (no executable is asked: BIN points nowhere).
SCHEMA_CASES = [
    (lambda d: d.update(surogate="quadratic"), 'unknown field "surogate" (allowed: '),
    (lambda d: d["inversion"].update(restarts="a"), "inversion.restarts: 'a' is not of type 'integer'"),
    (lambda d: d["targets"].update(sigma_u_MPa=0), "targets.sigma_u_MPa must be a non-zero number"),
    (lambda d: d["surfaces"][0]["design"].update(kind="ccf"), "surfaces[0].design.kind must be one of bbd, ccd, lhs"),
    (lambda d: d["surfaces"][0]["design"].update(centre=3), 'surfaces[0].design: unknown field "centre"'),
    (lambda d: d.pop("name"), 'missing "name"'),
    (lambda d: d.update(fixed="refrence"), 'fixed must be "reference" or an object of parameter: value'),
    (lambda d: d.update(fixed={"mu": "high"}), "fixed.mu: 'high' is not of type 'number'"),
    (lambda d: d["verification"].update(seeds=1), "verification.seeds must be at least 2"),
    (lambda d: d["verification"].update(seeds=5, max_seeds=3), "verification.max_seeds (3) must be at least verification.seeds (5)"),
    (lambda d: d.update(screening={"design": {"kind": "oa"}, "outputs": ["nu"], "p_threshold": 1.5}),
     "screening.p_threshold must lie in (0, 1)"),
    (lambda d: d.update(strategy="dem-in-loop"), "strategy must be one of dem_in_the_loop, surrogate, trust_region"),
    (lambda d: d.update(name="my study"), "name must be letters, digits"),
]


@pytest.mark.parametrize("change,expected", SCHEMA_CASES, ids=[c[1][:30] for c in SCHEMA_CASES])
def test_structure_errors_name_the_field(tmp_path, change, expected):
    assert expected in plan_error(tmp_path, edited(demo, change))


@pytest.mark.parametrize("token", ["NaN", "Infinity", "1e400"])
def test_a_number_that_is_not_finite(tmp_path, token):
    text = json.dumps(demo()).replace('"sigma_u_MPa": 25', f'"sigma_u_MPa": {token}')
    line = plan_error(tmp_path, text)
    assert "targets.sigma_u_MPa: " in line and line.endswith(" is not a finite number"), line


def test_a_file_that_is_not_json(tmp_path):
    assert "not valid JSON" in plan_error(tmp_path, '{"name": "x",}')


def test_a_missing_file(tmp_path):
    done = run_study_layer(["plan", str(tmp_path / "none.json"), str(tmp_path / "out")])
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "cannot open study" in done.stderr


@pytest.mark.parametrize("path", sorted(glob.glob(os.path.join(REPO, "data", "studies", "*.json"))))
def test_every_shipped_study_fits_the_schema(path):
    with open(path) as f:
        schema.check(json.load(f), path)


def test_the_schema_is_a_valid_draft7_schema():
    import jsonschema
    jsonschema.Draft7Validator.check_schema(schema.schema())


def test_schema_check_raises_the_error_in_process():
    with pytest.raises(StudyError, match=r"^x.json: inversion.restarts: 'a' is not of type 'integer'$"):
        schema.check(edited(demo, lambda d: d["inversion"].update(restarts="a")), "x.json")


# What involves the scene, the space, the executables or another field: validate.py (asks the executables).
CROSS_CASES = [
    (demo, lambda d: d["targets"].update(density=2400), "targets.density: not a DEM output"),
    (demo, lambda d: d["targets"].update({"sigma_t_MPa/sigma_u_MPa": 0.1}),
     "targets.sigma_t_MPa/sigma_u_MPa: not a DEM output, nor a ratio A/B of two"),
    (demo, lambda d: d["targets"].update({"sigma_u_MPa/": 0.1}), 'targets: "sigma_u_MPa/" is not an output or a ratio'),
    (demo, lambda d: d.update(tests=["data/scenes/ucs_rock_pb.json"]), 'give either "scene" (one lab test) or "tests"'),
    (demo, lambda d: d.update(scene="data/scenes/no_such_scene.json"),
     "scene: demcal-dem: error: data/scenes/no_such_scene.json: cannot open scene file"),
    (demo, lambda d: d["surfaces"][0]["factors"].__setitem__(-1, "kn_ks_x"), "factor kn_ks_x is not a parameter"),
    (demo, lambda d: d["surfaces"][0].update(factors="auto"), 'add a "screening" stage'),
    (demo, lambda d: d["surfaces"][0].update(factors=["Ec_GPa", "kn_ks"]),
     "surfaces[0]: a Box-Behnken design needs 3 to 7 factors, not 2"),
    (demo, lambda d: d["inversion"].update(algorithm="pso"), "inversion.algorithm must be one of ga, sa"),
    (demo, lambda d: d.update(screening={"design": {"kind": "lhs"}, "outputs": ["nu"]}),
     'screening: design.kind must be "oa"'),
    (loop, lambda d: d.update(surfaces=[]), '"surfaces" does not apply to strategy dem_in_the_loop'),
    (loop, lambda d: d["inversion"].update(polish=True), "polish needs a smooth surrogate"),
    (loop, lambda d: d["inversion"].update(objective="minimise"), "minimise drives one output down: give exactly one target"),
    (demo, lambda d: d.update(targets={"E_GPa": 30}) or d["inversion"].update(objective="minimise", polish=True),
     "polish fits outputs to targets by least squares; it does not apply to objective minimise"),
    (demo, lambda d: [d.pop(k) for k in ("surfaces", "surrogate", "inversion", "verification", "refinement",
                                          "seeds_per_point", "stability")]
     and d.update(screening={"design": {"kind": "oa", "runs": 18}, "outputs": ["nu"]}),
     '"targets" does not apply to a screening alone'),
]


@pytest.mark.parametrize("base,change,expected", CROSS_CASES, ids=[c[2][:30] for c in CROSS_CASES])
def test_cross_field_errors_name_the_field(tmp_path, bin_dir, base, change, expected):
    assert expected in plan_error(tmp_path, edited(base, change), bin_dir)


def test_a_good_study_plans(tmp_path, bin_dir):
    done = run_study_layer(["plan", "data/studies/demo.json", str(tmp_path / "demo")], bin_dir)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == str(tmp_path / "demo" / "plan.mk")
    assert (tmp_path / "demo" / "config" / "inversion.json").exists()


def test_a_screening_alone_plans_its_screening_and_report(tmp_path, bin_dir):
    done = run_study_layer(["plan", "data/studies/concrete_screening.json", str(tmp_path / "s")], bin_dir)
    assert done.returncode == 0, done.stderr
    plan = (tmp_path / "s" / "plan.mk").read_text()
    assert "$(D)/screening/anova.json:" in plan and "$(D)/report.md: $(D)/screening/anova.json" in plan
    assert "solution.json" not in plan and "refined.json" not in plan


def rock_with_tensile_ratio():
    """The rock surface study on a UCS and a Brazilian test per point, with sigma_t / sigma_u as a target."""
    with open(os.path.join(REPO, "data", "studies", "rock_response_surface.json")) as f:
        study = json.load(f)
    study.pop("scene")
    study["tests"] = ["data/scenes/ucs_rock_cb.json", "data/scenes/brazilian_rock_cb.json"]
    study["targets"]["sigma_t_MPa/sigma_u_MPa"] = 0.2
    study["screening"]["outputs"].append("sigma_t_MPa/sigma_u_MPa")
    study["surfaces"][0]["outputs"].append("sigma_t_MPa/sigma_u_MPa")
    study["surfaces"][0]["factors"] = ["Ec_Pa", "kn_ks", "cb_sigma_c_mean_Pa"]  # planned now, not after the screening
    return study


def test_a_study_of_several_tests_plans_them_as_one_list(tmp_path, bin_dir):
    path = tmp_path / "two_tests.json"
    path.write_text(json.dumps(rock_with_tensile_ratio()))
    done = run_study_layer(["plan", str(path), str(tmp_path / "s")], bin_dir)
    assert done.returncode == 0, done.stderr
    listed = json.loads((tmp_path / "s" / "config" / "tests.json").read_text())
    config = tmp_path / "s" / "config"
    assert [os.path.normpath(os.path.join(config, p)) for p in listed["tests"]] == [
        os.path.join(REPO, "data", "scenes", "ucs_rock_cb.json"), os.path.join(REPO, "data", "scenes", "brazilian_rock_cb.json")]
    study = json.loads((config / "study.json").read_text())
    assert study["scene"] == str(config / "tests.json") and "tests" not in study
    # A stage that runs the tests is remade when one of their scene files changes.
    plan = (tmp_path / "s" / "plan.mk").read_text()
    assert "data/scenes/brazilian_rock_cb.json" in plan
    # A ratio's surface is a file of its own, not a sub-folder.
    assert "$(D)/models/sigma_t_MPa_over_sigma_u_MPa.json:" in plan
    assert (config / "fit_sigma_t_MPa_over_sigma_u_MPa.json").exists()


def test_tests_must_be_scene_files(tmp_path, bin_dir):
    study = rock_with_tensile_ratio()
    study["tests"][1] = "data/scenes/no_such.json"
    assert "tests[1]: data/scenes/no_such.json is not a scene file" in plan_error(tmp_path, study, bin_dir)


def four_targets():
    with open(os.path.join(REPO, "data", "studies", "rock_four_targets.json")) as f:
        return json.load(f)


TRUST_REGION_CASES = [
    (lambda d: d.pop("budget"), 'missing "budget" (strategy trust_region)'),
    (lambda d: d.update(surfaces=[]), '"surfaces" does not apply to strategy trust_region'),
    (lambda d: d.update(budget=15), "budget: 15 DEM runs cannot hold a design and a verification (at least 10 points "
                                    "of 2 test(s): 20 test runs)"),
    (lambda d: d["targets"].update(c_MPa=10), "targets.c_MPa: not a DEM output"),
    (lambda d: d.update(fixed={"R_min_mm": 1}), "fixed.R_min_mm: not a parameter of"),
    (lambda d: d.update(scale_parameter="mu_x"), "scale_parameter: mu_x is not a parameter of"),
    (lambda d: d["verification"].update(max_seeds=30), "verification.max_seeds: the trust region starts"),
    (lambda d: d.update(check_tests=["data/scenes/nope.json"]), "check_tests[0]: data/scenes/nope.json is not a scene file"),
    (lambda d: d.update(check_tests=["data/scenes/biaxial_rock_pb.json"]),
     "check_tests[0]: data/scenes/biaxial_rock_pb.json lacks the calibrated parameter(s) fj_c_MPa, fj_phi_deg, "
     "fj_sigma_c_MPa"),
]


@pytest.mark.parametrize("change,expected", TRUST_REGION_CASES, ids=[c[1][:30] for c in TRUST_REGION_CASES])
def test_trust_region_study_errors_name_the_field(tmp_path, bin_dir, change, expected):
    assert expected in plan_error(tmp_path, edited(four_targets, change), bin_dir)


def test_only_a_trust_region_study_takes_a_budget_and_may_leave_out_the_space(tmp_path, bin_dir):
    assert 'missing "space"' in plan_error(tmp_path, edited(demo, lambda d: d.pop("space")), bin_dir)
    assert '"budget" applies to strategy trust_region only' in plan_error(
        tmp_path, edited(demo, lambda d: d.update(budget=80)), bin_dir)


def test_a_trust_region_study_plans_one_calibration_into_its_folder(tmp_path, bin_dir):
    out = tmp_path / "studies" / "rock_four_targets"
    done = run_study_layer(["plan", "data/studies/rock_four_targets.json", str(out)], bin_dir)
    assert done.returncode == 0, done.stderr
    plan = (out / "plan.mk").read_text()
    recipe = [line for line in plan.splitlines() if "demcal_study calibrate" in line]
    assert len(recipe) == 1
    assert f"--scene {out}/config/tests.json" in recipe[0]
    assert "--target sigma_t_MPa=4.57" in recipe[0] and "--budget 120" in recipe[0]
    assert f"--name rock_four_targets --out-root {tmp_path / 'studies'}" in recipe[0]
    # Unreachable (3) and budget spent (4) are results the report states; other exits stop make.
    assert recipe[0].endswith("; code=$$?; [ $$code -eq 0 ] || [ $$code -eq 3 ] || [ $$code -eq 4 ]")
    rule = [line for line in plan.splitlines() if line.startswith("$(D)/report.md:")]
    assert len(rule) == 1 and "data/scenes/brazilian_rock_fj.json" in rule[0] and "mohr.py" in rule[0]


def test_a_trust_region_study_picks_its_search(tmp_path, bin_dir):
    # "search": "kriging" reaches make calibrate's --strategy; the default stays off the line (stored
    # calibrations resume); a surrogate study has no search; an unknown one is named.
    study = edited(four_targets, lambda d: d.update(search="kriging"))
    path = tmp_path / "kriging.json"
    path.write_text(json.dumps(study))
    out = tmp_path / "studies" / "k"
    done = run_study_layer(["plan", str(path), str(out)], bin_dir)
    assert done.returncode == 0, done.stderr
    recipe = [line for line in (out / "plan.mk").read_text().splitlines() if "demcal_study calibrate" in line]
    assert len(recipe) == 1 and "--strategy kriging" in recipe[0]
    done = run_study_layer(["plan", "data/studies/rock_four_targets.json", str(tmp_path / "studies" / "d")], bin_dir)
    assert "--strategy" not in (tmp_path / "studies" / "d" / "plan.mk").read_text()
    assert '"search" applies to strategy trust_region only' in plan_error(
        tmp_path, edited(demo, lambda d: d.update(search="kriging")), bin_dir)
    assert "search must be trust-region, kriging or bayes" in plan_error(
        tmp_path, edited(four_targets, lambda d: d.update(search="simplex")), bin_dir)


def test_a_bayes_study_passes_each_target_with_its_scatter(tmp_path, bin_dir):
    # target_scatter reaches make calibrate as NAME=MEAN+-SD/n=N (n 1 left off); lab_specimens as its option, and
    # its CSV is a prerequisite of the report (a new measurement reruns the calibration).
    specimens = tmp_path / "lab.csv"
    specimens.write_text("test,output,value,specimen\nbrazilian,sigma_t_MPa,4.4,1\nbrazilian,sigma_t_MPa,4.7,2\n")

    def bayes(d):
        d.update(search="bayes", lab_specimens=str(specimens),
                 target_scatter={"sigma_u_MPa": {"sd": 4.0, "n": 5}, "E_GPa": {"sd": 1.2}, "nu": {"sd": 0.02, "n": 3}})
        d["targets"].pop("sigma_t_MPa")
    path = tmp_path / "bayes.json"
    path.write_text(json.dumps(edited(four_targets, bayes)))
    out = tmp_path / "studies" / "b"
    done = run_study_layer(["plan", str(path), str(out)], bin_dir)
    assert done.returncode == 0, done.stderr
    plan = (out / "plan.mk").read_text()
    recipe = [line for line in plan.splitlines() if "demcal_study calibrate" in line]
    assert len(recipe) == 1 and "--strategy bayes" in recipe[0]
    assert "--target sigma_u_MPa=46.96+-4.0/n=5" in recipe[0] and "--target E_GPa=16.82+-1.2 " in recipe[0]
    assert f"--lab-specimens {specimens}" in recipe[0]
    rule = [line for line in plan.splitlines() if line.startswith("$(D)/report.md:")]
    assert str(specimens) in rule[0]


BAYES_CASES = [
    (lambda d: d.update(search="bayes"), "target_scatter.E_GPa: missing: the bayes search weighs each target"),
    (lambda d: d.update(target_scatter={"UCS": {"sd": 1.0}}), "target_scatter.UCS: not one of the targets"),
    (lambda d: d.update(target_scatter={"nu": {"sd": 0}}), "target_scatter"),
    (lambda d: d.update(target_scatter={"nu": {"sd": 0.1, "n": 0}}), "target_scatter"),
    (lambda d: d.update(lab_specimens="no_such_file.csv"), "lab_specimens: no_such_file.csv: cannot read"),
]


@pytest.mark.parametrize("change, message", BAYES_CASES)
def test_a_bad_lab_scatter_is_named(tmp_path, bin_dir, change, message):
    assert message in plan_error(tmp_path, edited(four_targets, change), bin_dir)


def test_lab_specimens_may_not_repeat_a_target(tmp_path, bin_dir):
    specimens = tmp_path / "lab.csv"
    specimens.write_text("test,output,value\n,nu,0.17\n,nu,0.19\n")
    message = plan_error(tmp_path, edited(four_targets, lambda d: d.update(lab_specimens=str(specimens))), bin_dir)
    assert "lab_specimens: nu is also in targets: give it once" in message


def write_lab_curve(path, header="axial_strain,axial_stress_MPa,sd_MPa"):
    rows = [(0.0, 0.0, 0.5), (0.001, 10.0, 0.7), (0.002, 18.0, 0.9), (0.003, 22.0, 1.1), (0.004, 20.0, 1.3)]
    path.write_text(header + "\n" + "".join(",".join(str(x) for x in r) + "\n" for r in rows))
    return str(path)


def test_a_study_passes_its_curves_window_and_discrepancy_to_the_calibration(tmp_path, bin_dir):
    curve = write_lab_curve(tmp_path / "ucs_curve.csv")

    def with_curve(d):
        d.update(search="bayes", curves=[f"ucs:{curve}"], curve_window="0.2:1.0", model_discrepancy=0.1,
                 target_scatter={"sigma_u_MPa": {"sd": 4.0, "n": 5}, "E_GPa": {"sd": 1.2}, "nu": {"sd": 0.02},
                                 "sigma_t_MPa": {"sd": 0.4}})
    path = tmp_path / "curve.json"
    path.write_text(json.dumps(edited(four_targets, with_curve)))
    out = tmp_path / "studies" / "c"
    done = run_study_layer(["plan", str(path), str(out)], bin_dir)
    assert done.returncode == 0, done.stderr
    plan = (out / "plan.mk").read_text()
    recipe = [line for line in plan.splitlines() if "demcal_study calibrate" in line]
    assert f"--curve ucs:{curve} --curve-window 0.2:1.0 --model-discrepancy 0.1" in recipe[0]
    rule = [line for line in plan.splitlines() if line.startswith("$(D)/report.md:")]
    assert curve in rule[0].split()  # a new measured curve reruns the calibration


def test_a_bad_curve_field_is_named(tmp_path, bin_dir):
    curve = write_lab_curve(tmp_path / "c.csv")
    bare = write_lab_curve(tmp_path / "bare.csv", "axial_strain,axial_stress_MPa,lateral_strain")
    cases = [
        (lambda d: d.update(curves=[curve]), f"curves: {curve}: a test list's curve names its test, LABEL:{curve} "
                                             "(labels: ucs, brazilian)"),
        (lambda d: d.update(curves=[f"brazilian:{curve}"]), "the test's curve is 2F / (pi D t) (MPa) against platen "
                                                            "approach / D"),
        (lambda d: d.update(curves=[f"ucs:{curve}"], curve_window="0.2:3"), "curves[0]: " + curve + ": the window 0.2:3"),
        (lambda d: d.update(curve_window="0.2:1"), "curve_window: give the curves it applies to"),
        (lambda d: d.update(model_discrepancy=0.1), "model_discrepancy: only the bayes search weighs"),
        (lambda d: d.update(model_discrepancy=2), "model_discrepancy must lie in (0, 1)"),
        (lambda d: d.update(curves=[f"ucs:{bare}"], search="bayes", target_scatter={
            o: {"sd": 1.0} for o in ("sigma_u_MPa", "E_GPa", "nu", "sigma_t_MPa")}),
         f"curves: ucs:{bare}: the bayes search weighs each point by the lab's scatter"),
    ]
    for change, message in cases:
        assert message in plan_error(tmp_path, edited(four_targets, change), bin_dir), message
