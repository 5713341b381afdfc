"""Nothing a user types wrong costs work or blocks the next try: `calibrate` checks every option (the scene through
demcal-dem describe, the space, the targets against the outputs and their declared physical ranges, the fixed values
against the scene's bounds, the budget, the tolerance, the checks, the strategy) before it writes anything, reports
every problem of the command at once, one line each, exit 2, and the corrected command then runs."""
import json

import numpy as np
import pytest

from conftest import fake_describing_bin, run_study_layer
from demcal_study import calibrate, executables
from demcal_study.__main__ import parser
from demcal_study.errors import Problems, StudyErrors
from test_calibrate import DESCRIPTION, fake  # noqa: F401 (fake: the closed-form stand-in for the DEM)


def with_ranges(description=DESCRIPTION):
    """The stand-in's description with the physical range each output declares (null: no bound on that side)."""
    d = json.loads(json.dumps(description))
    d["outputs"]["E_GPa"]["range"] = [0, None]
    d["outputs"]["sigma_u_MPa"]["range"] = [0, None]
    d["outputs"]["nu"]["range"] = [-1, 1]
    return d


def command(tmp_path, *options):
    scene = tmp_path / "scene.json"
    scene.write_text("{}")
    return parser().parse_args(["calibrate", "--scene", str(scene), "--out-root", str(tmp_path / "calibrations"),
                                "--name", "cal", "--quiet", *options])


def problems_of(args):
    with pytest.raises(StudyErrors) as refused:
        calibrate.calibrate(args)
    return refused.value.messages


def test_a_refused_command_leaves_no_folder_and_the_corrected_one_runs(fake, tmp_path, bin_dir, monkeypatch):
    monkeypatch.setenv("BIN", bin_dir)  # demcal-doe makes the first design
    targets = ["--target", "E_GPa=6.5", "--target", "sigma_u_MPa=48", "--target", "nu=0.2"]
    # A typo in a fixed name: refused before anything is written (the folder used to keep calibration.json, and the
    # corrected command was then refused as "another calibration is stored here").
    messages = problems_of(command(tmp_path, *targets, "--fixed", "muu=0.5"))
    assert messages == ["--fixed: muu is not a parameter of the scene (did you mean mu?)"]
    assert not (tmp_path / "calibrations").exists()
    assert calibrate.calibrate(command(tmp_path, *targets, "--fixed", "mu=0.5")) == calibrate.EXIT_MET
    stored = json.loads((tmp_path / "calibrations" / "cal" / "calibration.json").read_text())
    assert stored["fixed"] == {"mu": 0.5}
    solution = json.loads((tmp_path / "calibrations" / "cal" / "solution.json").read_text())
    assert solution["x"]["mu"] == 0.5


def test_settings_stored_without_any_run_do_not_block_other_settings_but_stored_work_does(fake, tmp_path, bin_dir,
                                                                                          monkeypatch):
    monkeypatch.setenv("BIN", bin_dir)
    targets = ["--target", "E_GPa=6.5", "--target", "sigma_u_MPa=48", "--target", "nu=0.2"]
    folder = tmp_path / "calibrations" / "cal"
    folder.mkdir(parents=True)
    # What a refused command of an earlier version left: its settings, and no DEM run under them.
    (folder / "calibration.json").write_text(json.dumps({"scene": "other.json", "space": None, "targets": {"nu": 1},
                                                         "fixed": {"Ec_GPa": 20}, "tolerance": 0.05, "budget": 80,
                                                         "scale_parameter": None}))
    assert calibrate.calibrate(command(tmp_path, *targets)) == calibrate.EXIT_MET
    assert json.loads((folder / "calibration.json").read_text())["targets"] == {"E_GPa": 6.5, "sigma_u_MPa": 48.0,
                                                                                "nu": 0.2}
    # Once DEM points are stored under the settings, other settings are refused (their results are kept).
    messages = problems_of(command(tmp_path, "--target", "E_GPa=7"))
    assert len(messages) == 1 and "another calibration is stored here" in messages[0]
    assert (folder / "rounds").is_dir()
    # A larger budget is the same calibration, continued: accepted, and stored as the folder's budget.
    assert calibrate.calibrate(command(tmp_path, *targets, "--budget", "120")) == calibrate.EXIT_MET
    assert json.loads((folder / "calibration.json").read_text())["budget"] == 120


