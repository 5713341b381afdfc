"""scripts/uncertainty_benchmark.py without the DEM: the truths are a Latin hypercube of the prior, and the summary
counts what simulation-based calibration counts (the DEM runs themselves are `make uncertainty-benchmark`'s)."""
import json
import os

import numpy as np
import pytest

from conftest import REPO, load_script
from demcal_study.calibration_problem import Problem
from test_calibrate import DESCRIPTION


def module():
    return load_script("uncertainty_benchmark")


def test_the_space_keeps_the_four_searched_and_holds_the_rest_with_the_smallest_specimen():
    m = module()
    with open(os.path.join(REPO, "data", "spaces", "wang2017_rock_cb.json")) as f:
        space = m.benchmark_space(json.load(f))
    assert sorted(p["name"] for p in space["parameters"]) == sorted(m.SEARCHED)
    assert space["fixed"]["R_min_m"] == 0.001  # the space's largest radius: the fewest disks
    assert {"mu", "cb_sigma_c_std_Pa", "cb_tau_c_std_Pa", "R_max_over_R_min"} <= set(space["fixed"])


def test_the_truths_fill_the_prior_one_per_stratum_of_every_coordinate():
    m = module()
    space = {"parameters": [{"name": "Ec_Pa", "low": 1e9, "high": 1e11}, {"name": "kn_ks", "low": 0.5, "high": 10}],
             "fixed": {"sc_Pa": 1e8, "mu": 0.5}}
    problem = Problem(DESCRIPTION, {"E_GPa": 1.0}, space=space, where="test")
    truths = m.truths(problem, 20, seed=1)
    assert len(truths) == 20
    for c in problem.coordinates:
        u = np.array([c.code(t[c.name]) for t in truths])
        # A Latin hypercube: exactly one truth in each of the 20 strata of the coded interval.
        assert sorted(np.floor((u + 1) / 2 * 20).astype(int)) == list(range(20))
    assert truths == m.truths(problem, 20, seed=1) and truths != m.truths(problem, 20, seed=2)


def test_the_summary_counts_identified_intervals_that_hold_the_truth():
    m = module()
    posterior = {"parameters": {"a": {"credible_90": [1.0, 2.0], "identified": True, "coded_width": 0.5},
                                "b": {"credible_90": [1.0, 2.0], "identified": True, "coded_width": 0.8},
                                "c": {"credible_90": [0.0, 9.0], "identified": False, "coded_width": 1.9}}}
    predictive = {"outputs": {"E_GPa": {"posterior": {"interval_95": [9.0, 11.0]}, "target": 10.0, "inside": True,
                                        "verified_mean": 10.1, "exported": {"interval_95": [9.5, 10.5]}},
                              "nu": {"posterior": {"interval_95": [0.2, 0.3]}, "target": 0.25, "inside": False,
                                     "verified_mean": 0.35, "exported": {"interval_95": [0.22, 0.28]}},
                              "sigma_t_MPa": {"posterior": {"interval_95": [4, 6]}, "target": None, "inside": True,
                                              "verified_mean": 5.0, "exported": {"interval_95": [4.5, 5.5]}}}}
    fresh = [{"E_GPa": 10.0 + 0.1 * k, "nu": 0.35} for k in range(5)]
    row = m.rock_result({"a": 1.5, "b": 3.0, "c": 5.0}, posterior, predictive, {"status": "met", "dem_runs": 57},
                        fresh)
    assert row["parameters"]["a"]["inside"] and not row["parameters"]["b"]["inside"]
    assert row["predictive"]["E_GPa"]["inside"] and not row["predictive"]["nu"]["inside"]
    assert "sigma_u_MPa" not in row["predictive"]  # no predictive for it: not counted
    s = m.summary([row, dict(row, dem_runs=43)])
    assert s["coverage_identified"] == pytest.approx(0.5)  # a in, b out, twice; c not identified, not counted
    assert s["identified_intervals"] == 4
    assert s["per_parameter"]["c"] == {"identified": 0, "inside": 0, "median_width_of_prior": pytest.approx(0.95)}
    assert s["dem_runs_median"] == 50 and s["dem_runs_max"] == 57
    assert s["predictive_inside"] == pytest.approx(0.5) and s["met"] == 2
    # At the exported point: E in, nu out (targets); the untargeted tensile strength in, counted among all outputs.
    assert s["exported_targets_inside"] == pytest.approx(0.5) and s["exported_target_checks"] == 4
    assert s["exported_all_inside"] == pytest.approx(4 / 6) and s["exported_all_checks"] == 6


def test_the_summary_lists_each_rock_with_its_misses(tmp_path):
    m = module()
    posterior = {"parameters": {"a": {"credible_90": [1.0, 2.0], "identified": True, "coded_width": 0.5},
                                "b": {"credible_90": [1.0, 2.0], "identified": False, "coded_width": 1.5}}}
    predictive = {"outputs": {"E_GPa": {"posterior": {"interval_95": [9.0, 11.0]}, "target": 10.0, "inside": False,
                                        "verified_mean": 12.0, "exported": {"interval_95": [9.5, 10.5]}}}}
    row = dict(m.rock_result({"a": 3.0, "b": 1.5}, posterior, predictive, {"status": "budget", "dem_runs": 100},
                             [{"E_GPa": 12.0}] * 5), name="rock01")
    m.write_summary(str(tmp_path), m.summary([row]), [row], "# test")
    text = (tmp_path / "summary.md").read_text()
    assert "| rock01 | 3 | 1.5 | budget | 100 | a NO | E_GPa (truth), E_GPa (exported) |" in text, text

