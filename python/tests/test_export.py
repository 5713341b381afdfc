"""export: a calibrated set as PFC, YADE or LIGGGHTS input, from the scene's bindings at the solution's values, with
the conversions that follow from each program's contact law and the caveats written into the file."""
import math

import pytest

from demcal_study import export
from demcal_study.errors import StudyError

PB_SCENE = {
    "scene": "ucs_rock_pb.json", "test": "ucs",
    "parameters": {"Ec_GPa": {"value": 16}, "kn_ks": {"value": 1.45}, "pb_sigma_c_MPa": {"value": 10},
                   "pb_tau_c_MPa": {"value": 30}, "mu": {"value": 0.5}},
    "contacts": {
        "disk-disk": {"model": "parallel_bond", "parameters": {
            "modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": "mu", "bond_modulus_pa": "Ec_GPa*1e9",
            "bond_kn_ks": "kn_ks", "tensile_strength_pa": "pb_sigma_c_MPa*1e6", "shear_strength_pa": "pb_tau_c_MPa*1e6"}},
        "disk-platen": {"model": "linear", "parameters": {"modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": 0}}},
}
SOLUTION = {"x": {"Ec_GPa": 20.5, "pb_sigma_c_MPa": 12.25, "mu": 0.8}}


def test_pfc_gets_the_bound_values_under_its_own_keywords():
    text = export.export_text(PB_SCENE, SOLUTION, "pfc")
    assert "import itasca as it" in text
    assert ('it.command("contact cmat default model linearpbond method deformability emod 2.05e+10 kratio 1.45 '
            'pb_deformability emod 2.05e+10 kratio 1.45 property fric 0.8 pb_ten 12250000 pb_coh 30000000 pb_fa 0 pb_rmul 1")'
            in text)
    assert "model linear method deformability emod 2.05e+10 kratio 1.45 property fric 0\")" in text


def test_pfc_gets_a_contact_bonds_strengths_as_stresses_through_cb_strength():
    scene = {"scene": "ucs_rock_cb.json", "test": "ucs",
             "parameters": {"Ec_GPa": {"value": 20}, "cb_sigma_c_MPa": {"value": 40}, "cb_tau_c_MPa": {"value": 35}},
             "contacts": {"disk-disk": {"model": "contact_bond", "parameters": {
                 "modulus_pa": "Ec_GPa*1e9", "kn_ks": 1.8, "friction": 0.6, "tensile_strength_pa": "cb_sigma_c_MPa*1e6",
                 "shear_strength_pa": "cb_tau_c_MPa*1e6"}}}}
    text = export.export_text(scene, {"x": {"cb_sigma_c_MPa": 42.5}}, "pfc")
    assert ('it.command("contact cmat default model linearcbond method deformability emod 2e+10 kratio 1.8 '
            'property fric 0.6")') in text
    # Stresses, which PFC multiplies by the contact area 2 min(R) t, as our contact bond does: no formula to apply.
    assert '# it.command("contact method cb_strength tensile 42500000 shear 35000000")' in text
    assert "2 min(R) t" in text


def test_yade_takes_poisson_as_ks_over_kn_and_a_friction_angle():
    text = export.export_text(PB_SCENE, SOLUTION, "yade")
    assert "CAUTION: our DEM is 2D" in text
    line = [l for l in text.splitlines() if l.startswith("disk_disk = ")][0]
    d = eval(line.split(" = ", 1)[1], {"dict": dict})
    assert d["kind"] == "CohFrictMat" and d["young"] == 20.5e9
    assert d["poisson"] == pytest.approx(1 / 1.45) and d["frictionAngle"] == pytest.approx(math.atan(0.8))
    assert d["normalCohesion"] == pytest.approx(12.25e6) and d["shearCohesion"] == pytest.approx(30e6)


