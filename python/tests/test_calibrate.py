"""The adaptive calibration against a closed-form stand-in for the DEM that obeys the exact scaling (stress outputs
proportional to the stress-like parameters) and has specimen-to-specimen scatter: it must meet reachable targets
within its budget, verify on fresh seeds, correct specimen 1's bias, and call an unreachable target unreachable."""
import csv
import json
import math
import os
import sys

import numpy as np
import pytest

from demcal_study import (calibrate, calibrate_runs, calibrate_verify, commands, curve_targets, executables, outputs,
                          trust_region)
from demcal_study.calibration_problem import Problem
from demcal_study.calibrate_report import report
from demcal_study.searches import bayes_search
from demcal_study.errors import StudyError

DESCRIPTION = {
    "parameters": {
        "Ec_Pa": {"unit": "Pa", "quantity": "stress", "stress_like": True, "si_factor": 1.0, "value": 20e9,
                  "low": 1e8, "high": 1e11, "shapes_specimen": False},
        "sc_Pa": {"unit": "Pa", "quantity": "stress", "stress_like": True, "si_factor": 1.0, "value": 100e6,
                  "low": 0, "high": 1e9, "shapes_specimen": False},
        "kn_ks": {"unit": "1", "quantity": "dimensionless", "stress_like": False, "si_factor": 1.0, "value": 2.0,
                  "low": 0.1, "high": 10, "shapes_specimen": False},
        "mu": {"unit": "1", "quantity": "dimensionless", "stress_like": False, "si_factor": 1.0, "value": 0.5,
               "low": 0, "high": 1, "shapes_specimen": False},
        "R_m": {"unit": "m", "quantity": "length", "stress_like": False, "si_factor": 1.0, "value": 1e-3,
                "low": 1e-4, "high": 1e-2, "shapes_specimen": True},
    },
    "outputs": {
        "E_GPa": {"unit": "GPa", "stress_like": True, "si_factor": 1e9},
        "sigma_u_MPa": {"unit": "MPa", "stress_like": True, "si_factor": 1e6},
        "nu": {"unit": "1", "stress_like": False, "si_factor": 1.0},
    },
}
# The fake DEM's tensile strength, described only where a test reads outputs it does not target.
WITH_TENSILE = dict(DESCRIPTION, outputs=dict(DESCRIPTION["outputs"], sigma_t_MPa={
    "unit": "MPa", "stress_like": True, "si_factor": 1e6}))

# Two-sided 95 % Student t for 1..30 degrees of freedom (tables).
T975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
        2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]
SCATTER = 0.02  # CV of a specimen


def specimen(seed):
    """A specimen's own deviations (the same for every parameter set: common random numbers)."""
    g = np.random.default_rng(1000 + seed).normal(size=3)
    return 1 + SCATTER * g


def fake_dem(p, seed):
    s = specimen(seed)
    return {"E_GPa": s[0] * p["Ec_Pa"] / 1e9 * (0.4 + 0.4 / p["kn_ks"]),
            "sigma_u_MPa": s[1] * p["sc_Pa"] / 1e6 * (0.8 + 0.6 * p["mu"]) * (1 + 0.1 * math.log(p["kn_ks"])),
            "nu": s[2] * (0.12 + 0.08 * math.log(p["kn_ks"])),
            # Never a target here: the posterior predictive must still say what it will be.
            "sigma_t_MPa": specimen_t(seed) * p["sc_Pa"] / 1e6 * 0.12 * (1 + 0.2 * p["mu"])}


def fake_curve(p, seed):
    """The fake specimen's stress-strain curve, as a DEM result's `curve`: a parabola of initial slope E up to the
    peak sigma_u at strain 2 sigma_u / E, then a straight drop to zero at 1.5 times that strain; the lateral strain
    nu times the axial, positive as the DEM counts a swelling specimen."""
    m = fake_dem(p, seed)
    peak = 2 * m["sigma_u_MPa"] / (m["E_GPa"] * 1e3)
    e = np.linspace(0, 1.5 * peak, 61)
    rise = m["sigma_u_MPa"] * (2 * e / peak - (e / peak) ** 2)
    fall = m["sigma_u_MPa"] * np.clip(1 - (e - peak) / (0.5 * peak), 0, 1)
    return {"axial_strain": e.tolist(), "stress_MPa": np.where(e <= peak, rise, fall).tolist(),
            "lateral_strain": (m["nu"] * e).tolist(), "cracks": [0] * len(e)}


def specimen_t(seed):
    """The tensile strength's own specimen deviation (a stream apart: the other outputs' draws stay as they were)."""
    return 1 + 3 * SCATTER * np.random.default_rng(5000 + seed).normal()


@pytest.fixture
def fake(monkeypatch, tmp_path):
    calls = {"points": 0, "seeds": 0}

    def run_points(tools, scene, folder, points, quiet):
        calls["points"] += len(points)
        return [{"status": "ok", "outputs": fake_dem(p, 1), "reason": "", "curve": fake_curve(p, 1)} for p in points]

    def verify(tools, scene, folder, parameters, targets, predicted, first_seed, seeds, max_seeds, tolerance, quiet,
               intervals=None, scale_resolution=None, curves=None):
        # As demcal-verify and calibrate_runs.verify: the seed count follows the scalar targets, the curve's points
        # are added from the seeds' curves.
        os.makedirs(folder, exist_ok=True)
        all_targets = targets
        targets = {o: t for o, t in targets.items() if o not in set(curve_targets.names(curves or []))}
        def scalar_rows(n):
            runs = [outputs.with_ratios(fake_dem(parameters, s), targets) for s in range(first_seed, first_seed + n)]
            rows, passed = {}, True
            for o, t in targets.items():
                x = np.array([r[o] for r in runs])
                mean, sd = float(x.mean()), float(x.std(ddof=1))
                hw = T975[n - 2] * sd / math.sqrt(n)
                err = 100 * (mean - t) / abs(t)
                rows[o] = {"mean": mean, "relative_error_pct": err, "half_width_pct": 100 * hw / abs(t),
                           "passed": bool(abs(err) <= 100 * tolerance)}
                passed = passed and rows[o]["passed"]
            return runs, rows, passed

        n = seeds
        while True:
            runs, rows, passed = scalar_rows(n)
            if n >= max_seeds or all(r["half_width_pct"] <= 100 * tolerance for r in rows.values()):
                break
            n += 1
        while True:
            v = {"passed": passed, "verdict": "mean_inside_band" if passed else "outside", "outputs": rows,
                 "seeds": [{"seed": s, "status": "ok", "macro": {k: float(x) for k, x in r.items()}}
                           for s, r in zip(range(first_seed, first_seed + n), runs)]}
            if not curves:
                break
            v = curve_targets.add_to_verification(v, {s: fake_curve(parameters, s) for s in range(first_seed, first_seed + n)},
                                                  curves, all_targets, predicted or {}, intervals, tolerance)
            more = curve_targets.seeds_wanted(v, curves, tolerance, max_seeds)
            if more is None:
                break
            n = more
            runs, rows, passed = scalar_rows(n)
        calls["seeds"] += n
        with open(os.path.join(folder, "solution.json"), "w") as f:
            json.dump({"x": parameters, "predicted": predicted, "prediction_interval_95": intervals}, f)
        if scale_resolution:
            v["finer"] = {"factor": scale_resolution, "seeds": v["seeds"][:2], "shift_pct": {o: 0.0 for o in targets}}
        with open(os.path.join(folder, "verification.json"), "w") as f:
            json.dump(v, f)
        return v

    monkeypatch.setattr(calibrate_runs, "run_points", run_points)
    monkeypatch.setattr(calibrate_runs, "verify", verify)
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: DESCRIPTION)
    return calls