def test_every_problem_of_a_command_is_one_line_and_nothing_is_written(tmp_path):
    bin_dir = fake_describing_bin(str(tmp_path / "bin"), with_ranges())
    (tmp_path / "scene.json").write_text("{}")
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--out-root", str(tmp_path / "out"),
                            "--target", "E_GPa=-3", "--target", "nu=0.2", "--target", "nu=0.25",
                            "--target", "sigma_u_MPa=inf", "--target", "E_GPA=3",
                            "--fixed", "Ec_GPa=20", "--fixed", "mu=3", "--fixed", "kn_ks=two",
                            "--budget", "0", "--tolerance", "1", "--strategy", "simplex",
                            "--check-resolution", "0.5", "--check-test", str(tmp_path / "no_such_check.json"),
                            "--no-such-option"], bin_dir)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    expected = [
        "calibrate: unrecognized arguments: --no-such-option",
        "--target: nu is given twice (0.2 and 0.25): give it once",
        "--target: sigma_u_MPa: \"inf\" is not a number, MEAN+-SD or MEAN+-SD/n=N",
        "--fixed: \"kn_ks=two\" is not NAME=NUMBER",
        "--tolerance: 1.0 must lie in (0, 1)",
        "--budget: 0 must be a positive number of DEM runs",
        "--strategy: simplex is not one of trust-region, kriging, bayes",
        "--check-resolution: 0.5 must be above 1 (the radii are divided by it)",
        f"--check-test: {tmp_path / 'no_such_check.json'} does not exist",
        "--target: E_GPa=-3 lies outside its physical range, at least 0 GPa",
        "--target: E_GPA is not an output of the scene, nor a ratio A/B of two (did you mean E_GPa?) "
        "(outputs: E_GPa, nu, sigma_u_MPa)",
        "--fixed: Ec_GPa is not a parameter of the scene (did you mean Ec_Pa?)",
        "--fixed: mu=3 lies outside the scene's physical bounds, 0 to 1",
    ]
    assert lines == ["demcal_study: error: " + m for m in expected], done.stderr
    assert not (tmp_path / "out").exists()


def test_a_scene_demcal_dem_refuses_is_reported_with_the_other_problems(tmp_path):
    (tmp_path / "scene.json").write_text("{}")
    bin_dir = fake_describing_bin(str(tmp_path / "bin"), DESCRIPTION,
                                  fail_on={str(tmp_path / "scene.json"): f"{tmp_path / 'scene.json'}: test: missing"})
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--target", "E_GPa=6.5",
                            "--budget", "x", "--out-root", str(tmp_path / "out")], bin_dir)
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        "demcal_study: error: --budget: \"x\" is not a whole number",
        f"demcal_study: error: demcal-dem: error: {tmp_path / 'scene.json'}: test: missing"]
    assert not (tmp_path / "out").exists()


def test_a_target_is_checked_against_the_range_its_output_declares_and_only_then(monkeypatch, tmp_path):
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: with_ranges())
    assert problems_of(command(tmp_path, "--target", "E_GPa=6.5", "--target", "nu=-1.5")) == [
        "--target: nu=-1.5 lies outside its physical range, -1 to 1"]
    # An output without a declared range is not checked; a ratio A/B has none.
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: DESCRIPTION)
    config, _, _ = calibrate.checked_command(command(tmp_path, "--target", "E_GPa=6.5", "--target", "nu=-1.5"))
    assert config["targets"] == {"E_GPa": 6.5, "nu": -1.5}
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: with_ranges())
    config, _, _ = calibrate.checked_command(command(tmp_path, "--target", "E_GPa=6.5",
                                                     "--target", "sigma_u_MPa/E_GPa=-0.01"))
    assert config["targets"]["sigma_u_MPa/E_GPa"] == -0.01
    assert problems_of(command(tmp_path, "--target", "E_GPa=0")) == [
        "--target: E_GPa: 0 cannot be a target (its errors are relative to it)"]


def test_the_budget_must_hold_the_first_design_and_a_verification(monkeypatch, tmp_path):
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: DESCRIPTION)
    # Three coordinates (kn_ks, mu, sc_Pa over Ec_Pa): 1 reference + 6 design points + 5 verification seeds = 12.
    assert problems_of(command(tmp_path, "--target", "E_GPa=6.5", "--target", "nu=0.2", "--budget", "11")) == [
        "--budget: 11 DEM runs cannot hold a design and a verification (at least 12)"]
    listed = dict(DESCRIPTION, test="list", tests=[{"label": "a"}, {"label": "b"}])
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: listed)
    assert problems_of(command(tmp_path, "--target", "E_GPa=6.5", "--budget", "23")) == [
        "--budget: 23 DEM runs cannot hold a design and a verification (at least 12 points of 2 tests: 24 test runs)"]
    assert calibrate.checked_command(command(tmp_path, "--target", "E_GPa=6.5", "--budget", "24"))[0]["budget"] == 24


