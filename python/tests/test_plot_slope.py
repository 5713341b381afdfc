"""scripts/plot_slope.py: draws a slope run's snapshots and velocity histories; a missing snapshot, a failed run or
a point the run did not monitor is a one-line error with exit 2."""
import csv
import json
import os
import subprocess
import sys

from conftest import REPO

SCRIPT = os.path.join(REPO, "scripts", "plot_slope.py")


def snapshot(path, time, disks):
    """A legacy-VTK disk snapshot as the slope test writes it: POINTS, then a radius field."""
    lines = ["# vtk DataFile Version 3.0", f"demcal disks at t = {time} s", "ASCII", "DATASET POLYDATA",
             f"POINTS {len(disks)} double"]
    lines += [f"{x} {y} 0" for x, y, _ in disks]
    lines += [f"POINT_DATA {len(disks)}", "SCALARS radius double 1", "LOOKUP_TABLE default"]
    lines += [str(r) for _, _, r in disks]
    path.write_text("\n".join(lines) + "\n")


def slope_run(tmp_path, status="ok"):
    folder = tmp_path / "vtk"
    folder.mkdir()
    bedrock = [(5.0 * i + 2.5, 2.5, 2.5) for i in range(10)]
    for name, shift in (("slope_start.vtk", 0), ("slope_input_end.vtk", 1), ("slope_end.vtk", 3)):
        fill = [(0.5 * i + 0.5 + shift, 5.5, 0.5) for i in range(20)]
        snapshot(folder / name, shift, bedrock + fill)
    result = tmp_path / "run.json"
    result.write_text(json.dumps({"status": status, "reason": "" if status == "ok" else "unstable",
                                  "macro": {"peak_speed_m_s_3_3": 0.4, "peak_time_s_3_3": 2.2}}))
    curve = tmp_path / "run.csv"
    with open(curve, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "vx_3_3_m_s", "vy_3_3_m_s"])
        for k in range(50):
            w.writerow([0.1 * k, 0.01 * k, 0.0])
    return folder, result, curve


def run(*args):
    return subprocess.run([sys.executable, SCRIPT, *map(str, args)], capture_output=True, text=True)


def test_draws_the_snapshots_and_the_velocities(tmp_path):
    folder, result, curve = slope_run(tmp_path)
    done = run("--vtk", folder, "--out", tmp_path / "s.png", "--result", result, "--curve", curve,
               "--points", "3-3", "--velocity-out", tmp_path / "v.png")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "s.png").stat().st_size > 1000
    assert (tmp_path / "v.png").stat().st_size > 1000


def test_a_missing_snapshot_is_one_line_exit_2(tmp_path):
    folder, _, _ = slope_run(tmp_path)
    (folder / "slope_end.vtk").unlink()
    done = run("--vtk", folder, "--out", tmp_path / "s.png")
    assert done.returncode == 2
    assert "missing snapshot(s)" in done.stderr and "slope_end.vtk" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


def test_a_point_not_monitored_and_a_failed_run_are_refused(tmp_path):
    folder, result, curve = slope_run(tmp_path)
    done = run("--vtk", folder, "--out", tmp_path / "s.png", "--result", result, "--curve", curve,
               "--points", "9-9", "--velocity-out", tmp_path / "v.png")
    assert done.returncode == 2
    assert "no column vx_9_9_m_s (point 9-9 is not a monitoring point of this run)" in done.stderr
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"status": "failed", "reason": "unstable"}))
    done = run("--vtk", folder, "--out", tmp_path / "s.png", "--result", bad, "--curve", curve,
               "--velocity-out", tmp_path / "v.png")
    assert done.returncode == 2
    assert "the run failed (unstable)" in done.stderr