def run_calibration(tmp_path, bin_dir, targets, budget=60, strategy=None, check_resolution=None, check_tests=None,
                    **more):
    """The calibration of the fake DEM on `targets`; `more`: further settings (curves, target_uncertainty)."""
    out = str(tmp_path / "cal")
    os.makedirs(out, exist_ok=True)
    config = dict({"scene": "fake.json", "space": None, "targets": targets, "fixed": {}, "tolerance": 0.05,
                   "budget": budget, "scale_parameter": None}, **more)
    if strategy:
        config["strategy"] = strategy
    if check_resolution:
        config["check_resolution"] = check_resolution
    if check_tests:
        config["check_tests"] = check_tests
    with open(os.path.join(out, "calibration.json"), "w") as f:
        json.dump(config, f)
    tools = commands.Tools(bin=bin_dir, jobs="2", cache=str(tmp_path / "cache"), python="")
    code = calibrate.Calibration(config, out, tools, quiet=True).run()
    with open(os.path.join(out, "solution.json")) as f:
        return code, json.load(f), out


@pytest.mark.parametrize("strategy", [None, "kriging"])
def test_reachable_targets_are_met_and_verified(fake, tmp_path, bin_dir, strategy):
    targets = {"E_GPa": 6.5, "sigma_u_MPa": 48.0, "nu": 0.2}
    code, solution, out = run_calibration(tmp_path, bin_dir, targets, strategy=strategy)
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["status"] == "met"
    assert solution["dem_runs"] <= 60
    assert solution["dem_runs"] == fake["points"] + fake["seeds"]  # every run counted
    # The solution truly meets the targets on the population mean (specimen effects averaged out).
    mean = {o: np.mean([fake_dem(solution["x"], s)[o] for s in range(100, 400)]) for o in targets}
    for o, t in targets.items():
        assert abs(mean[o] / t - 1) < 0.05, (o, mean[o], t)
    # The scale factor is exact: E is met by scaling, the ratios are what the dimensionless problem chose.
    assert solution["x"]["Ec_Pa"] == pytest.approx(20e9 * solution["scale_factor"], rel=1e-12)
    assert solution["x"]["sc_Pa"] == pytest.approx(solution["ratios"]["sc_Pa"] * solution["x"]["Ec_Pa"], rel=1e-12)
    assert "R_m" not in solution["x"]  # shapes the specimen: left at the scene's default
    # The solution is the point the last verification ran at, with the interval it was shown.
    last = solution["verifications"][-1]["folder"]
    verified = json.load(open(os.path.join(out, last, "solution.json")))
    assert verified["x"] == solution["x"] and verified["predicted"] == solution["predicted"]
    assert verified["prediction_interval_95"] == solution["prediction_interval_95"]
    for o, (lo, hi) in solution["prediction_interval_95"].items():
        assert lo < solution["predicted"][o] < hi
    report(out)
    md = open(os.path.join(out, "report.md")).read()
    assert "## The problem in dimensionless form" in md and "| sigma_u_MPa/E_GPa | 0.007385 |" in md
    assert os.path.exists(os.path.join(out, "report.html"))


@pytest.mark.parametrize("strategy", [None, "kriging"])
def test_a_target_outside_the_bounds_is_unreachable(fake, tmp_path, bin_dir, strategy):
    # nu = 0.12 + 0.08 ln(kn_ks) <= 0.12 + 0.08 ln 10 = 0.304 (plus a little scatter): 0.45 cannot be reached.
    code, solution, _ = run_calibration(tmp_path, bin_dir, {"E_GPa": 6.5, "nu": 0.45}, strategy=strategy)
    assert code == calibrate.EXIT_UNREACHABLE, solution["why"]
    assert solution["status"] == "unreachable"
    assert solution["reachable"]["nu"]["highest_error_pct"] < -25  # the best reached is far below the target
    assert solution["dem_runs"] <= 60


def test_check_tests_run_at_the_verified_solution_on_fresh_seeds_apart_from_the_budget(fake, tmp_path, bin_dir,
                                                                                      monkeypatch):
    asked = []

    def check(tools, scene, folder, parameters, first_seed, seeds, quiet):
        asked.append((scene, dict(parameters), first_seed, seeds))
        return {"runs": seeds, "ok": seeds, "outputs": {"phi_deg": {"mean": 40.0, "sd": 1.5, "n": seeds}}}
    monkeypatch.setattr(calibrate_runs, "check", check)
    code, solution, out = run_calibration(tmp_path, bin_dir, {"E_GPa": 6.5, "sigma_u_MPa": 48.0, "nu": 0.2},
                                          check_tests=["biaxial.json"])
    assert code == calibrate.EXIT_MET
    assert len(asked) == 1
    scene, parameters, first_seed, seeds = asked[0]
    last = solution["verifications"][-1]
    assert scene == "biaxial.json" and first_seed == last["first_seed"] + last["seeds"] and seeds == 4
    # Every parameter of the calibrated scene, at the solution where it was calibrated, else at its default.
    assert parameters == dict({n: q["value"] for n, q in DESCRIPTION["parameters"].items()}, **solution["x"])
    assert solution["checks"][0]["outputs"]["phi_deg"]["mean"] == 40.0
    assert solution["dem_runs"] == fake["points"] + fake["seeds"]  # the check's runs are not in the budget
    report(out)
    md = open(os.path.join(out, "report.md")).read()
    # The check's scene as every path of a report: relative to the report's folder.
    shown = os.path.relpath(os.path.abspath("biaxial.json"), out)
    assert f"## Check 1: `{shown}` at the solution (not a target)" in md and "| phi_deg | 40 | 1.5 | 4 |" in md


def test_the_scale_target_is_the_modulus_describe_ranks_first():
    # Described moduli are preferred by their rank, whatever the names; without one, the first stress target.
    d = json.loads(json.dumps(DESCRIPTION))
    d["outputs"]["secant_GPa"] = {"unit": "GPa", "stress_like": True, "si_factor": 1e9, "modulus": 2}
    d["outputs"]["tangent_GPa"] = {"unit": "GPa", "stress_like": True, "si_factor": 1e9, "modulus": 1}
    p = Problem(d, {"sigma_u_MPa": 48, "secant_GPa": 6.0, "tangent_GPa": 6.5, "nu": 0.2})
    assert p.scale_target == "tangent_GPa"
    assert Problem(d, {"sigma_u_MPa": 48, "secant_GPa": 6.0, "nu": 0.2}).scale_target == "secant_GPa"
    assert Problem(d, {"sigma_u_MPa": 48, "nu": 0.2}).scale_target == "sigma_u_MPa"


