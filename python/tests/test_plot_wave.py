"""scripts/plot_wave.py: draws wave-strip results' velocity histories; a failed run or a result that is not a
wave strip's is a one-line error with exit 2."""
import json
import math
import os
import subprocess
import sys

from conftest import REPO

SCRIPT = os.path.join(REPO, "scripts", "plot_wave.py")


def strip_result(tmp_path, name, status="ok", curve=True):
    t = [0.002 * k for k in range(200)]
    result = {"status": status, "reason": "" if status == "ok" else "unstable",
              "macro": {"total_recovery_time_s": 1.2, "reflection_coefficient": 0.1}, "curve": {}}
    if curve:
        result["curve"]["time_s"] = t
        for k, delay in enumerate([0.05, 0.15, 0.25], start=1):
            v = [0.5 * (1 - math.cos(2 * math.pi * (x - delay) / 0.2)) if delay <= x <= delay + 0.2 else 0.0 for x in t]
            result["curve"][f"vx_T{k}_m_s"] = v
            result["curve"][f"vy_T{k}_m_s"] = [0.0] * len(t)
    path = tmp_path / name
    path.write_text(json.dumps(result))
    return path


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *map(str, args)], capture_output=True, text=True)


def test_draws_one_panel_per_run(tmp_path):
    out = tmp_path / "wave.png"
    done = run(strip_result(tmp_path, "a.json"), strip_result(tmp_path, "b.json"), "--labels", "fixed", "viscous",
               "--out", out)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_failed_run_or_another_tests_result_is_a_one_line_error(tmp_path):
    for path, message in [(strip_result(tmp_path, "f.json", status="failed"), "the run failed (unstable)"),
                          (strip_result(tmp_path, "n.json", curve=False), "not a wave-strip result")]:
        done = run(path, "--out", tmp_path / "x.png")
        assert done.returncode == 2
        assert message in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1
    done = run(strip_result(tmp_path, "a.json"), "--labels", "one", "two", "--out", tmp_path / "x.png")
    assert done.returncode == 2 and "2 labels for 1 results" in done.stderr


def test_takes_the_curve_from_a_csv_when_the_result_has_none(tmp_path):
    with_curve = json.loads(strip_result(tmp_path, "a.json").read_text())
    columns = with_curve.pop("curve")
    (tmp_path / "bare.json").write_text(json.dumps(with_curve))
    names = list(columns)
    rows = [",".join(names)] + [",".join(str(columns[n][k]) for n in names) for k in range(len(columns["time_s"]))]
    (tmp_path / "a.csv").write_text("\n".join(rows) + "\n")
    out = tmp_path / "wave.png"
    done = run(tmp_path / "bare.json", "--curves", tmp_path / "a.csv", "--out", out)
    assert done.returncode == 0, done.stderr
    assert out.exists()


def test_named_points_of_a_slope_result_and_a_missing_one_as_one_line(tmp_path):
    t = [0.01 * k for k in range(100)]
    result = {"status": "ok", "macro": {"total_recovery_time_s": 8.0, "recovery_time_s_2_1": 1.06},
              "curve": {"time_s": t, "vy_2_1_m_s": [math.sin(x) for x in t], "vx_2_1_m_s": [0.0] * len(t)}}
    path = tmp_path / "slope.json"
    path.write_text(json.dumps(result))
    out = tmp_path / "slope.png"
    done = run(path, "--points", "2-1", "--component", "vy", "--out", out)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    done = run(path, "--points", "2-1", "9-9", "--out", tmp_path / "x.png")
    assert done.returncode == 2
    assert "no time_s or no vx column for point(s) 9-9" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