def test_a_check_test_that_would_not_test_the_same_material_is_refused_before_anything_is_written(monkeypatch,
                                                                                                  tmp_path):
    check = tmp_path / "check.json"
    check.write_text("{}")
    fewer = json.loads(json.dumps(DESCRIPTION))
    del fewer["parameters"]["mu"]
    monkeypatch.setattr(executables, "describe",
                        lambda scene, space=None: fewer if scene == str(check) else DESCRIPTION)
    messages = problems_of(command(tmp_path, "--target", "E_GPa=6.5", "--check-test", str(check)))
    assert messages == [f"--check-test {check}: it lacks the calibrated scene's parameter(s) mu: it would not test "
                        "the same material"]
    assert not (tmp_path / "calibrations").exists()


def test_a_problem_of_the_calibration_itself_is_reported_with_the_rest(monkeypatch, tmp_path):
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: DESCRIPTION)
    messages = problems_of(command(tmp_path, "--target", "E_GPa=6.5", "--scale-parameter", "mu", "--tolerance", "-1"))
    assert messages == ["--tolerance: -1.0 must lie in (0, 1)",
                        "calibrate: scale parameter mu is not a varied stress-like parameter (those: Ec_Pa, sc_Pa)"]


def test_assignments_refuse_a_name_given_twice():
    with pytest.raises(Exception, match="nu is given twice"):
        calibrate.parse_assignments(["nu=0.2", "E_GPa=3 nu=0.3"], "--target")
    assert calibrate.parse_assignments(["nu=0.2 E_GPa=3"], "--target") == {"nu": 0.2, "E_GPa": 3.0}


def write_curve(path, rows, header="axial_strain,axial_stress_MPa"):
    path.write_text(header + "\n" + "".join(",".join(str(x) for x in r) + "\n" for r in rows))
    return str(path)


def test_every_problem_of_a_measured_curve_is_one_line_and_nothing_is_written(tmp_path):
    description = dict(with_ranges(), curve_axes={"x": "axial strain", "y": "axial stress (MPa)"})
    bin_dir = fake_describing_bin(str(tmp_path / "bin"), description)
    (tmp_path / "scene.json").write_text("{}")
    good = [(0.0, 0.0), (0.001, 10.0), (0.002, 18.0), (0.003, 22.0), (0.004, 20.0)]
    short = write_curve(tmp_path / "short.csv", good[:4])
    unordered = write_curve(tmp_path / "unordered.csv", [good[0], good[2], good[1], good[3], good[4]])
    ok = write_curve(tmp_path / "ok.csv", good)
    words = write_curve(tmp_path / "words.csv", good[:2] + [(0.002, "high")] + good[3:])
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--out-root", str(tmp_path / "out"),
                            "--target", "nu=0.2", "--curve", short, "--curve", unordered, "--curve", words,
                            "--curve", "ucs:" + ok, "--curve", str(tmp_path / "none.csv"),
                            "--curve-window", "0.1:1.5"], bin_dir)
    assert done.returncode == 2, done.stderr
    lines = [x.removeprefix("demcal_study: error: ") for x in done.stderr.strip().splitlines()]
    assert lines == [
        f"--curve: {short}: 4 point(s); a curve needs at least 5",
        f"--curve: {unordered}: line 4: axial_strain 0.001 is not above the one before (0.002): strains must increase",
        f"--curve: {words}: line 4: axial_stress_MPa \"high\" is not a number",
        f"--curve: {ok}: the window 0.1:1.5 of the peak strain 0.003 spans strains 0.0003 to 0.0045, outside the "
        "curve's 0 to 0.004",
        f"--curve: {tmp_path / 'none.csv'}: cannot be read (No such file or directory)",
    ], done.stderr
    assert not (tmp_path / "out").exists()
    # A window of the right form that the curve holds, a label on a single test, and no scalar target beside it.
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--out-root", str(tmp_path / "out"),
                            "--curve", "ucs:" + ok, "--curve-window", "0.5"], bin_dir)
    lines = [x.removeprefix("demcal_study: error: ") for x in done.stderr.strip().splitlines()]
    assert done.returncode == 2 and lines == [
        "--target: give at least one NAME=VALUE (e.g. --target E_GPa=6.5)",
        "--curve-window: \"0.5\" is not A:B with 0 <= A < B (fractions of the peak strain, e.g. 0.1:1.0)",
    ], done.stderr
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--out-root", str(tmp_path / "out"),
                            "--target", "nu=0.2", "--curve", "ucs:" + ok], bin_dir)
    lines = [x.removeprefix("demcal_study: error: ") for x in done.stderr.strip().splitlines()]
    assert done.returncode == 2 and lines == [
        f"--curve: ucs:{ok}: the scene is a single test: give the curve without a label"], done.stderr
    assert not (tmp_path / "out").exists()