def test_problem_codes_wide_ranges_on_a_log_scale_and_fixes_what_shapes_the_specimen():
    p = Problem(DESCRIPTION, {"E_GPa": 6.5, "sigma_u_MPa": 48, "nu": 0.2})
    assert p.scale_parameter == "Ec_Pa" and p.scale_target == "E_GPa"
    names = [c.name for c in p.coordinates]
    assert names == ["kn_ks", "mu", "sc_Pa"]
    by = {c.name: c for c in p.coordinates}
    assert by["sc_Pa"].ratio and by["sc_Pa"].log_scale
    assert by["sc_Pa"].low == pytest.approx(1e6 / 20e9)  # low 0 raised to 1e-3 of the high, over Ec's reference
    assert by["mu"].log_scale and by["mu"].low == pytest.approx(1e-3)
    assert by["kn_ks"].log_scale  # 0.1 .. 10 spans two decades
    for c in p.coordinates:
        assert c.decode(c.code(c.reference)) == pytest.approx(c.reference)
    assert p.dimensionless_targets() == {"nu": 0.2, "sigma_u_MPa/E_GPa": pytest.approx(48e6 / 6.5e9)}
    # A point at the reference and scale 2: every stress-like value doubles, ratios hold.
    x = p.absolute(p.reference_point(), 2.0)
    assert x["Ec_Pa"] == pytest.approx(40e9) and x["sc_Pa"] == pytest.approx(200e6) and x["mu"] == pytest.approx(0.5)


def test_a_scene_that_does_not_declare_the_scaling_is_searched_without_it():
    # An external program: its stress-like parameters are searched as they are, no scale factor.
    described = dict(DESCRIPTION, exact_scaling=False)
    p = Problem(described, {"E_GPa": 6.5, "sigma_u_MPa": 48})
    assert p.scale_parameter is None and p.scale_target is None
    assert sorted(c.name for c in p.coordinates) == ["Ec_Pa", "kn_ks", "mu", "sc_Pa"]
    assert not any(c.ratio for c in p.coordinates)
    with pytest.raises(StudyError, match='does not declare "exact_scaling": true'):
        Problem(described, {"E_GPa": 6.5}, scale_parameter="Ec_Pa")


def test_a_friction_angle_is_searched_linearly_from_its_own_low():
    # The flat joint's phi_b (0..80 deg, default 0): varied, neither scaled nor log-coded, zero kept as its low.
    described = json.loads(json.dumps(DESCRIPTION))
    described["parameters"]["phi_deg"] = {"unit": "deg", "quantity": "angle", "stress_like": False,
                                          "si_factor": 1.0, "value": 0.0, "low": 0.0, "high": 80.0,
                                          "shapes_specimen": False}
    p = Problem(described, {"E_GPa": 6.5, "nu": 0.2})
    phi = {c.name: c for c in p.coordinates}["phi_deg"]
    assert not phi.ratio and not phi.log_scale and (phi.low, phi.high, phi.reference) == (0.0, 80.0, 0.0)
    assert phi.code(40.0) == pytest.approx(0.0) and phi.decode(0.5) == pytest.approx(60.0)
    assert p.absolute(p.reference_point(), 3.0)["phi_deg"] == 0.0  # the scale factor leaves it alone


def test_a_fixed_stress_like_parameter_turns_the_scaling_off():
    p = Problem(DESCRIPTION, {"E_GPa": 6.5, "nu": 0.2}, fixed={"sc_Pa": 50e6})
    assert p.scale_parameter is None and p.held_stress == ["sc_Pa"]
    assert "Ec_Pa" in [c.name for c in p.coordinates]
    with pytest.raises(StudyError, match="needs every stress-like value to follow"):
        Problem(DESCRIPTION, {"E_GPa": 6.5}, fixed={"sc_Pa": 50e6}, scale_parameter="Ec_Pa")


def test_bad_targets_name_the_field():
    with pytest.raises(StudyError, match="target peak_MPa is not an output"):
        Problem(DESCRIPTION, {"peak_MPa": 3})
    with pytest.raises(StudyError, match="fixed density is not a parameter"):
        Problem(DESCRIPTION, {"E_GPa": 3}, fixed={"density": 1})


def test_least_norm_step_inside_the_box():
    # One residual, three coordinates: r = 0.3 + u0 + 2 u1 (u2 has no effect). Least-norm: delta = -0.3 (1, 2, 0) / 5.
    delta, predicted, held = trust_region.step([0.3], [[1.0, 2.0, 0.0]], np.zeros(3), 1.0)
    assert delta == pytest.approx([-0.06, -0.12, 0.0])
    assert predicted == pytest.approx([0.0], abs=1e-12)
    assert held == []
    # A box of 0.05: u1 is held at its face, u0 takes the rest: 0.3 - 0.1 + u0 = 0 -> u0 = -0.2 -> held too.
    delta, predicted, held = trust_region.step([0.3], [[1.0, 2.0, 0.0]], np.zeros(3), 0.05)
    assert delta == pytest.approx([-0.05, -0.05, 0.0])
    assert predicted == pytest.approx([0.15])
    assert held == [0, 1]


def test_local_fit_recovers_a_linear_response_and_tells_noise_from_effects():
    rng = np.random.default_rng(3)
    u = rng.uniform(-1, 1, size=(40, 3))
    z = 1.0 + u @ np.array([0.5, -0.2, 0.0]) + 0.01 * rng.normal(size=40)
    model = trust_region.fit_local(u, z[:, None], np.zeros(3), 10.0)
    assert model.intercept[0] == pytest.approx(1.0, abs=0.01)
    assert model.slopes[0] == pytest.approx([0.5, -0.2, 0.0], abs=0.01)
    kept = model.significant().slopes[0]
    assert kept[0] != 0 and kept[1] != 0 and kept[2] == 0  # the third slope is noise
    assert model.prediction_sd(np.zeros(3))[0] == pytest.approx(0.01, rel=0.35)


@pytest.mark.parametrize("args,message", [
    (["--scene", "no_such_scene.json", "--target", "E_GPa=6.5"], "--scene: no_such_scene.json does not exist"),
    (["--scene", "data/scenes/ucs_rock_cb.json", "--target", "E_GPa"], "--target: \"E_GPa\" is not NAME=VALUE, NAME=MEAN+-SD or NAME=MEAN+-SD/n=N"),
    (["--scene", "data/scenes/ucs_rock_cb.json"], "--target: give at least one NAME=VALUE"),
    (["--scene", "data/scenes/ucs_rock_cb.json", "--target", "E_GPa=6.5", "--budget", "5"], "--budget: 5 DEM runs"),
    (["--scene", "data/scenes/ucs_rock_cb.json", "--target", "E_GPa=6.5", "--tolerance", "2"], "--tolerance: 2.0"),
])
def test_bad_command_lines_get_one_line_errors(args, message, tmp_path):
    from conftest import fake_describing_bin, run_study_layer
    # demcal-dem describes the scene before anything runs: a stand-in answers for it (no build needed).
    done = run_study_layer(["calibrate", "--out-root", str(tmp_path)] + args,
                           fake_describing_bin(str(tmp_path / "bin"), DESCRIPTION))
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], done.stderr


