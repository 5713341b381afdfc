"""The LIGGGHTS drum driver (data/external/liggghts/run_drum_liggghts.py): its surface measure against a closed
form, what it reads from a drum scene and refuses, the mesh it writes (closed), the input it writes, and the parsing
of LIGGGHTS' dumps and logs. One short drum in LIGGGHTS itself when Debian's liggghts is installed."""
import copy
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
from collections import Counter

import pytest

from conftest import REPO

DRIVER = os.path.join(REPO, "data", "external", "liggghts", "run_drum_liggghts.py")
SCENE = os.path.join(REPO, "data", "scenes", "drum_spheres_3d.json")


def load_driver():
    spec = importlib.util.spec_from_file_location("run_drum_liggghts", DRIVER)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


drv = load_driver()


def scene():
    with open(SCENE) as f:
        return json.load(f)


def defaults(s):
    return {name: p["value"] for name, p in s["parameters"].items()}


@pytest.mark.parametrize("angle_deg", [0.0, 12.5, 30.0, 47.8])
def test_the_surface_measure_returns_the_angle_of_a_straight_surface(angle_deg):
    # One sphere on the surface line at the middle of every bin: the fit is exact, whatever the fraction fitted.
    r_drum, bin_m, radius = 0.0225, 0.003, 0.0015
    bins = int(math.ceil(2 * r_drum / bin_m))
    x = [-r_drum + (b + 0.5) * bin_m for b in range(bins)]
    z = [math.tan(math.radians(angle_deg)) * xi for xi in x]
    # Spheres below the surface change nothing.
    x += x[:5]
    z += [zi - 0.01 for zi in z[:5]]
    got = drv.surface_angle_deg(x, z, [radius] * len(x), r_drum, bin_m, 0.6)
    assert got == pytest.approx(angle_deg, abs=1e-9)


def test_the_surface_measure_fits_only_the_middle_bins():
    # A surface at 20 degrees in its middle 60 % and climbing the shell at both ends reads 20 degrees.
    r_drum, bin_m = 0.02, 0.002
    x = [-r_drum + (b + 0.5) * bin_m for b in range(20)]
    z = [math.tan(math.radians(20)) * xi for xi in x]
    for k in (0, 1, 2, 3):
        z[k] += 0.05
    for k in (16, 17, 18, 19):
        z[k] += 0.01
    assert drv.surface_angle_deg(x, z, [0.001] * 20, r_drum, bin_m, 0.6) == pytest.approx(20, abs=1e-9)
    assert drv.surface_angle_deg(x, z, [0.001] * 20, r_drum, bin_m, 1.0) != pytest.approx(20, abs=1)


def test_a_flow_is_steady_when_its_halves_agree():
    mean, sd, first, second = drv.steady_angle([30, 31, 29, 30, 31, 29], 2.0)
    assert (mean, first, second) == (30, 30, 30)
    assert sd == pytest.approx(math.sqrt(4 / 5))
    with pytest.raises(drv.Refused, match="no steady state"):
        drv.steady_angle([20, 21, 20, 30, 31, 30], 2.0)
    with pytest.raises(drv.Refused, match="only 3 surface samples"):
        drv.steady_angle([20, 21, 20], 2.0)


def test_the_shipped_scene_is_read_with_the_points_parameters_bound():
    s = scene()
    values = dict(defaults(s), mu_pp=0.7, mu_r_pp=0.12)
    particles, drum, run, contacts = drv.read_drum(s, values)
    assert contacts["particle-particle"]["friction"] == 0.7
    assert contacts["particle-particle"]["rolling_friction_cdt_relative"] == 0.12
    assert contacts["particle-wall"]["shear_modulus_2_pa"] == 7.9e10
    assert drum["fill_fraction"] == 0.3 and run["rayleigh_fraction"] == 0.2
    assert run["surface_fraction"] == 0.6  # drum_3d's default where the scene is silent


@pytest.mark.parametrize("edit, message", [
    (lambda s: s.update(test="heap_3d"), "this driver runs drum_3d scenes"),
    (lambda s: s["particles"].update(clump_aspect_ratio=1.3, clump_fraction=1.0), "particles: clumps"),
    (lambda s: s["run"].update(local_damping=0.1), "run.local_damping"),
    (lambda s: s["run"].pop("rayleigh_fraction"), "run.rayleigh_fraction"),
    (lambda s: s["contacts"]["particle-wall"]["parameters"].update(rolling_friction_cdt=0.1),
     "contacts.particle-wall.parameters.rolling_friction_cdt: no LIGGGHTS counterpart"),
    (lambda s: s["contacts"]["particle-particle"].update(model="jkr"), "contacts.particle-particle.model \"jkr\""),
    (lambda s: s["contacts"]["particle-wall"]["parameters"].update(poisson=0.3),
     "contacts.particle-wall.parameters.poisson: differs"),
    (lambda s: s["contacts"]["particle-particle"]["parameters"].update(friction="mu_xx"),
     "\"mu_xx\" in \"mu_xx\" is neither a number nor a parameter"),
])
def test_what_liggghts_cannot_run_is_refused_by_name(edit, message):
    s = copy.deepcopy(scene())
    edit(s)
    with pytest.raises(drv.Refused, match=message.replace("(", r"\(").replace(")", r"\)")):
        drv.read_drum(s, defaults(scene()))


