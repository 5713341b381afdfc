"""A confined test's measured curve as a target: the lab's sigma_3 in the file, matched to the piece of the series'
curve run at that sigma_3, compared as sigma_1 (the DEM's deviator plus its measured sigma_3)."""
import numpy as np
import pytest

from demcal_study import curve_targets
from demcal_study.errors import Problems

BIAXIAL = {"test": "biaxial", "curve_axes": {"x": "axial strain", "y": "deviatoric stress (MPa)"},
           "curve_confinements_MPa": [1.0, 2.5, 4.0, 8.0], "outputs": {}}
UCS = {"test": "ucs", "curve_axes": {"x": "axial strain", "y": "axial stress (MPa)"}, "curve_confinements_MPa": None,
       "outputs": {}}


def write(path, rows, header):
    path.write_text(header + "\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n")
    return str(path)


def lab_rows(sigma_3, e_peak=0.004, peak_q=40.0, rows=21):
    """A lab triaxial curve: sigma_1 = sigma_3 + q, q a parabola to its peak."""
    out = []
    for e in np.linspace(0, 1.2 * e_peak, rows):
        q = peak_q * (2 * e / e_peak - (e / e_peak) ** 2) if e <= e_peak else peak_q * (1 - (e - e_peak) / e_peak)
        out.append((e, sigma_3 + q, -0.25 * e, sigma_3))
    return out


def read(tmp_path, sigma_3=2.5, description=BIAXIAL, spec_label=None):
    path = write(tmp_path / "lab.csv", lab_rows(sigma_3), "axial_strain,axial_stress_MPa,lateral_strain,confining_stress_MPa")
    problems = Problems()
    spec = f"{spec_label}:{path}" if spec_label else path
    curves = curve_targets.read_curves([spec], "0.25:1.0", problems, "--curve", "--curve-window", description=description)
    return curves, problems.messages


def test_a_confined_curve_is_matched_to_its_confinement_and_named_by_it(tmp_path):
    curves, problems = read(tmp_path, 2.5)
    assert problems == []
    c = curves[0]
    assert c["confining_stress_MPa"] == 2.5 and c["piece"] == 1
    names = [q["name"] for q in c["points"]]
    first = f"{c['points'][0]['strain']:.4g}"  # the window's first strain (a quarter of the peak strain)
    assert names[0] == f"curve_s3_2p5_MPa@{first}" and names[8] == f"curve_lateral_s3_2p5@{first}"
    # The targets are the lab's sigma_1 at the window's strains, the last at the peak.
    assert c["points"][7]["value"] == pytest.approx(max(r[1] for r in lab_rows(2.5)), rel=1e-12)


def test_a_confined_curve_in_a_test_list_names_its_test(tmp_path):
    listing = {"test": "list", "tests": [dict(UCS, label="ucs"), dict(BIAXIAL, label="biax")], "outputs": {}}
    curves, problems = read(tmp_path, 8.0, listing, spec_label="biax")
    assert problems == [] and curves[0]["piece"] == 3
    assert curves[0]["points"][0]["name"].startswith("biax.curve_s3_8_MPa@")


@pytest.mark.parametrize("sigma_3, description, message", [
    (3.0, BIAXIAL, "confining_stress_MPa 3: the scene's series runs sigma_3 of 1, 2.5, 4, 8 MPa; add 3 to its "
                   "loading.confining_stresses_MPa"),
    (2.5, UCS, "confining_stress_MPa 2.5: the test is not a confined series (its curve is axial stress (MPa) against "
               "axial strain)"),
])
def test_a_confinement_the_scene_does_not_run_is_refused(tmp_path, sigma_3, description, message):
    _, problems = read(tmp_path, sigma_3, description)
    assert len(problems) == 1 and problems[0].endswith(message), problems


def test_an_unconfined_curve_on_a_series_asks_for_its_sigma_3(tmp_path):
    path = write(tmp_path / "ucs.csv", [r[:2] for r in lab_rows(0.0)][1:], "axial_strain,axial_stress_MPa")
    problems = Problems()
    curve_targets.read_curves([path], "0.25:1.0", problems, "--curve", "--curve-window", description=BIAXIAL)
    assert problems.messages == [
        f"--curve: {path}: the test's curve is deviatoric stress (MPa) against axial strain; a measured curve is "
        "compared with an axial stress against axial strain (a uniaxial test); a confined series' curve gives its "
        "sigma_3 in a confining_stress_MPa column"]