def test_kriging_interpolates_and_knows_where_it_has_no_data():
    from demcal_study import kriging
    rng = np.random.default_rng(5)
    x = rng.uniform(-1, 1, size=(30, 2))
    y = np.sin(2 * x[:, 0]) + 0.5 * x[:, 1]
    gp = kriging.fit(x, y)
    mean, sd = gp.predict(np.array([[0.1, -0.2], [0.5, 0.5]]))
    assert mean == pytest.approx([np.sin(0.2) - 0.1, np.sin(1.0) + 0.25], abs=0.03)
    assert np.all(sd < 0.05)
    _, far = gp.predict(np.array([[5.0, 5.0]]))
    assert far[0] > 10 * sd.max()  # far from every point the posterior is as wide as the prior
    # Expected improvement of a misfit (y - 0.3)^2: largest where the mean crosses 0.3, not where y is lowest.
    grid = np.array([[u, 0.0] for u in np.linspace(-1, 1, 201)])
    ei, _ = kriging.expected_improvement([gp], lambda z: (z[..., 0] - 0.3) ** 2, grid, best=0.01)
    assert abs(np.sin(2 * grid[int(np.argmax(ei)), 0]) - 0.3) < 0.05


def test_a_scale_beyond_the_bounds_is_unreachable_and_names_the_parameter(fake, tmp_path, bin_dir):
    # E = Ec (0.4 + 0.4 / kn_ks) <= 4.4 Ec (kn_ks >= 0.1): 2,000 GPa needs Ec >= 455 GPa, above its bound 100 GPa.
    code, solution, _ = run_calibration(tmp_path, bin_dir, {"E_GPa": 2000.0, "nu": 0.2})
    assert code == calibrate.EXIT_UNREACHABLE, solution["why"]
    assert "needs a scale factor" in solution["why"] and "Ec_Pa" in solution["why"] and "bounds 1e+08 to 1e+11" in solution["why"]


def stiffer_with_friction(monkeypatch):
    """The stand-in with E = Ec (0.4 + 0.4 / kn_ks) (0.5 + mu): friction raises E / Ec."""
    plain = fake_dem

    def stiffer(p, seed):
        out = plain(p, seed)
        out["E_GPa"] *= 0.5 + p["mu"]
        return out

    monkeypatch.setattr(sys.modules[__name__], "fake_dem", stiffer)


def with_two_deviations(sd1_pa, sd2_pa):
    """DESCRIPTION with two more stress-like parameters (bounds 1e5 to 1e8 Pa) that no output depends on."""
    described = json.loads(json.dumps(DESCRIPTION))
    for name, value in (("sd1_Pa", sd1_pa), ("sd2_Pa", sd2_pa)):
        described["parameters"][name] = {"unit": "Pa", "quantity": "stress", "stress_like": True, "si_factor": 1.0,
                                         "value": value, "low": 1e5, "high": 1e8, "shapes_specimen": False}
    return described


def test_a_scale_beyond_the_bounds_at_the_first_solution_is_searched_on_with_the_scale_at_its_bound(
        fake, tmp_path, bin_dir, monkeypatch):
    # E = Ec (0.4 + 0.4 / kn_ks) (0.5 + mu), nu as before: nu = 0.2 fixes kn_ks = e, so E / Ec = 0.547 (0.5 + mu).
    # The first solution keeps mu near its reference 0.5 and wants Ec = 70 / 0.547 = 128 GPa, above the bound
    # of 100 GPa; at mu = 0.78 the bound itself gives 70 GPa. That was called unreachable (ldb_granite,
    # docs/explanation/calibration_benchmark.md) while the old global strategy met it.
    stiffer_with_friction(monkeypatch)
    code, solution, _ = run_calibration(tmp_path, bin_dir, {"E_GPa": 70.0, "nu": 0.2}, budget=80)
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["bounded_scale"] is True
    # Where it ended, the bounds allow the factor E wants (within the tolerance): the first solution's did not.
    assert solution["wanted_scale_factor"] <= 1.05 * solution["scale_interval"][1]
    assert solution["x"]["mu"] > 0.6  # it moved along the free coordinate that raises E / Ec
    assert any(r.get("bounded_scale") for r in solution["rounds"])


def test_two_parameters_that_hold_the_scale_together_are_both_moved_to_free_it(fake, tmp_path, bin_dir, monkeypatch):
    # As above, but two more stress-like parameters (a strength's two standard deviations, say) that no output
    # depends on stand at nearly the same ratio to Ec, and their bound (1e8 Pa) caps the scale near 2.5, Ec at
    # 50 GPa: E = 70 GPa needs both lowered together. On ldb_granite, with the slope over the hard minimum, the
    # search stalled on the bounds of such a pair (docs/explanation/calibration_benchmark.md); this smooth stand-in meets the
    # target with the hard minimum too, so the test holds the case, not the stall.
    described = with_two_deviations(39.8e6, 40e6)
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: described)
    stiffer_with_friction(monkeypatch)
    code, solution, _ = run_calibration(tmp_path, bin_dir, {"E_GPa": 70.0, "nu": 0.2}, budget=80)
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["bounded_scale"] is True
    assert solution["x"]["sd1_Pa"] / solution["x"]["Ec_Pa"] < 1.5e-3 and solution["x"]["sd2_Pa"] / solution["x"]["Ec_Pa"] < 1.5e-3
    assert solution["x"]["Ec_Pa"] > 60e9


def test_soft_scale_bounds_share_the_slope_of_bounds_that_bind_together():
    p = Problem(with_two_deviations(40e6, 40e6), {"E_GPa": 70.0, "nu": 0.2})
    u = p.reference_point()
    low, high = p.scale_interval(u)
    assert high == pytest.approx(2.5)  # 1e8 / 40e6: both standard deviations bind at once
    soft_low, soft_high = p.scale_interval(u, 20.0)
    # Two equal bounds: the soft min lies log(2) / 20 below them; the soft max of the lows at least their max.
    assert math.log(high / soft_high) == pytest.approx(math.log(2) / 20)
    assert soft_low >= low
    # One of the two lowered: the hard bound does not move, the soft one rises by about half as much.
    i = [c.name for c in p.coordinates].index("sd1_Pa")
    v = np.array(u, float)
    v[i] -= 0.1
    assert p.scale_interval(v)[1] == pytest.approx(high)
    assert p.scale_interval(v, 20.0)[1] > soft_high


def test_a_value_put_on_its_bound_by_the_scale_factor_stays_inside_it():
    # The bounded search sets the scale factor to a bound over a value at factor 1, and the product lands back on
    # the bound only up to rounding: one ulp above 1e8 Pa stopped ldb_granite's calibration (demcal-verify refuses
    # it). Over deviations of 30-70 MPa some products round above the bound; every value handed on must not.
    rounded_out = 0
    for k in range(200):
        p = Problem(with_two_deviations(30e6 + k * 0.2e6 + 0.123, 40e6), {"E_GPa": 70.0, "nu": 0.2})
        u = p.reference_point()
        high = p.scale_interval(u)[1]
        values = p.absolute(u, high)
        i = [c.name for c in p.coordinates].index("sd1_Pa")
        raw = p.coordinates[i].decode(u[i]) * p.scale_reference * high
        rounded_out += raw > 1e8
        for name, (lo, hi) in p.absolute_bounds.items():
            assert lo <= values[name] <= hi, (name, values[name])
        assert values["sd1_Pa"] == pytest.approx(1e8, rel=1e-12) or values["sd2_Pa"] == pytest.approx(1e8, rel=1e-12)
    assert rounded_out > 0  # the case the snap is for occurs among these


