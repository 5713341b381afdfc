"""A GA-BP study with held-out design points and a search whose candidates are each verified (He et al. 2019's
chain, data/studies/powder_gabp.json), run end to end on the test suite's stand-in simulator (y = 2 a + 3 b + 0.01
(seed mod 5)): the held-out points take no part in the fit and get their own R^2; every candidate is verified and
the best verified one becomes the answer; the report shows the held-out R^2, the Sobol indices, the DEM's range
over the design, the candidate table and the outputs nobody judged at the answer."""
import csv
import json
import os
import subprocess

import pytest

from conftest import REPO, run_study_layer


def write_study(tmp_path, **changes):
    space = tmp_path / "space.json"
    space.write_text(json.dumps({"parameters": [
        {"name": "a_MPa", "unit": "MPa", "low": 0, "high": 5, "reference": 2},
        {"name": "b_MPa", "unit": "MPa", "low": 0, "high": 5, "reference": 3}]}))
    study = {"name": "holdout_candidates", "description": "held-out points and verified candidates",
             "scene": "tests/data/external_fake.json", "space": str(space), "targets": {"y_MPa": 12},
             "fixed": {"mode": 0},
             "surfaces": [{"outputs": ["y_MPa"], "factors": ["a_MPa", "b_MPa"], "design": {"kind": "lhs", "runs": 30},
                           "holdout": 10}],
             "surrogate": "gabp",
             "inversion": {"algorithm": "search", "samples": 300, "search_tolerance": 0.05, "restarts": 1, "seed": 1},
             "verification": {"seeds": 2, "max_seeds": 2, "tolerance": 0.05, "candidates": 3},
             "refinement": {"rounds": 0}}
    study.update(changes)
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    return path


def test_held_out_points_score_the_fit_and_every_candidate_is_verified(tmp_path, bin_dir):
    out = tmp_path / "out"
    planned = run_study_layer(["plan", str(write_study(tmp_path)), str(out)], bin_dir)
    assert planned.returncode == 0, planned.stderr
    env = dict(os.environ, PYTHONPATH=os.path.join(REPO, "python"))
    made = subprocess.run(["make", "--no-print-directory", "-f", str(out / "plan.mk"), f"BIN={bin_dir}",
                           f"CACHE={tmp_path / 'cache'}", "JOBS=2", "all"], cwd=REPO, env=env, capture_output=True,
                          text=True)
    assert made.returncode == 0, made.stdout[-3000:] + made.stderr[-3000:]

    split = json.loads((out / "g1" / "split.json").read_text())
    assert (split["train_points"], split["held_out"]) == (20, 10)
    with open(out / "g1" / "train.csv") as f:
        trained = {int(r["run"]) for r in csv.DictReader(f)}
    with open(out / "g1" / "holdout.csv") as f:
        held = {int(r["run"]) for r in csv.DictReader(f)}
    assert held == set(split["held_out_points"]) and not trained & held and len(trained | held) == 30
    model = json.loads((out / "models" / "y_MPa.json").read_text())
    assert model["training"]["rows"] + model["validation"]["rows"] == 20  # the network never saw a held-out point
    score = json.loads((out / "models" / "y_MPa_holdout.json").read_text())
    # A plane over the box: the network predicts unseen points well (R^2 above 0.95, RMSE below 0.5 MPa on 0-25).
    assert score["rows"] == 10 and score["r2"] > 0.95 and score["rmse"] < 0.5

    candidates = json.loads((out / "candidates.json").read_text())["candidates"]
    assert 1 <= len(candidates) <= 3
    assert sum(c["chosen"] for c in candidates) == 1
    for c in candidates:
        v = json.loads((out / "candidates" / f"c{c['rank']}" / "verification.json").read_text())
        assert len(v["seeds"]) == 2
        # The stand-in's y at the candidate, seeds 1 and 2: 2 a + 3 b + 0.015 on average.
        expected = 2 * c["x"]["a_MPa"] + 3 * c["x"]["b_MPa"] + 0.015
        assert v["outputs"]["y_MPa"]["mean"] == pytest.approx(expected, abs=1e-9)
    chosen = next(c for c in candidates if c["chosen"])
    final = json.loads((out / "verification.json").read_text())
    assert final["solution"].endswith(os.path.join("candidates", f"c{chosen['rank']}", "solution.json"))
    assert final["parameters"]["a_MPa"] == pytest.approx(chosen["x"]["a_MPa"])
    assert chosen["max_abs_relative_error_pct"] == min(c["max_abs_relative_error_pct"] for c in candidates
                                                       if c["verdict"] == chosen["verdict"])
    report = (out / "report.md").read_text()
    for heading in ("## What the DEM reaches over the design", "R^2 held out", "## Sensitivity",
                    "## Candidates verified in DEM"):
        assert heading in report
    # The outputs nobody judged are reported at the answer (its final verification): the stand-in's z = a b.
    z = final["parameters"]["a_MPa"] * final["parameters"]["b_MPa"]
    assert f"Other outputs at the answer (mean and SD over the final verification's seeds that ran): z {z:.4g} (SD 0)." in report
    # The cost counts the design and every candidate's verification runs.
    from demcal_study.cost import study_cost
    assert study_cost(str(out))["dem_runs"] == 30 + 2 * len(candidates)


def test_the_settings_of_a_search_need_a_search(tmp_path, bin_dir):
    path = write_study(tmp_path, inversion={"algorithm": "ga", "samples": 300})
    done = run_study_layer(["plan", str(path), str(tmp_path / "out")], bin_dir)
    assert done.returncode != 0 and "inversion.samples is a setting of the search" in done.stderr
    path = write_study(tmp_path, inversion={"algorithm": "ga"})
    done = run_study_layer(["plan", str(path), str(tmp_path / "out")], bin_dir)
    assert done.returncode != 0 and "verification.candidates verifies a search's" in done.stderr


def test_a_holdout_must_leave_points_to_fit_on(tmp_path, bin_dir):
    path = write_study(tmp_path, surfaces=[{"outputs": ["y_MPa"], "factors": ["a_MPa", "b_MPa"],
                                            "design": {"kind": "lhs", "runs": 10}, "holdout": 10}])
    done = run_study_layer(["plan", str(path), str(tmp_path / "out")], bin_dir)
    assert done.returncode != 0 and "holds out 10 of its 10 design points" in done.stderr


def test_a_candidate_whose_seeds_failed_loses_to_one_judged_on_all_of_them():
    from demcal_study.candidates import choose
    row = lambda rank, verdict, failed, error: {"rank": rank, "verdict": verdict, "seeds_failed": failed,  # noqa: E731
                                               "max_abs_relative_error_pct": error}
    # Both outside: the one judged on 2 of 5 seeds loses despite its smaller error.
    assert choose([row(1, "outside", 0, 15.7), row(2, "outside", 3, 4.9)])["rank"] == 1
    # A verdict still comes first, then the error.
    assert choose([row(1, "outside", 0, 1.0), row(2, "mean_inside_band", 1, 3.0)])["rank"] == 2
    assert choose([row(1, "interval_inside_band", 0, 2.0), row(2, "interval_inside_band", 0, 1.0)])["rank"] == 2