def test_a_file_with_more_than_one_confinement_is_refused(tmp_path):
    rows = lab_rows(2.5)
    rows[-1] = rows[-1][:3] + (5.0,)
    path = write(tmp_path / "two.csv", rows, "axial_strain,axial_stress_MPa,lateral_strain,confining_stress_MPa")
    problems = Problems()
    curve_targets.read_curves([path], "0.25:1.0", problems, "--curve", "--curve-window", description=BIAXIAL)
    assert problems.messages == [f"--curve: {path}: confining_stress_MPa must be one positive sigma_3 on every line "
                                 "(one confinement per file; it spans 2.5 to 5)"]


def dem_series(stiffness_mpa, measured_sigma_3, pieces=4, rows=41):
    """A biaxial result's curve: one piece per confinement from zero strain, deviator q = k e, the servo's measured
    sigma_3 beside it, the lateral strain (a swelling specimen counts positive) 0.3 e."""
    curve = {"axial_strain": [], "stress_MPa": [], "lateral_strain": [], "confining_stress_MPa": []}
    for k in range(pieces):
        e = np.linspace(0, 0.006, rows)
        curve["axial_strain"] += e.tolist()
        curve["stress_MPa"] += (stiffness_mpa[k] * e).tolist()
        curve["lateral_strain"] += (0.3 * e).tolist()
        curve["confining_stress_MPa"] += [measured_sigma_3[k]] * rows
    return curve


def test_the_dem_value_is_the_pieces_deviator_plus_its_measured_sigma_3(tmp_path):
    curves, _ = read(tmp_path, 2.5)
    curve = dem_series([1e4, 2e4, 3e4, 4e4], [1.0, 2.51, 4.0, 8.0])
    values = curve_targets.point_values(curve, curves)
    for q in curves[0]["points"]:
        if q["kind"] == "stress":
            assert values[q["name"]] == pytest.approx(2e4 * q["strain"] + 2.51, rel=1e-12)
        else:
            assert values[q["name"]] == pytest.approx(-0.3 * q["strain"], rel=1e-12)  # compression positive
    # A run that stopped before the piece gives no value for it; the last piece reads to the curve's end.
    assert curve_targets.point_values(dem_series([1e4, 2e4], [1, 2.5], pieces=1), curves) == {}
    last, _ = read(tmp_path, 8.0)
    assert curve_targets.point_values(curve, last)[last[0]["points"][0]["name"]] == pytest.approx(
        4e4 * last[0]["points"][0]["strain"] + 8.0)


def test_a_small_step_back_within_a_piece_does_not_split_it(tmp_path):
    curves, _ = read(tmp_path, 2.5)
    curve = dem_series([1e4, 2e4, 3e4, 4e4], [1.0, 2.5, 4.0, 8.0])
    curve["axial_strain"][5] = curve["axial_strain"][4] * 0.99  # the first piece's strain steps back a little
    values = curve_targets.point_values(curve, curves)
    assert values[curves[0]["points"][0]["name"]] == pytest.approx(2e4 * curves[0]["points"][0]["strain"] + 2.5)


def test_a_plain_curve_is_stored_with_the_keys_it_always_had(tmp_path):
    # A calibration's settings hold its curves; one begun before confined and several-specimen curves existed must
    # find the same settings and resume.
    path = write(tmp_path / "ucs.csv", [r[:3] for r in lab_rows(0.0)][1:], "axial_strain,axial_stress_MPa,lateral_strain")
    problems = Problems()
    (c,) = curve_targets.read_curves([path], "0.25:1.0", problems, "--curve", "--curve-window", description=UCS)
    assert problems.messages == []
    assert set(c) == {"spec", "label", "path", "window", "peak_strain", "points"}
    assert all(set(q) == {"name", "strain", "kind", "value", "sd"} for q in c["points"])