def test_a_resumed_verification_keeps_its_stored_point_only_when_it_ran(tmp_path, monkeypatch):
    # Within SAME_POINT_RTOL the stored point is the one verified before, so its stored runs stand. A point that
    # demcal-verify refused (one ulp outside a bound) ran nothing: the new point must replace it, or every resume
    # hands the refused one over again.
    class Tools:
        jobs, cache = "1", str(tmp_path / "cache")

        def program(self, name):
            return name

    def fake_run(cmd, stdout=None):
        with open(cmd[cmd.index("--out") + 1], "w") as f:
            f.write("{}")
        return type("Done", (), {"returncode": 0})()

    monkeypatch.setattr(calibrate_runs.subprocess, "run", fake_run)
    stored, new = {"a_Pa": 1.0000000000000002e8}, {"a_Pa": 1e8}
    for ran, expected in ((False, new), (True, stored)):
        folder = tmp_path / f"v_{ran}"
        folder.mkdir()
        (folder / "solution.json").write_text(json.dumps({"status": "ok", "x": stored}))
        if ran:
            (folder / "runs").mkdir()
        calibrate_runs.verify(Tools(), "scene.json", str(folder), dict(new), {"y": 1.0}, {"y": 1.0}, 2, 5, 20, 0.05, True)
        assert json.loads((folder / "solution.json").read_text())["x"] == expected


def test_check_resolution_runs_once_met_and_is_listed_apart(fake, tmp_path, bin_dir):
    code, solution, _ = run_calibration(tmp_path, bin_dir, {"E_GPa": 6.5, "sigma_u_MPa": 48.0, "nu": 0.2},
                                        check_resolution=2.0)
    assert code == calibrate.EXIT_MET
    assert solution["finer_check"]["factor"] == 2.0 and solution["finer_check"]["runs"] == 2


def test_t_quantiles_and_weights_that_only_place_the_fit():
    assert trust_region.t975(4) == pytest.approx(2.776, abs=1e-3)
    assert trust_region.t975(17.5) == pytest.approx(2.105, abs=2e-3)  # between the tables' 15 and 20
    assert trust_region.t975(1e9) == pytest.approx(1.960, abs=1e-3)
    # Scaling every weight by 10 moves neither the slopes' t values nor the prediction interval.
    rng = np.random.default_rng(4)
    u = rng.uniform(-1, 1, size=(15, 3))
    z = (0.3 + u @ np.array([0.2, -0.1, 0.05]) + 0.02 * rng.normal(size=15))[:, None]
    w = rng.uniform(0.2, 1.0, size=15)
    a = trust_region.fit_local(u, z, np.zeros(3), 1.0, w=w)
    b = trust_region.fit_local(u, z, np.zeros(3), 1.0, w=0.1 * w)
    assert a.slope_t() == pytest.approx(b.slope_t(), rel=1e-6)
    assert a.prediction_sd(np.full(3, 0.3)) == pytest.approx(b.prediction_sd(np.full(3, 0.3)), rel=1e-6)


def test_the_noise_allowance_never_reaches_the_tolerance():
    # close_enough only reads the tolerance: a bare instance is enough.
    c = calibrate.Calibration.__new__(calibrate.Calibration)
    c.tolerance = 0.05
    assert c.close_enough([0.015, -0.01], [0.0, 0.0])        # within a third of the tolerance
    assert c.close_enough([0.022, 0.0], [0.03, 0.0])          # within the measured noise
    assert not c.close_enough([0.055, 0.0], [0.08, 0.0])      # noise above the tolerance is capped at half of it
    assert c.close_enough([0.024, 0.0], [0.08, 0.0])
    assert not c.close_enough([0.026, 0.0], [0.08, 0.0])


def test_a_ratio_target_over_a_test_list_is_met_and_each_test_is_counted(fake, tmp_path, bin_dir, monkeypatch):
    # The same stand-in as a list of two tests per point (each point costs two runs), with sigma_u / E as a
    # target in its own right (dimensionless: both are stresses).
    listed = dict(DESCRIPTION, test="list", tests=[{"label": "ucs"}, {"label": "other"}])
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: listed)
    target = fake_dem({"Ec_Pa": 15e9, "sc_Pa": 120e6, "kn_ks": 2.5, "mu": 0.5}, 1)
    targets = {"E_GPa": target["E_GPa"], "sigma_u_MPa/E_GPa": target["sigma_u_MPa"] / target["E_GPa"]}
    code, solution, out = run_calibration(tmp_path, bin_dir, targets, budget=120)
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["dem_runs"] == 2 * (fake["points"] + fake["seeds"])
    p = Problem(listed, targets)
    assert not p.output_stress_like["sigma_u_MPa/E_GPa"]
    assert p.dimensionless_targets()["sigma_u_MPa/E_GPa"] == targets["sigma_u_MPa/E_GPa"]


def test_ratio_outputs_are_formed_per_run_and_refused_when_they_make_no_sense():
    assert outputs.with_ratios({"a": 6.0, "b": 3.0}, ["a/b", "b", "a/c"]) == {"a": 6.0, "b": 3.0, "a/b": 2.0}
    info = outputs.output_info(DESCRIPTION["outputs"], "sigma_u_MPa/E_GPa", "w")
    assert not info["stress_like"] and info["si_factor"] == 1e-3
    assert outputs.output_info(DESCRIPTION["outputs"], "sigma_u_MPa/nu", "w")["stress_like"]
    with pytest.raises(StudyError, match="a pure number over a stress"):
        outputs.output_info(DESCRIPTION["outputs"], "nu/E_GPa", "w")
    with pytest.raises(StudyError, match="is not an output or a ratio"):
        Problem(DESCRIPTION, {"E_GPa/": 3})


def test_a_point_computed_again_in_its_last_digits_reuses_the_stored_one(tmp_path, monkeypatch):
    # On resume a candidate may differ in its last bits (sums in another order): the stored design is the decision,
    # so its points are run (resumed), not new ones that the batch would take for other parameter values.
    folder = tmp_path / "r02"
    folder.mkdir()
    stored = [{"a": 0.1 + 0.2, "b": 2.0}, {"a": 1.0 / 3.0, "b": 5.0}]
    (folder / "design.csv").write_text("run,a,b\n" + "".join(f"{k + 1},{p['a']!r},{p['b']!r}\n"
                                                             for k, p in enumerate(stored)))
    ran = []

    def batch(cmd, **kwargs):
        design = cmd[cmd.index("--design") + 1]
        ran.append(open(design).read())
        with open(cmd[cmd.index("--csv") + 1], "w") as f:
            f.write("run,a,b,seed,status,y\n1,0,0,1,ok,1.5\n2,0,0,1,ok,2.5\n")
        return type("Done", (), {"returncode": 0})()
    monkeypatch.setattr(calibrate_runs.subprocess, "run", batch)
    tools = commands.Tools(bin="bin", jobs="1", cache="c", python="")
    again = [{"a": 0.3, "b": 2.0}, {"a": 0.3333333333333333 * (1 + 1e-15), "b": 5.0}]  # 0.1 + 0.2 != 0.3
    results = calibrate_runs.run_points(tools, "s.json", str(folder), again, quiet=True)
    assert ran == [(folder / "design.csv").read_text()] and "0.30000000000000004" in ran[0]
    assert [r["outputs"]["y"] for r in results] == [1.5, 2.5]
    moved = [{"a": 0.3 * (1 + 1e-6), "b": 2.0}, {"a": 1.0 / 3.0, "b": 5.0}]  # a real step: a new design
    calibrate_runs.run_points(tools, "s.json", str(folder), moved, quiet=True)
    assert repr(0.3 * (1 + 1e-6)) in ran[1]


