"""scripts/boundary_calibration_comparison.py: the runs an optimiser took to come within 5 % of its own best and of the
best of all, and bad arguments as one-line errors (the DEM runs themselves are `make boundary-calibration`'s)."""
import os
import subprocess
import sys

from conftest import REPO, load_script

SCRIPT = os.path.join(REPO, "scripts", "boundary_calibration_comparison.py")


def module():
    return load_script("boundary_calibration_comparison")


def test_runs_to_within_a_share_of_the_final_best():
    m = module()
    points = [(1, 1.0), (20, 0.6), (40, 0.52), (120, 0.5)]
    assert m.runs_to_within(points, 0.05) == 40  # 0.52 is within 5 % of 0.5
    assert m.runs_to_within(points, 0.01) == 120
    assert m.runs_to_within([(7, 0.3)], 0.05) == 7


def test_runs_to_within_a_share_of_a_common_best_or_never():
    m = module()
    points = [(1, 1.0), (20, 0.6), (40, 0.52), (120, 0.5)]
    assert m.runs_to_within(points, 0.05, best=0.48) == 120  # 0.5 is within 5 % of 0.48, 0.52 is not
    assert m.runs_to_within(points, 0.05, best=0.40) is None  # this run never came near the best of all


def test_medians_of_run_counts_rank_never_above_every_count():
    m = module()
    assert m.median_and_range([105, 64, 161]) == "105 (64-161)"
    assert m.median_and_range([None, 81, 360]) == "360 (81-never)"
    assert m.median_and_range([None, 104, None]) == "never (104-never)"
    assert m.median_and_range([10, 20]) == "15 (10-20)"
    assert m.median_and_range([10, None]) == "never (10-never)"


def test_bad_arguments_are_one_line_errors(tmp_path):
    done = subprocess.run([sys.executable, SCRIPT, "--budget", "5", "--out", str(tmp_path)], capture_output=True,
                          text=True)
    assert done.returncode == 2
    assert "--budget must be at least 10" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


def test_a_scene_the_script_does_not_know_needs_its_space_and_reference(tmp_path):
    done = subprocess.run([sys.executable, SCRIPT, "--scene", "data/scenes/ucs_rock_pb.json", "--out", str(tmp_path)],
                          capture_output=True, text=True, cwd=REPO)
    assert done.returncode == 2
    assert "data/scenes/ucs_rock_pb.json: not a shipped boundary scene; give --space and --fixed-scene" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    done = subprocess.run([sys.executable, SCRIPT, "--scene", "data/scenes/rockfill_slope.json", "--fixed-scene",
                           "data/scenes/no_such_scene.json", "--out", str(tmp_path)], capture_output=True, text=True,
                          cwd=REPO)
    assert done.returncode == 2
    assert "data/scenes/no_such_scene.json: no such file" in done.stderr


def test_make_passes_a_budget_only_when_one_is_given():
    # make calibrate's default BUDGET of 80 once reached this target and cut the slope's 400 runs to 80.
    def dry(*args):
        done = subprocess.run(["make", "-n", "boundary-calibration"] + list(args), cwd=REPO, capture_output=True,
                              text=True)
        assert done.returncode == 0, done.stderr
        return [line for line in done.stdout.splitlines() if "--budget" in line or "--scene" in line]
    assert not any("--budget" in line for line in dry("SCENE=data/scenes/rockfill_slope.json"))
    assert any("--budget 12" in line for line in dry("BUDGET=12"))
