"""Several specimens' curves in one file (a `specimen` column): each point's target is their mean with their SD
and count, and the points' correlation over the specimens (with the scalar outputs of the same specimens, when the
lab's specimen file names them) joins the lab's correlation, so the Bayesian likelihood does not count eight points
of one curve, or a peak and its curve, as independent measurements."""
import numpy as np
import pytest

from demcal_study import calibrate, curve_targets, executables
from demcal_study.errors import Problems
from test_calibrate import DESCRIPTION
from test_calibrate_input import command

UCS = dict(DESCRIPTION, curve_axes={"x": "axial strain", "y": "axial stress (MPa)"})
HEADER = "specimen,axial_strain,axial_stress_MPa,lateral_strain"
# Four specimens: stiffer ones stronger (a common factor) with their own shape (a second, independent one).
FACTORS = [(0.9, 0.02), (1.0, -0.03), (1.1, 0.01), (1.05, 0.04)]


def specimen_rows(name, scale, bend, rows=16):
    out = []
    for e in np.linspace(0, 0.0045, rows):
        q = scale * 30 * (2 * e / 0.003 - (e / 0.003) ** 2 + bend * np.sin(1000 * e))
        out.append((name, e, q, -0.25 * scale * e))
    return out


def write(path, rows, header=HEADER):
    path.write_text(header + "\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n")
    return str(path)


def lab_file(tmp_path, factors=FACTORS):
    rows = [r for k, (scale, bend) in enumerate(factors) for r in specimen_rows(f"s{k + 1}", scale, bend)]
    return write(tmp_path / "specimens.csv", rows)


def test_each_point_is_the_specimens_mean_with_their_sd_and_correlation(tmp_path):
    problems = Problems()
    (c,) = curve_targets.read_curves([lab_file(tmp_path)], "0.2:1.0", problems, "--curve", "--curve-window",
                                     description=UCS)
    assert problems.messages == []
    assert c["specimens"] == 4 and len(c["points"]) == 16
    at = [q["strain"] for q in c["points"][:8]]
    values = np.array([np.concatenate([np.interp(at, [r[1] for r in rows], [r[2] for r in rows]),
                                       np.interp(at, [r[1] for r in rows], [r[3] for r in rows])])
                       for rows in (specimen_rows(f"s{k}", s, b) for k, (s, b) in enumerate(FACTORS))])
    for q, mean, sd in zip(c["points"], values.mean(axis=0), values.std(axis=0, ddof=1)):
        assert (q["value"], q["sd"], q["n"]) == (pytest.approx(mean, rel=1e-12), pytest.approx(sd, rel=1e-12), 4)
    names = [q["name"] for q in c["points"]]
    assert list(c["by_specimen"]) == ["s1", "s2", "s3", "s4"]
    assert np.array([[c["by_specimen"][s][n] for n in names] for s in c["by_specimen"]]) == pytest.approx(values, rel=1e-12)
    # The stresses of one specimen move together: neighbouring points correlate strongly.
    assert np.corrcoef(values.T)[3][4] > 0.9
    # The window follows the mean curve's peak strain.
    mean_peak = c["peak_strain"]
    assert at[-1] == pytest.approx(mean_peak) and 0.0027 < mean_peak < 0.0033


def test_the_calibration_weighs_the_points_by_the_specimens_and_joins_their_correlation(monkeypatch, tmp_path):
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: UCS)
    lab = lab_file(tmp_path)
    config, _, _ = calibrate.checked_command(command(tmp_path, "--target", "nu=0.2+-0.02/n=4", "--strategy", "bayes",
                                                     "--curve", lab, "--curve-window", "0.2:1.0"))
    names = [n for n in config["targets"] if n.startswith("curve_")]
    assert len(names) == 16  # the lateral strains too: the specimens give their scatter
    assert all(config["target_uncertainty"][n]["n"] == 4 for n in names)
    stored = config["lab_correlation"]
    assert stored["names"] == names
    (c,) = config["curves"]
    values = np.array([[c["by_specimen"][s][n] for n in names] for s in c["by_specimen"]])
    assert np.array(stored["matrix"]) == pytest.approx(np.corrcoef(values.T), abs=1e-12)


def test_a_specimens_peak_and_its_curve_are_correlated_across_the_two_files(monkeypatch, tmp_path):
    # The lab's specimen file gives each specimen's UCS; the curve file the same specimens' curves. A specimen's
    # peak and its curve's last point (at the peak strain) move together: the likelihood must know it.
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: UCS)
    lab = lab_file(tmp_path)
    peaks = {f"s{k + 1}": max(r[2] for r in specimen_rows(f"s{k + 1}", s, b)) for k, (s, b) in enumerate(FACTORS)}
    scalars = tmp_path / "specimens_ucs.csv"
    scalars.write_text("test,output,value,specimen\n" + "".join(f",sigma_u_MPa,{v},{s}\n" for s, v in peaks.items()))
    config, _, _ = calibrate.checked_command(command(tmp_path, "--lab-specimens", str(scalars), "--strategy", "bayes",
                                                     "--curve", lab, "--curve-window", "0.2:1.0"))
    stored = config["lab_correlation"]
    assert stored["names"][0] == "sigma_u_MPa" and len(stored["names"]) == 17
    (c,) = config["curves"]
    last = [q["name"] for q in c["points"] if q["kind"] == "stress"][-1]
    expected = np.corrcoef([peaks[s] for s in c["by_specimen"]], [c["by_specimen"][s][last] for s in c["by_specimen"]])
    k = stored["names"].index(last)
    assert stored["matrix"][0][k] == pytest.approx(expected[0, 1], abs=1e-12) and stored["matrix"][0][k] > 0.9


def test_two_specimens_give_a_scatter_but_no_correlation(monkeypatch, tmp_path):
    monkeypatch.setattr(executables, "describe", lambda scene, space=None: UCS)
    lab = lab_file(tmp_path, FACTORS[:2])
    config, _, _ = calibrate.checked_command(command(tmp_path, "--target", "nu=0.2+-0.02/n=4", "--strategy", "bayes",
                                                     "--curve", lab, "--curve-window", "0.2:1.0"))
    assert "lab_correlation" not in config  # 2 specimens cannot tell a correlation
    assert config["curves"][0]["points"][0]["n"] == 2


@pytest.mark.parametrize("rows, header, message", [
    (specimen_rows("s1", 1, 0), HEADER, "one specimen gives no scatter; give at least 2 (or an sd_MPa column)"),
    ([r + (0.5,) for r in specimen_rows("s1", 1, 0) + specimen_rows("s2", 1.1, 0)], HEADER + ",sd_MPa",
     "give a specimen column or an sd_MPa column, not both (the specimens give the SD)"),
    (specimen_rows("s1", 1, 0) + [r if k != 3 else (r[0], 0.0001, r[2], r[3])
                                  for k, r in enumerate(specimen_rows("s2", 1.1, 0))], HEADER,
     "specimen s2: line 21: axial_strain 0.0001 is not above the one before (0.0006): strains must increase"),
    (specimen_rows("s1", 1, 0) + specimen_rows("s2", 1, 0), HEADER,
     "every specimen gives the same value at curve_MPa@0.0006008: no scatter to weigh it by"),
])
def test_bad_specimen_files_are_one_line_naming_the_specimen(tmp_path, rows, header, message):
    path = write(tmp_path / "bad.csv", rows, header)
    problems = Problems()
    curve_targets.read_curves([path], "0.2:1.0", problems, "--curve", "--curve-window", description=UCS)
    assert len(problems.messages) == 1 and problems.messages[0].endswith(message), problems.messages
