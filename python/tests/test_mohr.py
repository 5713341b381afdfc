"""Mohr circles of a biaxial series in the calibration report: the mean peaks per confinement over the ok runs, the
least-squares envelope through them, the per-run envelope outputs beside it."""
import math

from demcal_study import mohr


def write_runs(path, rows, columns):
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for row in rows:
            f.write(",".join(str(row.get(c, "")) for c in columns) + "\n")


def test_means_per_confinement_over_the_ok_runs_and_the_envelope_through_them(tmp_path):
    # sigma_1 = 20 + 3 sigma_3 exactly at the means (N_phi 3: phi 30 deg, c = 20 / (2 sqrt 3)); the two ok runs sit
    # +-1 MPa around each mean, and a failed run with wild numbers must not count.
    cols = ["run", "seed", "status", "ucs.E_GPa", "biaxial.sigma_3_peak_MPa_1", "biaxial.sigma_1_peak_MPa_1",
            "biaxial.sigma_3_peak_MPa_2", "biaxial.sigma_1_peak_MPa_2", "biaxial.c_MPa", "biaxial.phi_deg"]
    rows = [{"run": 1, "seed": s, "status": "ok", "ucs.E_GPa": 10, "biaxial.sigma_3_peak_MPa_1": 1,
             "biaxial.sigma_1_peak_MPa_1": 23 + d, "biaxial.sigma_3_peak_MPa_2": 4, "biaxial.sigma_1_peak_MPa_2": 32 - d,
             "biaxial.c_MPa": 5.5 + d, "biaxial.phi_deg": 30 + d} for s, d in ((2, 1), (3, -1))]
    rows.append({"run": 1, "seed": 4, "status": "failed", "biaxial.sigma_1_peak_MPa_1": 999})
    runs = tmp_path / "runs.csv"
    write_runs(runs, rows, cols)
    means, envelope = mohr.series_means(str(runs))
    assert list(means) == ["biaxial"]
    assert means["biaxial"] == [(1, 1.0, 23.0, 2), (2, 4.0, 32.0, 2)]
    assert envelope["biaxial"]["c_MPa"] == [6.5, 4.5] and envelope["biaxial"]["hb_m_i"] == []
    sigma_c, n_phi, c, phi = mohr.envelope_line(means["biaxial"])
    assert math.isclose(n_phi, 3.0) and math.isclose(sigma_c, 20.0)
    assert math.isclose(c, 20 / (2 * math.sqrt(3))) and math.isclose(phi, 30.0)
    lines = mohr.mohr_section(str(runs), str(tmp_path))
    assert lines[0] == "## Mohr circles of biaxial"
    assert any(line.startswith("Envelope through the mean peaks: c 5.774 MPa, phi 30 deg") for line in lines)
    assert "![Mohr circles](mohr_biaxial.png)" in lines and (tmp_path / "mohr_biaxial.png").stat().st_size > 0


def test_no_series_no_section_and_a_falling_envelope_has_no_angle(tmp_path):
    runs = tmp_path / "runs.csv"
    write_runs(runs, [{"run": 1, "seed": 2, "status": "ok", "sigma_u_MPa": 40}], ["run", "seed", "status", "sigma_u_MPa"])
    assert mohr.mohr_section(str(runs), str(tmp_path)) == []
    assert mohr.envelope_line([(1, 1.0, 30.0, 1), (2, 4.0, 25.0, 1)]) is None
    assert mohr.envelope_line([(1, 1.0, 30.0, 1)]) is None
