"""seeds_per_point "auto" (DEM in the loop): the plan measures the scatter first, then chooses K from it."""
import json
import os

import pytest

from conftest import REPO, run_study_layer
from demcal_study import scatter


def loop_study(tmp_path, **changes):
    with open(os.path.join(REPO, "tests", "data", "study_small_loop.json")) as f:
        study = json.load(f)
    study.update(changes)
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
    return str(path)


def test_k_is_the_smallest_with_a_standard_error_below_a_third_of_the_tolerance():
    # tolerance 15 %: allowed 5 %; CV 12 % -> (12 / 5)^2 = 5.76 -> 6 specimens.
    v = {"outputs": {"sigma_u_MPa": {"cv_pct": 12.0}, "E_GPa": {"cv_pct": 3.0}}, "seeds": [{}] * 5}
    chosen = scatter.seeds_per_point(v, 0.15)
    assert chosen["seeds_per_point"] == 6 and not chosen["capped"]
    assert chosen["standard_error_pct"] == pytest.approx(12 / 6 ** 0.5)
    v["outputs"]["sigma_u_MPa"]["cv_pct"] = 40.0  # would need 64: capped, and says so
    chosen = scatter.seeds_per_point(v, 0.15)
    assert chosen["seeds_per_point"] == scatter.MAX_SEEDS_PER_POINT and chosen["capped"]
    v["outputs"]["sigma_u_MPa"]["cv_pct"] = 1.0
    assert scatter.seeds_per_point(v, 0.15)["seeds_per_point"] == 1


def test_the_plan_measures_the_scatter_then_uses_its_k(tmp_path, bin_dir):
    study = loop_study(tmp_path, seeds_per_point="auto")
    out = str(tmp_path / "plan")
    done = run_study_layer(["plan", study, out], bin_dir)
    assert done.returncode == 0, done.stderr
    mk = open(os.path.join(out, "plan.mk")).read()
    assert "$(D)/scatter/verification.json:" in mk and "stages: ;" in mk
    point = json.load(open(os.path.join(out, "config", "scatter_point.json")))
    assert set(point["x"]) == {"pb_sigma_c_MPa", "pb_tau_c_MPa"}
    # The scatter as demcal-verify would have written it: CV 12 % against a 15 % tolerance -> K = 6.
    os.makedirs(os.path.join(out, "scatter"))
    with open(os.path.join(out, "scatter", "verification.json"), "w") as f:
        json.dump({"outputs": {"sigma_u_MPa": {"cv_pct": 12.0}, "E_GPa": {"cv_pct": 2.0}}, "seeds": [{}] * 5}, f)
    done = run_study_layer(["plan", study, out], bin_dir)
    assert done.returncode == 0, done.stderr
    assert json.load(open(os.path.join(out, "config", "seeds.json")))["seeds_per_point"] == 6
    assert json.load(open(os.path.join(out, "config", "inversion.json")))["dem_seeds"] == 6
    assert json.load(open(os.path.join(out, "config", "verification.json")))["first_seed"] == 7  # other specimens
    assert "--dem-seeds 6" in open(os.path.join(out, "plan.mk")).read()


def test_auto_seeds_need_the_dem_in_the_loop(tmp_path):
    with open(os.path.join(REPO, "tests", "data", "study_small.json")) as f:
        study = json.load(f)
    study["seeds_per_point"] = "auto"
    path = tmp_path / "s.json"
    path.write_text(json.dumps(study))
    done = run_study_layer(["plan", str(path), str(tmp_path / "p")])
    assert done.returncode == 2
    assert "seeds_per_point \"auto\" chooses the specimens per DEM-in-the-loop evaluation" in done.stderr
