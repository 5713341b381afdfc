"""Lab targets with their scatter: the written form, the specimens' CSV, and the likelihood of a DEM mean against
closed forms."""
import math

import numpy as np
import pytest

from demcal_study.errors import StudyError
from demcal_study.lab_targets import LabTarget, gaussian_log_likelihood, named_as_outputs, parse_target, read_specimens


def test_written_forms():
    assert parse_target("E_GPa=69") == LabTarget("E_GPa", 69.0)
    granite = parse_target("sigma_u_MPa=200+-22")
    assert granite == LabTarget("sigma_u_MPa", 200.0, 22.0, 1)
    assert granite.standard_error == 22.0
    five = parse_target("sigma_u_MPa=200+-22/n=5")
    assert five.n == 5
    assert five.standard_error == pytest.approx(22.0 / math.sqrt(5), rel=1e-15)
    assert five.text() == "sigma_u_MPa=200+-22/n=5"
    assert parse_target("nu=0.26+-0.04").text() == "nu=0.26+-0.04"
    assert LabTarget("E_GPa", 69.0).standard_error == 0.0


@pytest.mark.parametrize("text, words", [
    ("sigma_u_MPa=200+-0", "must be a number above 0"),
    ("sigma_u_MPa=200+--3", "must be a number above 0"),
    ("sigma_u_MPa=200+-x", "must be a number above 0"),
    ("sigma_u_MPa=200+-22/n=0", "at least 1"),
    ("sigma_u_MPa=200+-22/n=2.5", "whole number"),
    ("sigma_u_MPa=abc+-22", "the mean"),
    ("sigma_u_MPa=200~22", "is not a number"),
    ("sigma_u_MPa", "is not NAME=VALUE"),
    ("=200", "is not NAME=VALUE"),
])
def test_bad_forms_name_what_is_wrong(text, words):
    message = parse_target(text)
    assert isinstance(message, str)
    assert message.startswith("--target: ")
    assert words in message


def write(tmp_path, text):
    path = tmp_path / "specimens.csv"
    path.write_text(text)
    return str(path)


def test_specimens_give_mean_sd_n_and_correlation(tmp_path):
    ucs = [190.0, 212.0, 205.0, 178.0, 215.0]
    e = [66.0, 72.0, 70.0, 63.0, 74.0]
    rows = ["specimen,test,output,value"]
    rows += [f"s{k},,sigma_u_MPa,{v}" for k, v in enumerate(ucs)]
    rows += [f"s{k},,E_GPa,{v}" for k, v in enumerate(e)]
    rows += ["b1,brazilian,sigma_t_MPa,9.1", "b2,brazilian,sigma_t_MPa,10.3"]
    targets, names, r = read_specimens(write(tmp_path, "\n".join(rows) + "\n"))
    assert names == ["sigma_u_MPa", "E_GPa", "brazilian.sigma_t_MPa"]
    assert targets["sigma_u_MPa"].mean == pytest.approx(np.mean(ucs), rel=1e-15)
    assert targets["sigma_u_MPa"].sd == pytest.approx(np.std(ucs, ddof=1), rel=1e-15)
    assert targets["sigma_u_MPa"].n == 5
    assert targets["brazilian.sigma_t_MPa"].n == 2
    assert r[0, 1] == pytest.approx(np.corrcoef(ucs, e)[0, 1], rel=1e-12)
    assert r[0, 1] > 0.9
    assert r[0, 2] == 0.0  # no specimen measured both
    assert np.allclose(np.diag(r), 1.0)


def test_specimens_without_ids_are_independent(tmp_path):
    _, _, r = read_specimens(write(tmp_path, "test,output,value\n,nu,0.25\n,nu,0.27\n,E_GPa,60\n,E_GPa,64\n"))
    assert np.array_equal(r, np.eye(2))


@pytest.mark.parametrize("text, words", [
    ("output,value\nnu,0.2\n", "lacks test"),
    ("test,output,value\n,nu,0.2\n,nu,x\n", "line 3: value"),
    ("test,output,value\n,nu,0.2\n", "one specimen gives no scatter"),
    ("test,output,value\n,nu,0.2\n,nu,0.2\n", "no scatter"),
    ("test,output,value\n,,0.2\n", "line 2: output is empty"),
    ("specimen,test,output,value\na,,nu,0.2\na,,nu,0.3\n", "specimen a has nu twice"),
    ("test,output,value\n", "no specimens"),
])
def test_bad_specimen_files_name_the_file_and_line(tmp_path, text, words):
    path = write(tmp_path, text)
    with pytest.raises(StudyError) as caught:
        read_specimens(path)
    assert str(caught.value).startswith(path)
    assert words in str(caught.value)


def test_a_test_column_names_an_output_only_where_the_scene_prefixes_it(tmp_path):
    # ucs.E_GPa stays prefixed where the scene list gives E_GPa in two tests; brazilian.sigma_t_MPa is sigma_t_MPa.
    path = tmp_path / "lab.csv"
    path.write_text("test,output,value,specimen\nucs,E_GPa,60,a\nucs,E_GPa,70,b\nbrazilian,sigma_t_MPa,9,a\n"
                    "brazilian,sigma_t_MPa,11,b\n")
    by_name, names, r = named_as_outputs(read_specimens(str(path)), {"ucs.E_GPa", "biaxial.E_GPa", "sigma_t_MPa"})
    assert names == ["ucs.E_GPa", "sigma_t_MPa"] and set(by_name) == set(names)
    assert by_name["sigma_t_MPa"].mean == 10 and by_name["sigma_t_MPa"].n == 2
    assert by_name["sigma_t_MPa"].sd == pytest.approx(math.sqrt(2), rel=1e-12)


def test_one_target_likelihood_is_the_normal_density_of_the_summed_variances():
    target = LabTarget("sigma_u_MPa", 200.0, 22.0, 5)
    dem_mean, dem_se = 190.0, 3.0
    variance = 22.0 ** 2 / 5 + 3.0 ** 2
    expected = -0.5 * ((dem_mean - 200.0) ** 2 / variance + math.log(2 * math.pi * variance))
    assert gaussian_log_likelihood([target], [dem_mean], [dem_se]) == pytest.approx(expected, rel=1e-13)


def test_two_correlated_targets_match_the_bivariate_closed_form():
    a, b = LabTarget("sigma_u_MPa", 200.0, 22.0, 4), LabTarget("E_GPa", 69.0, 5.8, 4)
    rho = 0.6
    dem_means, dem_se = [210.0, 66.0], [4.0, 0.5]
    s1 = math.sqrt(a.standard_error ** 2 + dem_se[0] ** 2)
    s2 = math.sqrt(b.standard_error ** 2 + dem_se[1] ** 2)
    c = rho * a.standard_error * b.standard_error / (s1 * s2)  # only the lab's errors are correlated
    x, y = (210.0 - 200.0) / s1, (66.0 - 69.0) / s2
    expected = (-math.log(2 * math.pi * s1 * s2 * math.sqrt(1 - c * c))
                - (x * x - 2 * c * x * y + y * y) / (2 * (1 - c * c)))
    r = np.array([[1.0, rho], [rho, 1.0]])
    assert gaussian_log_likelihood([a, b], dem_means, dem_se, lab_correlation=r) == pytest.approx(expected, rel=1e-12)


def test_a_bare_number_needs_the_dem_scatter():
    with pytest.raises(ValueError, match="positive definite"):
        gaussian_log_likelihood([LabTarget("E_GPa", 69.0)], [68.0], [0.0])
    assert math.isfinite(gaussian_log_likelihood([LabTarget("E_GPa", 69.0)], [68.0], [0.4]))