def test_the_offset_is_a_trimmed_mean_that_one_far_seed_does_not_move():
    # yineng_siltstone's second verification: nu of one seed at 2.7x the others moved a plain mean's correction by
    # 14 % of the target (docs/explanation/calibration_benchmark.md).
    rng = np.random.default_rng(7)
    clean = rng.normal(0.0, 0.012, size=(19, 2))
    far = np.vstack([clean, [[0.0, 0.33]]])
    assert abs(far[:, 1].mean() - clean[:, 1].mean()) > 0.015
    assert abs(calibrate_verify.trimmed_mean(far, calibrate_verify.OFFSET_TRIM)[1] - np.median(clean[:, 1])) < 0.006
    # Five seeds lose the lowest and the highest; two or three seeds keep them all.
    np.testing.assert_allclose(calibrate_verify.trimmed_mean([[1.0], [2.0], [3.0], [4.0], [100.0]], 0.2), [3.0])
    np.testing.assert_allclose(calibrate_verify.trimmed_mean([[1.0], [2.0], [9.0]], 0.2), [4.0])


def test_the_secant_update_takes_the_measured_change_along_the_step_and_keeps_the_rest():
    jac = np.array([[1.0, 0.0], [0.0, 2.0]])
    c1, c2 = np.array([0.0, 0.0]), np.array([0.5, 0.0])
    r1, r2 = np.array([0.1, 0.2]), np.array([0.1 + 0.8, 0.2 + 0.05])  # along the step: 1.6 and 0.1 per unit
    new = calibrate_verify.secant_update(jac, (c1, r1), (c2, r2))
    np.testing.assert_allclose(new @ (c2 - c1), r2 - r1)
    np.testing.assert_allclose(new[:, 1], jac[:, 1])  # across the step: unchanged
    # No step, or residual vectors of another length (the bounded scale term came on): as it was.
    np.testing.assert_array_equal(calibrate_verify.secant_update(jac, (c1, r1), (c1, r2)), jac)
    np.testing.assert_array_equal(calibrate_verify.secant_update(jac, (c1, r1), (c2, np.append(r2, 0.0))), jac)


def test_an_invocation_stopped_by_an_error_still_counts_its_wall_time(fake, tmp_path, bin_dir, monkeypatch):
    import argparse
    scene = tmp_path / "fake.json"
    scene.write_text("{}")
    args = argparse.Namespace(target=["E_GPa=6.5 sigma_u_MPa=48 nu=0.2"], fixed=None, tolerance=0.05, scene=str(scene),
                              space=None, budget=60, name="cal", out_root=str(tmp_path), scale_parameter=None,
                              check_resolution=None, check_test=None, strategy="trust-region", quiet=True)
    working = calibrate_runs.run_points

    def broken(*a, **k):
        raise StudyError("demcal-dem batch: the machine went away")
    monkeypatch.setattr(calibrate_runs, "run_points", broken)
    with pytest.raises(StudyError, match="went away"):
        calibrate.calibrate(args)
    with open(tmp_path / "cal" / "wall_s.json") as f:
        assert len(json.load(f)) == 1
    assert not (tmp_path / "cal" / "solution.json").exists()
    monkeypatch.setattr(calibrate_runs, "run_points", working)
    assert calibrate.calibrate(args) == calibrate.EXIT_MET
    with open(tmp_path / "cal" / "solution.json") as f:
        solution = json.load(f)
    assert len(solution["wall_s_parts"]) == 2
    assert solution["wall_s_total"] == pytest.approx(sum(solution["wall_s_parts"]))


def test_the_secant_update_keeps_only_the_part_of_a_mismatch_its_means_tell_from_their_noise():
    jac = np.array([[1.0, 0.0], [0.0, 2.0]])
    c1, c2 = np.array([0.0, 0.0]), np.array([0.5, 0.0])
    r1 = np.array([0.1, 0.2])
    # Along the step the Jacobian expects +0.5 and 0.0; the means measured +0.5 + 0.03 and 0.0 + 0.2.
    r2 = np.array([0.1 + 0.5 + 0.03, 0.2 + 0.2])
    var1, var2 = np.array([0.02 ** 2, 0.01 ** 2]), np.array([0.02 ** 2, 0.01 ** 2])
    new = calibrate_verify.secant_update(jac, (c1, r1, var1), (c2, r2, var2))
    # First residual: a mismatch of 0.03 against a noise SD of 0.028 keeps 1 - 0.0008 / 0.0009 of it.
    # Second: 0.2 against 0.014 keeps 1 - 0.0002 / 0.04 = 99.5 %.
    np.testing.assert_allclose(new @ (c2 - c1) - jac @ (c2 - c1), [0.03 * (1 - 0.0008 / 0.0009), 0.2 * 0.995])
    np.testing.assert_allclose(new[:, 1], jac[:, 1])
    # A mismatch smaller than its noise changes nothing; without variances the whole mismatch is taken.
    quiet = calibrate_verify.secant_update(jac, (c1, r1, var1), (c2, np.array([0.1 + 0.5 + 0.02, 0.2]), var2))
    np.testing.assert_allclose(quiet, jac)
    np.testing.assert_allclose(calibrate_verify.secant_update(jac, (c1, r1), (c2, r2)) @ (c2 - c1), r2 - r1)


def test_the_trimmed_mean_variance_is_the_plain_means_without_a_cut_and_matches_repeated_trimmed_means():
    rng = np.random.default_rng(11)
    rows = rng.normal(0.0, 1.0, size=(20, 2))
    np.testing.assert_allclose(calibrate_verify.trimmed_mean_variance(rows, 0.0), rows.var(axis=0, ddof=1) / 20)
    # Over 4,000 samples of 20 normal values, the 20 %-trimmed mean's variance (large-n theory: 1.144 / 20)
    # against the estimate averaged over the samples: within 10 %.
    samples = rng.normal(0.0, 1.0, size=(4000, 20, 1))
    means = np.array([calibrate_verify.trimmed_mean(s, calibrate_verify.OFFSET_TRIM)[0] for s in samples])
    estimates = np.array([calibrate_verify.trimmed_mean_variance(s, calibrate_verify.OFFSET_TRIM)[0] for s in samples])
    assert abs(estimates.mean() / means.var(ddof=1) - 1.0) < 0.10
    assert 1.05 / 20 < means.var(ddof=1) < 1.35 / 20
    assert np.isinf(calibrate_verify.trimmed_mean_variance([[1.0]], 0.2)).all()