def test_the_bayesian_search_takes_a_curve_with_its_sd_and_weighs_each_point_by_it(tmp_path):
    description = dict(DESCRIPTION, curve_axes={"x": "axial strain", "y": "axial stress (MPa)"})
    rows = [(0.0, 0.0, 0.5), (0.001, 10.0, 0.7), (0.002, 18.0, 0.9), (0.003, 22.0, 1.1), (0.004, 20.0, 1.3)]
    with_sd = write_curve(tmp_path / "sd.csv", rows, "axial_strain,axial_stress_MPa,sd_MPa")
    bare = write_curve(tmp_path / "bare.csv", [r[:2] for r in rows])
    lateral = write_curve(tmp_path / "lateral.csv", [r[:2] + (-r[0] / 4, r[2]) for r in rows],
                          "axial_strain,axial_stress_MPa,lateral_strain,sd_MPa")

    def curves_of(path, strategy):
        problems, targets, uncertainty = Problems(), {"nu": 0.2}, {"nu": {"sd": 0.01, "n": 3}}
        args = type("Args", (), {"curve": [path], "curve_window": "0.2:1.0"})()
        curves = calibrate.measured_curves(args, targets, uncertainty, description, strategy, problems)
        return curves, targets, uncertainty, problems.messages

    curves, targets, uncertainty, problems = curves_of(with_sd, "bayes")
    assert not problems
    points = curves[0]["points"]
    # 8 strains from 0.2 to 1.0 of the peak strain 0.003, the SD interpolated between the file's rows.
    assert [q["strain"] for q in points] == pytest.approx(list(np.linspace(0.0006, 0.003, 8)))
    for q in points:
        assert targets[q["name"]] == pytest.approx(np.interp(q["strain"], [r[0] for r in rows], [r[1] for r in rows]))
        assert uncertainty[q["name"]] == {"sd": pytest.approx(0.5 + 200 * q["strain"]), "n": 1}
    _, _, _, problems = curves_of(bare, "bayes")
    assert problems == [f"--curve {bare}: the Bayesian search weighs each point by the lab's scatter: give the curve "
                        "a specimen column (several specimens' curves) or an sd_MPa column"]
    _, _, _, problems = curves_of(lateral, "bayes")
    assert problems == [f"--curve {lateral}: the Bayesian search weighs each point by the lab's scatter: give the "
                        "curve a specimen column (several specimens' curves) or an sd_MPa column and no lateral_strain "
                        "column (sd_MPa is the stress's)"]
    _, targets, _, problems = curves_of(lateral, "trust-region")
    assert not problems and len(targets) == 1 + 16


def test_a_model_discrepancy_is_a_fraction_and_only_for_the_bayesian_search(monkeypatch, tmp_path):
    bin_dir = fake_describing_bin(str(tmp_path / "bin"), with_ranges())
    (tmp_path / "scene.json").write_text("{}")
    done = run_study_layer(["calibrate", "--scene", str(tmp_path / "scene.json"), "--out-root", str(tmp_path / "out"),
                            "--target", "E_GPa=6.5", "--model-discrepancy", "1.5"], bin_dir)
    lines = [x.removeprefix("demcal_study: error: ") for x in done.stderr.strip().splitlines()]
    assert done.returncode == 2 and lines == [
        "--model-discrepancy: 1.5 must lie in (0, 1) (a fraction of each target)",
        "--model-discrepancy: only the Bayesian search weighs the targets by their uncertainty: add --strategy bayes",
    ], done.stderr
    assert not (tmp_path / "out").exists()
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: with_ranges())
    config, _, _ = calibrate.checked_command(command(tmp_path, "--target", "E_GPa=6.5+-0.3", "--strategy", "bayes",
                                                     "--model-discrepancy", "0.1"))
    assert config["model_discrepancy"] == 0.1
