"""Stored calibrations of literature targets, replayed: each fixture (scripts/replay_fixture.py) holds every DEM
result a real calibration used and the decisions it made. The calibration runs again on those results alone, so a
change to the searches, the runner or the verifier that asks for a point the stored one did not run, or decides
otherwise, fails here. Nothing is built or run: the DEM and demcal-verify answer from the fixture."""
import glob
import json
import math
import os

import pytest

from demcal_study import calibrate, calibrate_runs, commands, executables

FIXTURES = sorted(glob.glob(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "replay_*.json")))
RTOL = 1e-9  # the decisions are the same computation on the same results; 1e-9 leaves room for a BLAS's last digits


def close(a, b, where):
    """Whether two decoded JSON values agree, numbers within RTOL; raises AssertionError naming the first place
    they do not."""
    if isinstance(a, dict) and isinstance(b, dict):
        assert set(a) == set(b), f"{where}: keys {sorted(set(a) ^ set(b))} differ"
        for k in a:
            close(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list) and isinstance(b, list):
        assert len(a) == len(b), f"{where}: {len(a)} items against {len(b)}"
        for k, (x, y) in enumerate(zip(a, b)):
            close(x, y, f"{where}[{k}]")
    elif isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) or not isinstance(b, (int, float)):
        assert a == b, f"{where}: {a!r} against {b!r}"
    else:
        assert a == b or math.isclose(a, b, rel_tol=RTOL, abs_tol=1e-300), f"{where}: {a!r} against {b!r}"


@pytest.mark.parametrize("path", FIXTURES, ids=[os.path.basename(p)[len("replay_"):-len(".json")] for p in FIXTURES])
def test_a_stored_calibration_replays_to_the_same_decisions(path, tmp_path, monkeypatch):
    with open(path) as f:
        fixture = json.load(f)
    asked = {"points": 0, "verifications": 0}

    def run_points(tools, scene, folder, points, quiet):
        results = []
        for p in points:
            hit = next((q for q in fixture["points"] if calibrate_runs.same_values(q["parameters"], p)), None)
            assert hit is not None, f"{folder}: the replay asks for a point the stored calibration did not run: {p}"
            results.append({"status": hit["status"], "outputs": dict(hit["outputs"]), "reason": "", "curve": None})
        asked["points"] += len(points)
        return results

    def verify(tools, scene, folder, parameters, targets, predicted, first_seed, seeds, max_seeds, tolerance, quiet,
               intervals=None, scale_resolution=None, curves=None):
        hit = next((v for v in fixture["verifications"] if calibrate_runs.same_values(v["x"], parameters)), None)
        assert hit is not None, f"{folder}: the replay verifies a point the stored calibration did not: {parameters}"
        assert hit["verification"]["seeds"][0]["seed"] == first_seed, f"{folder}: verified on other seeds"
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "verification.json"), "w") as f:
            json.dump(hit["verification"], f)
        asked["verifications"] += 1
        return json.loads(json.dumps(hit["verification"]))

    monkeypatch.setattr(calibrate_runs, "run_points", run_points)
    monkeypatch.setattr(calibrate_runs, "verify", verify)
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: fixture["description"])
    out = str(tmp_path / "cal")
    os.makedirs(os.path.join(out, "rounds"))
    if fixture["design_lhs"]:  # demcal-doe's design, as a resumed calibration finds it
        with open(os.path.join(out, "rounds", "design_lhs.csv"), "w") as f:
            f.write(fixture["design_lhs"])
    with open(os.path.join(out, "calibration.json"), "w") as f:
        json.dump(fixture["config"], f)
    tools = commands.Tools(bin="no-executables-needed", jobs="1", cache=str(tmp_path / "cache"), python="")
    code = calibrate.Calibration(fixture["config"], out, tools, quiet=True).run()
    with open(os.path.join(out, "solution.json")) as f:
        solution = json.load(f)
    decisions = fixture["decisions"]
    assert code == decisions["exit_code"], solution["why"]
    close({k: solution.get(k) for k in decisions}, decisions, "solution")
    assert asked["verifications"] == len(fixture["verifications"])