def test_a_mean_met_with_an_interval_too_wide_is_noisy_and_says_how_many_disks_would_do(fake, tmp_path, bin_dir,
                                                                                        monkeypatch):
    # nu scatters 12 % from specimen to specimen, the stress outputs 2 %: 20 seeds leave nu's half-width above 5 %.
    def noisy_nu(seed):
        g = np.random.default_rng(1000 + seed).normal(size=3)
        return 1 + np.array([0.02, 0.02, 0.12]) * g

    monkeypatch.setattr(sys.modules[__name__], "specimen", noisy_nu)
    code, solution, out = run_calibration(tmp_path, bin_dir, {"E_GPa": 10.0, "sigma_u_MPa": 60.0, "nu": 0.2},
                                          budget=80)
    assert solution["status"] == "noisy" and code == calibrate.EXIT_BUDGET, solution["why"]
    with open(os.path.join(out, "verification.json")) as f:
        final = json.load(f)["outputs"]["nu"]
    assert final["half_width_pct"] > 5
    factor = calibrate_verify.disk_factor_for(final["half_width_pct"], 0.05, 20, 20)
    assert f"on 20 seeds a specimen with about {factor:.1f}x the disks" in solution["why"]
    assert calibrate_verify.disk_factor_for(10.0, 0.05, 20, 20) == pytest.approx(4.0)  # twice the half-width, 4x the disks
    # 8.5 % on the 11 seeds a budget left is a 12.65 % scatter per seed: 5.92 % on 20 seeds, so 1.40x the disks.
    assert calibrate_verify.disk_factor_for(8.5, 0.05, 11, 20) == pytest.approx((8.5 * math.sqrt(11) / 2.228 * 2.093
                                                                           / math.sqrt(20) / 5) ** 2, rel=2e-3)


def test_the_bayesian_search_gives_a_posterior_and_a_verified_point(fake, tmp_path, bin_dir, monkeypatch):
    # Unextended chains keep this test at about 20 s (friction's flat posterior would run each to the cap);
    # the extension itself is tested in test_bayes_posterior.py.
    monkeypatch.setattr(bayes_search, "MAX_STEPS", 4000)
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: WITH_TENSILE)
    # The lab's means at a reachable point, with a 3 % SD over 5 specimens (SE 1.3 %): the exported point must still
    # meet every target within 5 % on fresh seeds, and the posterior must say what the data pin down.
    targets = {"E_GPa": 6.5, "sigma_u_MPa": 48.0, "nu": 0.2}
    code, solution, out = run_calibration(tmp_path, bin_dir, targets, strategy="bayes", target_uncertainty={
        o: {"sd": 0.03 * v, "n": 5} for o, v in targets.items()})
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["dem_runs"] <= 60
    mean = {o: np.mean([fake_dem(solution["x"], s)[o] for s in range(100, 400)]) for o in targets}
    for o, t in targets.items():
        assert abs(mean[o] / t - 1) < 0.05, (o, mean[o], t)
    posterior = json.load(open(os.path.join(out, "posterior.json")))
    # Three targets, four parameters (Ec, sc, kn_ks, mu): E fixes Ec's scale, nu kn_ks, sigma_u only sc and mu
    # together: mu cannot be told from sc.
    assert "kn_ks" in posterior["identified"]
    assert "mu" in posterior["not_identified"]
    d = posterior["diagnostics"]
    assert d["effective_samples"] > 200 and 0.1 < d["acceptance"] < 0.9
    rows = list(csv.DictReader(open(os.path.join(out, "posterior.csv"))))
    assert len(rows) == d["kept"] and {"Ec_Pa", "sc_Pa", "kn_ks", "mu", "weight"} <= set(rows[0])
    kn = np.array([float(r["kn_ks"]) for r in rows])
    lo, hi = posterior["parameters"]["kn_ks"]["credible_90"]
    assert np.mean((kn >= lo) & (kn <= hi)) == pytest.approx(0.9, abs=0.01)
    report(out)
    md = open(os.path.join(out, "report.md")).read()
    section = md[md.index("## Posterior (Bayesian search)"):]
    assert "| kn_ks |" in section and "| E_GPa | 6.5 | 0.195 | 5 |" in section
    rounds = [r for r in solution["rounds"] if "bayes" in r]
    assert rounds and section.count("\n| ") >= len(rounds) + 4 + 3
    # The posterior predictive: every output, the untargeted tensile strength included. At the exported point the
    # 95 % interval of a 5-specimen mean holds the verified 5-seed mean, and is at least as wide as the specimens'
    # scatter makes it (specimen 1's own deviation plus the mean's: 1.96 sqrt(1 + 1/5) SD).
    predictive = json.load(open(os.path.join(out, "predictive.json")))
    rows = predictive["outputs"]
    assert set(rows) == {"E_GPa", "sigma_u_MPa", "nu", "sigma_t_MPa"}
    assert rows["sigma_t_MPa"]["target"] is None and rows["E_GPa"]["target"] == 6.5
    seeds = json.load(open(os.path.join(out, solution["verifications"][0]["folder"], "verification.json")))["seeds"]
    for o, r in rows.items():
        values = np.array([s["macro"][o] for s in seeds])
        assert r["verified_mean"] == pytest.approx(values[:5].mean(), rel=1e-12)
        assert r["specimen_sd"] == pytest.approx(values.std(ddof=1), rel=1e-12)
        lo, hi = r["exported"]["interval_95"]
        assert hi - lo >= 2 * 1.959963984540054 * math.sqrt(1.2) * r["specimen_sd"] * (1 - 1e-12)
        assert r["inside"] and lo <= r["verified_mean"] <= hi, (o, lo, r["verified_mean"], hi)
        plo, phi = r["posterior"]["interval_95"]
        assert plo < r["posterior"]["median"] < phi
    # The untargeted output's interval holds the population's true mean at the verified point (300 specimens).
    x = json.load(open(os.path.join(out, solution["verifications"][0]["folder"], "solution.json")))["x"]
    truth = np.mean([fake_dem(x, s)["sigma_t_MPa"] for s in range(100, 400)])
    lo, hi = rows["sigma_t_MPa"]["exported"]["interval_95"]
    assert lo <= truth <= hi
    assert "### What a mean of 5 fresh specimens will show" in md and "| sigma_t_MPa | - |" in md


def lab_curve_at(p, path, seeds=range(100, 400)):
    """The population's mean curve at parameters p (the fake's specimens averaged), written as a lab curve file:
    compression positive, so the lateral strain negative; returns its rows."""
    peak = np.mean([2 * fake_dem(p, s)["sigma_u_MPa"] / (fake_dem(p, s)["E_GPa"] * 1e3) for s in seeds])
    e = np.linspace(0, 1.3 * peak, 40)
    stress = np.mean([np.interp(e, c["axial_strain"], c["stress_MPa"]) for c in (fake_curve(p, s) for s in seeds)], axis=0)
    lateral = -np.mean([np.interp(e, c["axial_strain"], c["lateral_strain"]) for c in (fake_curve(p, s) for s in seeds)], axis=0)
    with open(path, "w") as f:
        f.write("axial_strain,axial_stress_MPa,lateral_strain\n")
        for row in zip(e, stress, lateral):
            f.write(",".join(repr(float(x)) for x in row) + "\n")
    return e, stress, lateral