def test_the_drum_mesh_is_closed_and_on_the_drum(tmp_path):
    path = tmp_path / "drum.stl"
    radius, length, facets = 0.0225, 0.1, 24
    assert drv.write_drum_stl(str(path), radius, length, facets) == 4 * facets
    triangles, vertex = [], []
    for line in path.read_text().splitlines():
        if line.startswith("vertex"):
            vertex.append(tuple(round(float(v), 12) for v in line.split()[1:]))
            if len(vertex) == 3:
                triangles.append(vertex)
                vertex = []
    edges = Counter()
    for t in triangles:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            edges[tuple(sorted((a, b)))] += 1
    assert set(edges.values()) == {2}  # every edge shared by two facets: no hole
    for t in triangles:
        for x, y, z in t:
            assert abs(y) == pytest.approx(0.5 * length)
            assert math.hypot(x, z) in (pytest.approx(radius), 0.0)


def test_the_input_carries_the_scenes_materials_step_and_phases(tmp_path):
    s = scene()
    particles, drum, run, contacts = drv.read_drum(s, defaults(s))
    dt = run["rayleigh_fraction"] * drv.rayleigh_step_s(particles, contacts["particle-particle"])
    # demcal's drum_3d reports this step for the scene's defaults (dt_over_rayleigh_step 0.2).
    assert dt == pytest.approx(0.2 * math.pi * 0.0015 * math.sqrt(2500 / 1e7) / (0.1631 * 0.25 + 0.8766), rel=1e-12)
    path = tmp_path / "in.drum"
    plan = drv.write_input(str(path), particles, drum, run, contacts, dt, seed=3)
    text = path.read_text()
    assert f"youngsModulus peratomtype {2 * 1e7 * 1.25:.17g} {2 * 7.9e10 * 1.3:.17g}" in text
    assert "coefficientFriction peratomtypepair 2 0.40000000000000002 0.5 0.5 0.5" in text
    assert "coefficientRollingFriction peratomtypepair 2 0.050000000000000003 0.050000000000000003" in text
    assert "pair_style gran model hertz tangential history rolling_friction cdt" in text
    assert f"timestep {dt:.17g}" in text
    assert f"run {math.ceil(0.5 / dt)}\n" in text and "period 1\n" in text  # 60 rpm
    assert "volumefraction_region 0.16500000000000001" in text
    assert plan["first_sample_step"] == 1 + math.ceil(0.5 / dt) + math.ceil(0.7 / dt)
    seeds = [int(w) for line in text.splitlines() for k, w in enumerate(line.split())
             if k > 0 and line.split()[k - 1] in ("seed", "particletemplate/sphere", "particledistribution/discrete/numberbased")]
    assert len(seeds) == 2 + drv.SIZE_CLASSES and len(set(seeds)) == len(seeds)
    assert all(n > 10000 and all(n % d for d in range(2, int(math.isqrt(n)) + 1)) for n in seeds)
    # Another seed, another fill.
    assert drv.liggghts_seeds(4, 3) != drv.liggghts_seeds(3, 3)


def test_dumps_and_logs_are_read():
    dump = ("ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
                       "ITEM: ATOMS id x y z radius\n1 0.1 0.2 0.3 0.001\n2 0.4 0.5 0.6 0.002\n"
                       "ITEM: TIMESTEP\n20\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
                       "ITEM: ATOMS id x y z radius\n1 0.7 0.8 0.9 0.003\n")
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".dump", delete=False) as f:
        f.write(dump)
    try:
        frames = drv.read_dump_frames(f.name)
    finally:
        os.remove(f.name)
    assert [step for step, _ in frames] == [10, 20]
    assert frames[0][1]["z"] == [0.3, 0.6] and frames[1][1]["radius"] == [0.003]
    log = ("Loop time of 0.5 on 1 procs for 100 steps with 40 atoms, finish time x\n"
           "Loop time of 2.25e+01 on 1 procs for 3000 steps with 41 atoms\n")
    assert drv.loop_times(log) == [(0.5, 100, 40), (22.5, 3000, 41)]


@pytest.mark.skipif(shutil.which("liggghts") is None, reason="Debian's liggghts is not installed (make liggghts-study installs it)")
def test_a_short_drum_runs_in_liggghts(tmp_path):
    s = scene()
    s["drum"]["length_m"] = 0.012
    # A short slice for a short time: the pipeline, not a steady flow (the halves may differ by 15 degrees).
    s["run"].update(settle_time_s=0.1, measure_from_s=0.1, measure_time_s=0.2, sample_every_s=0.05,
                    steady_tolerance_deg=15)
    (tmp_path / "drum.json").write_text(json.dumps(s))
    (tmp_path / "params.json").write_text(json.dumps({"parameters": defaults(s), "seed": 2}))
    subprocess.run([sys.executable, DRIVER, "params.json", "out.json", "drum.json"], cwd=tmp_path, check=True,
                   timeout=300)
    out = json.loads((tmp_path / "out.json").read_text())
    assert out["status"] == "ok", out.get("reason")
    o = out["outputs"]
    assert 5 <= o["aor_deg"] <= 60
    assert o["samples"] == 5
    assert o["particles"] > 50 and o["particle_steps"] == pytest.approx(o["particles"] * o["steps"], rel=0.01)
