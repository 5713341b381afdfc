"""scripts/plot_heap.py: draws a heap result with its profile and fitted flanks; a failed run or a result
without a curve is a one-line error with exit 2."""
import json
import os
import subprocess
import sys

from conftest import REPO

SCRIPT = os.path.join(REPO, "scripts", "plot_heap.py")


def heap_result(tmp_path, status="ok"):
    # A 30-degree heap 20 mm high, its profile as a batch point's curve.
    slope = 0.57735
    x = [k * 0.002 - 0.04 for k in range(41)]
    h = [max(0.0, 0.02 - slope * abs(v)) for v in x]
    result = {"status": status, "reason": "" if status == "ok" else "the funnel jammed",
              "macro": {"aor_deg": 30.0, "aor_left_deg": 30.0, "aor_right_deg": 30.0, "heap_height_m": 0.02,
                        "flow_time_s": 0.5},
              "specimen": {"aor_left_slope": slope, "aor_left_intercept_m": 0.02, "aor_right_slope": -slope,
                           "aor_right_intercept_m": 0.02},
              "curve": {"axial_strain": x, "lateral_strain": h}}
    path = tmp_path / "heap.json"
    path.write_text(json.dumps(result))
    return path


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *map(str, args)], capture_output=True, text=True)


def test_draws_a_heap_from_a_result_with_its_curve(tmp_path):
    out = tmp_path / "heap.png"
    done = run(heap_result(tmp_path), "--out", out)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_takes_the_curve_from_a_csv_when_the_result_has_none(tmp_path):
    path = heap_result(tmp_path)
    result = json.loads(path.read_text())
    curve = result.pop("curve")
    path.write_text(json.dumps(result))
    csv = tmp_path / "profile.csv"
    csv.write_text("run,axial_strain,stress_MPa,lateral_strain,cracks\n" + "".join(
        f"{k + 1},{x},0,{h},0\n" for k, (x, h) in enumerate(zip(curve["axial_strain"], curve["lateral_strain"]))))
    missing = run(path, "--out", tmp_path / "a.png")
    assert missing.returncode == 2 and "--curve" in missing.stderr and missing.stderr.count("\n") == 1
    done = run(path, "--curve", csv, "--out", tmp_path / "b.png")
    assert done.returncode == 0, done.stderr


def test_a_failed_run_is_a_one_line_error(tmp_path):
    done = run(heap_result(tmp_path, status="failed"), "--out", tmp_path / "c.png")
    assert done.returncode == 2
    assert "the funnel jammed" in done.stderr and done.stderr.count("\n") == 1