def test_a_measured_curve_is_met_point_by_point_and_verified(fake, tmp_path, bin_dir):
    # The lab's curve is the population's mean curve at a truth, with the lateral strain: the calibration must meet
    # its 16 points (8 stresses, 8 lateral strains over 0.1-1.0 of the peak strain) and the one scalar target on
    # fresh seeds, and the population's curve at the answer must lie within 5 % of the lab's at every point.
    truth = {"Ec_Pa": 15e9, "sc_Pa": 80e6, "kn_ks": 2.5, "mu": 0.5}
    path = str(tmp_path / "lab_curve.csv")
    lab_curve_at(truth, path)
    targets = {"sigma_u_MPa": float(np.mean([fake_dem(truth, s)["sigma_u_MPa"] for s in range(100, 400)]))}
    uncertainty = {}
    problems = calibrate.Problems()
    args = type("Args", (), {"curve": [path], "curve_window": None})()
    with_axes = dict(DESCRIPTION, curve_axes={"x": "axial strain", "y": "axial stress (MPa)"})
    curves = calibrate.measured_curves(args, targets, uncertainty, with_axes, "trust-region", problems)
    problems.raise_if_any()
    assert len(targets) == 1 + 16 and not uncertainty
    code, solution, out = run_calibration(tmp_path, bin_dir, targets, budget=80, curves=curves)
    assert code == calibrate.EXIT_MET, solution["why"]
    assert solution["dem_runs"] <= 80
    rows = json.load(open(os.path.join(out, "verification.json")))["outputs"]
    names = curve_targets.names(curves)
    assert set(names) < set(rows) and all(rows[n]["passed"] for n in names)
    assert all(rows[n]["mean"] < 0 for n in names if "curve_lateral@" in n)  # compression positive, as the file
    x = solution["x"]
    for q in curves[0]["points"]:
        kind = "stress_MPa" if q["kind"] == "stress" else "lateral_strain"
        sign = 1 if q["kind"] == "stress" else -1
        mean = np.mean([sign * np.interp(q["strain"], c["axial_strain"], c[kind])
                        for c in (fake_curve(x, s) for s in range(100, 400))])
        assert abs(mean / q["value"] - 1) < 0.05, (q["name"], mean, q["value"])
    report(out)
    assert "| curve_MPa@" in open(os.path.join(out, "report.md")).read()


def test_a_curve_point_too_scattered_for_its_seeds_asks_for_as_many_as_its_sd_needs():
    # demcal-verify chooses its seeds by the scalar targets; a curve point whose half-width is still too wide asks
    # for the seeds its SD needs ((t sd / (tol target))^2), at least one more, at most max_seeds.
    curves = [{"label": None, "points": [{"name": "curve_MPa@0.001", "kind": "stress"},
                                         {"name": "curve_MPa@0.002", "kind": "stress"}]}]
    seeds = [{"seed": s, "status": "ok"} for s in range(2, 7)]

    def v(sd, half):
        return {"seeds": seeds, "outputs": {"curve_MPa@0.001": {"runs": 5, "sd": 0.1, "target": 10.0,
                                                                "half_width_pct": 1.0},
                                            "curve_MPa@0.002": {"runs": 5, "sd": sd, "target": 20.0,
                                                                "half_width_pct": half}}}
    assert curve_targets.seeds_wanted(v(0.5, 3.1), curves, 0.05, 20) is None
    # SD 1.5 of 20 at 5 % needs (2.776 * 1.5 / 1)^2 = 17.3 -> 18 seeds.
    assert curve_targets.seeds_wanted(v(1.5, 9.3), curves, 0.05, 20) == 18
    assert curve_targets.seeds_wanted(v(3.0, 18.6), curves, 0.05, 20) == 20
    assert curve_targets.seeds_wanted(v(0.75, 5.2), curves, 0.05, 20) == 6  # (2.776 * 0.75)^2 = 4.3: one more
    seeds.extend({"seed": s, "status": "ok"} for s in range(7, 22))
    assert curve_targets.seeds_wanted(v(3.0, 7.0), curves, 0.05, 20) is None  # 20 run: no more


def test_a_finer_resolution_check_gives_every_curve_point_its_shift(tmp_path, monkeypatch):
    # demcal-verify runs the scalar target on both resolutions and gives its shift; the curve's points are read
    # from the seeds' curves of each: here the finer specimens' curves are 10 % softer at every strain.
    class Tools:
        jobs, cache = "1", str(tmp_path / "cache")

        def program(self, name):
            return name

    curves = [{"label": None, "points": [{"name": "curve_MPa@0.001", "kind": "stress", "strain": 0.001, "value": 10.0},
                                         {"name": "curve_MPa@0.002", "kind": "stress", "strain": 0.002, "value": 20.0}]}]
    folder = tmp_path / "v01"

    def curve(seed, factor):
        return {"axial_strain": [0.0, 0.003], "stress_MPa": [0.0, factor * (30.0 + 0.1 * seed)]}

    def fake_run(cmd, stdout=None):
        for batch, seeds, factor in (("runs.h5", range(2, 7), 1.0), ("finer_runs.h5", range(2, 4), 0.9)):
            points = folder / "runs" / f"{batch}.points"
            points.mkdir(parents=True, exist_ok=True)
            for s in seeds:
                (points / f"run1_seed{s}.json").write_text(json.dumps({"curve": curve(s, factor)}))
        v = {"passed": True, "verdict": "mean_inside_band",
             "outputs": {"y": {"mean": 1.0, "relative_error_pct": 0.0, "half_width_pct": 1.0, "passed": True}},
             "seeds": [{"seed": s, "status": "ok", "macro": {"y": 1.0}} for s in range(2, 7)],
             "finer": {"factor": 2.0, "seeds": [{"seed": s} for s in (2, 3)], "shift_pct": {"y": -1.5}}}
        with open(cmd[cmd.index("--out") + 1], "w") as f:
            json.dump(v, f)
        return type("Done", (), {"returncode": 0})()

    monkeypatch.setattr(calibrate_runs.subprocess, "run", fake_run)
    targets = {"y": 1.0, "curve_MPa@0.001": 10.0, "curve_MPa@0.002": 20.0}
    v = calibrate_runs.verify(Tools(), "scene.json", str(folder), {"a_Pa": 1e8}, targets, dict(targets), 2, 5, 20, 0.05,
                              True, scale_resolution=2.0, curves=curves)
    shifts = v["finer"]["shift_pct"]
    assert shifts["y"] == -1.5  # demcal-verify's own, kept
    # Coarse seeds 2-6 against finer seeds 2-3, each curve linear in strain: the mean stresses' ratio at any strain.
    expected = 100 * (0.9 * np.mean([30 + 0.1 * s for s in (2, 3)]) / np.mean([30 + 0.1 * s for s in range(2, 7)]) - 1)
    assert shifts["curve_MPa@0.001"] == pytest.approx(expected, rel=1e-12)
    assert shifts["curve_MPa@0.002"] == pytest.approx(expected, rel=1e-12)
    assert json.load(open(folder / "verification.json"))["finer"]["shift_pct"] == shifts  # stored as returned