def test_liggghts_gets_the_hertz_mindlin_poisson_ratio_of_the_stiffness_ratio():
    text = export.export_text(PB_SCENE, SOLUTION, "liggghts")
    nu = float([l for l in text.splitlines() if "poissonsRatio" in l][0].split()[-1])
    r = 2 * (1 - nu) / (2 - nu)  # Hertz-Mindlin's ks / kn back from nu
    assert r == pytest.approx(1 / 1.45, rel=1e-9)
    assert "LIGGGHTS-PUBLIC has no bonds" in text
    stiff = export.export_text(PB_SCENE, {"x": {"kn_ks": 1.2}}, "liggghts")  # ks / kn 0.83 -> nu 0.29
    assert "poissonsRatio peratomtype 0.2857142857" in stiff
    soft = export.export_text(PB_SCENE, {"x": {"kn_ks": 3.0}}, "liggghts")  # ks / kn 1/3: no Hertz-Mindlin nu
    assert "has no Hertz-Mindlin Poisson's ratio" in soft and "poissonsRatio peratomtype" not in soft


def test_an_external_scene_exports_its_own_parameters_by_name():
    scene = {"scene": "yade_cpm.json", "test": "external", "parameters": {"young_GPa": {"value": 30},
                                                                          "sigmaT_MPa": {"value": 3}},
             "contacts": {}}
    text = export.export_text(scene, {"x": {"young_GPa": 31.5}}, "yade")
    assert "parameters = {'sigmaT_MPa': 3, 'young_GPa': 31.5}" in text


def test_bad_requests_say_what_is_wrong():
    with pytest.raises(StudyError, match="--to must be one of pfc, yade, liggghts"):
        export.export_text(PB_SCENE, SOLUTION, "edem")
    with pytest.raises(StudyError, match="x.Ec_Pa is not a parameter of ucs_rock_pb.json"):
        export.export_text(PB_SCENE, {"x": {"Ec_Pa": 1}}, "pfc")


HERTZ_LIST = {
    "scene": "rock_list.json", "test": "list",
    "parameters": {"Ec_GPa": {"value": 16}, "kn_ks": {"value": 1.45}, "mu": {"value": 0.5}, "G_Pa": {"value": 3e7}},
    "contacts": {
        "ucs": {"disk-disk": {"model": "parallel_bond", "parameters": {
            "modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": "mu", "bond_modulus_pa": "Ec_GPa*1e9",
            "bond_kn_ks": "kn_ks", "tensile_strength_pa": 1e7, "shear_strength_pa": 3e7, "radius_multiplier": 0.8}}},
        "heap": {"particle-particle": {"model": "hertz_mindlin", "parameters": {
            "shear_modulus_pa": "G_Pa", "poisson": 0.3, "restitution": 0.5, "friction": "mu"}},
                 "disk-platen": {"model": "linear", "parameters": {"kn_n_m": 1e8, "ks_n_m": 5e7, "friction": 0.2}}}},
}


def test_every_exporter_takes_a_test_list_with_models_it_cannot_translate():
    # A Hertz contact has no counterpart: said, not a traceback; stiffness-given springs go to PFC's kn and ks.
    pfc = export.export_text(HERTZ_LIST, {"x": {}}, "pfc")
    assert "# heap.particle-particle: model hertz_mindlin has no PFC counterpart in this exporter" in pfc
    assert 'model linear property kn 100000000 ks 50000000 property fric 0.2")' in pfc
    assert "pb_rmul 0.8" in pfc  # the bond radius multiplier carries over
    yade = export.export_text(HERTZ_LIST, {"x": {}}, "yade")
    compile(yade, "yade.py", "exec")  # labelled roles are Python names
    assert "ucs_disk_disk = dict(" in yade
    ligggghts = export.export_text(HERTZ_LIST, {"x": {}}, "liggghts")
    ids = [l.split()[1] for l in ligggghts.splitlines() if l.startswith("fix ")]
    assert len(ids) == len(set(ids)) and "m1_ucs_disk_disk" in ids  # no fix id defined twice
