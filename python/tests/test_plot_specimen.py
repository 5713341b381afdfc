"""scripts/plot_specimen.py: draws a UCS specimen from its VTK snapshots, with the platens from the walls file
`demcal-dem run --vtk` writes beside the disks."""
import glob
import os
import subprocess
import sys

from conftest import REPO

SCRIPTS = os.path.join(REPO, "scripts")
sys.path.insert(0, SCRIPTS)
from plot_specimen import read_vtk, read_vtk_lines  # noqa: E402


def test_the_walls_file_holds_the_platens_where_the_disks_meet_them_and_the_picture_takes_it(tmp_path, bin_dir):
    vtk = tmp_path / "vtk"
    done = subprocess.run([os.path.join(bin_dir, "demcal-dem"), "run", "--scene",
                           os.path.join(REPO, "tests", "data", "ucs_small.json"), "--seed", "1", "--quiet",
                           "--threads", "1", "--vtk", str(vtk), "--out", str(tmp_path / "r.json")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    disks, = glob.glob(str(vtk / "final_0*.vtk"))
    breaks, = glob.glob(str(vtk / "final_breaks_*.vtk"))
    walls, = glob.glob(str(vtk / "final_walls_*.vtk"))
    xy, s = read_vtk(disks)
    segments, ws = read_vtk_lines(walls)
    assert len(segments) == len(ws["active"]) >= 2
    # The acting walls of a UCS are its two platens, level, one under the lowest disk centre and one over the
    # highest, each overlapping (or within a skin of) the disks it holds: within a tenth of the smallest radius.
    platens = [seg for seg, on in zip(segments, ws["active"]) if on]
    assert len(platens) == 2
    levels = sorted(a[1] for a, b in platens)
    for a, b in platens:
        assert a[1] == b[1]
    bottom, top = levels
    r = s["radius"]
    assert bottom < xy[:, 1].min() and top > xy[:, 1].max()
    assert abs((xy[:, 1] - r).min() - bottom) < 0.1 * r.min()
    assert abs((xy[:, 1] + r).max() - top) < 0.1 * r.min()
    out = tmp_path / "specimen.png"
    done = subprocess.run([sys.executable, os.path.join(SCRIPTS, "plot_specimen.py"), disks, breaks, "--walls", walls,
                           "--out", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
