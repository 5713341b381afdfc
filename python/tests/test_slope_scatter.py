"""scripts/slope_scatter.py: the tangents and secants of stored UCS curves and their seed CV, against curves whose
slopes are known in closed form."""
import os
import re
import subprocess
import sys

import h5py
import numpy as np

from conftest import REPO

SCRIPT = os.path.join(REPO, "scripts", "slope_scatter.py")


def write_runs(path, curves):
    with h5py.File(path, "w") as f:
        for name, (strain, stress_mpa, lateral) in curves.items():
            g = f.create_group(f"points/{name}")
            g["curve_axial_strain"] = strain
            g["curve_stress_MPa"] = stress_mpa
            g["curve_lateral_strain"] = lateral


def rows(output):
    """{label: (E GPa, E CV %, nu, nu CV %)} from the script's table."""
    found = {}
    for line in output.splitlines():
        m = re.match(r"\s+(.+?)\s+E\s+([\d.]+) GPa \(CV\s+([\d.]+) %\)\s+nu ([\d.]+) \(CV\s+([\d.]+) %\)", line)
        if m:
            found[m.group(1)] = tuple(float(v) for v in m.groups()[1:])
    return found


def test_straight_curves_give_their_modulus_and_ratio_in_every_row_and_their_spread_as_the_cv(tmp_path):
    strain = np.linspace(0, 1e-3, 201)
    # Two specimens: E 10 and 12 GPa, nu 0.2 and 0.25 (MPa = 1e3 GPa x strain).
    write_runs(tmp_path / "runs.h5", {"run1_seed1": (strain, 1e4 * strain, 0.2 * strain),
                                      "run1_seed2": (strain, 1.2e4 * strain, 0.25 * strain)})
    done = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "runs.h5")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    table = rows(done.stdout)
    assert len(table) == 5 and "2 curves" in done.stdout
    for e, e_cv, nu, nu_cv in table.values():
        assert abs(e - 11.0) < 1e-3 and abs(nu - 0.225) < 1e-4
        # CV of (10, 12) and of (0.2, 0.25): sample SD over the mean.
        assert abs(e_cv - 100 * np.sqrt(2) / 11) < 0.05 and abs(nu_cv - 100 * 0.035355 / 0.225) < 0.05


def test_a_softening_curve_has_its_tangent_below_its_secant_at_half_the_peak(tmp_path):
    # stress = E0 (e - 1000 e^2), E0 = 10 GPa: peak at e = 5e-4; half the peak at e_h = (1 - sqrt(0.5)) / 2000,
    # where the tangent is E0 (1 - 2000 e_h) = 7.07 GPa and the secant E0 (1 - 1000 e_h) = 8.54 GPa.
    strain = np.linspace(0, 5e-4, 501)
    stress = 1e4 * (strain - 1000 * strain ** 2)
    curve = (strain, stress, 0.2 * strain)
    write_runs(tmp_path / "runs.h5", {"run1_seed1": curve, "run1_seed2": curve})
    done = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "runs.h5")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    table = rows(done.stdout)
    # The curve is sampled every 1e-6: the half-peak point is the first sample at or above half the peak, one
    # sample past e_h. A least-squares line through a parabola's points set evenly about one of them has the
    # parabola's slope there, so the tangent is exact at that sample.
    e_h = (1 - np.sqrt(0.5)) / 2000
    e_s = strain[np.argmax(stress >= 0.5 * stress.max())]
    assert e_h <= e_s < e_h + 1e-6
    assert abs(table["tangent, 1/20"][0] - 10 * (1 - 2000 * e_s)) < 1e-3
    assert abs(table["secant at half the peak"][0] - 10 * (1 - 1000 * e_s)) < 1e-3
    assert table["tangent, 1/20"][0] < 7.1 < 8.5 < table["secant at half the peak"][0]
    assert table["tangent, 1/20"][1] == 0.0 and table["secant at half the peak"][3] == 0.0
