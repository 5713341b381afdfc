"""export: a calibrated set as PFC, YADE or LIGGGHTS input, from the scene's bindings at the solution's values, with
the conversions that follow from each program's contact law and the caveats written into the file."""
import json
import math
import os
import re
import subprocess

import pytest

from demcal_study import export
from demcal_study.errors import StudyError

PB_SCENE = {
    "scene": "ucs_rock_pb.json", "test": "ucs",
    "parameters": {"Ec_GPa": {"value": 16}, "kn_ks": {"value": 1.45}, "pb_sigma_c_MPa": {"value": 10},
                   "pb_tau_c_MPa": {"value": 30}, "mu": {"value": 0.5}},
    "contacts": {
        "particle-particle": {"model": "parallel_bond", "parameters": {
            "modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": "mu", "bond_modulus_pa": "Ec_GPa*1e9",
            "bond_kn_ks": "kn_ks", "tensile_strength_pa": "pb_sigma_c_MPa*1e6", "shear_strength_pa": "pb_tau_c_MPa*1e6"}},
        "particle-platen": {"model": "linear", "parameters": {"modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": 0}}},
}
SOLUTION = {"x": {"Ec_GPa": 20.5, "pb_sigma_c_MPa": 12.25, "mu": 0.8}}


@pytest.fixture
def peers(bin_dir):
    """Each contact model's names in the other programs, as the models declare them."""
    done = subprocess.run([os.path.join(bin_dir, "demcal-dem"), "describe", "--registries"], capture_output=True,
                          text=True, check=True)
    return json.loads(done.stdout)["contact_model_peer_names"]


def test_pfc_gets_the_bound_values_under_its_own_keywords(peers):
    text = export.export_text(PB_SCENE, SOLUTION, "pfc", peers)
    assert "import itasca as it" in text
    assert ('it.command("contact cmat default model linearpbond method deformability emod 2.05e+10 kratio 1.45 '
            'pb_deformability emod 2.05e+10 kratio 1.45 property fric 0.8 pb_ten 12250000 pb_coh 30000000 pb_fa 0 pb_rmul 1")'
            in text)
    assert "model linear method deformability emod 2.05e+10 kratio 1.45 property fric 0\")" in text


def test_pfc_gets_a_contact_bonds_strengths_as_stresses_through_cb_strength(peers):
    scene = {"scene": "ucs_rock_cb.json", "test": "ucs",
             "parameters": {"Ec_GPa": {"value": 20}, "cb_sigma_c_MPa": {"value": 40}, "cb_tau_c_MPa": {"value": 35}},
             "contacts": {"particle-particle": {"model": "contact_bond", "parameters": {
                 "modulus_pa": "Ec_GPa*1e9", "kn_ks": 1.8, "friction": 0.6, "tensile_strength_pa": "cb_sigma_c_MPa*1e6",
                 "shear_strength_pa": "cb_tau_c_MPa*1e6"}}}}
    text = export.export_text(scene, {"x": {"cb_sigma_c_MPa": 42.5}}, "pfc", peers)
    assert ('it.command("contact cmat default model linearcbond method deformability emod 2e+10 kratio 1.8 '
            'property fric 0.6")') in text
    # Stresses, which PFC multiplies by the contact area 2 min(R) t, as our contact bond does: no formula to apply.
    assert '# it.command("contact method cb_strength tensile 42500000 shear 35000000")' in text
    assert "2 min(R) t" in text


def test_yade_takes_poisson_as_ks_over_kn_and_a_friction_angle(peers):
    text = export.export_text(PB_SCENE, SOLUTION, "yade", peers)
    assert "CAUTION: our DEM is 2D" in text
    line = [l for l in text.splitlines() if l.startswith("particle_particle = ")][0]
    d = eval(line.split(" = ", 1)[1], {"dict": dict})
    assert d["kind"] == "CohFrictMat" and d["young"] == 20.5e9
    assert d["poisson"] == pytest.approx(1 / 1.45) and d["frictionAngle"] == pytest.approx(math.atan(0.8))
    assert d["normalCohesion"] == pytest.approx(12.25e6) and d["shearCohesion"] == pytest.approx(30e6)


def test_liggghts_gets_the_hertz_mindlin_poisson_ratio_of_the_stiffness_ratio(peers):
    text = export.export_text(PB_SCENE, SOLUTION, "liggghts", peers)
    nu = float([l for l in text.splitlines() if "poissonsRatio" in l][0].split()[-1])
    r = 2 * (1 - nu) / (2 - nu)  # Hertz-Mindlin's ks / kn back from nu
    assert r == pytest.approx(1 / 1.45, rel=1e-9)
    assert "LIGGGHTS-PUBLIC has no bonds" in text
    stiff = export.export_text(PB_SCENE, {"x": {"kn_ks": 1.2}}, "liggghts", peers)  # ks / kn 0.83 -> nu 0.29
    assert "poissonsRatio peratomtype 0.2857142857" in stiff
    soft = export.export_text(PB_SCENE, {"x": {"kn_ks": 3.0}}, "liggghts", peers)  # ks / kn 1/3: no Hertz-Mindlin nu
    assert "has no Hertz-Mindlin Poisson's ratio" in soft and "poissonsRatio peratomtype" not in soft


def test_an_external_scene_exports_its_own_parameters_by_name(peers):
    scene = {"scene": "yade_cpm.json", "test": "external", "parameters": {"young_GPa": {"value": 30},
                                                                          "sigmaT_MPa": {"value": 3}},
             "contacts": {}}
    text = export.export_text(scene, {"x": {"young_GPa": 31.5}}, "yade", peers)
    assert "parameters = {'sigmaT_MPa': 3, 'young_GPa': 31.5}" in text


def test_bad_requests_say_what_is_wrong(peers):
    with pytest.raises(StudyError, match="--to must be one of pfc, pfc3d, yade, liggghts"):
        export.export_text(PB_SCENE, SOLUTION, "edem", peers)
    with pytest.raises(StudyError, match="x.Ec_Pa is not a parameter of ucs_rock_pb.json"):
        export.export_text(PB_SCENE, {"x": {"Ec_Pa": 1}}, "pfc", peers)


HERTZ_LIST = {
    "scene": "rock_list.json", "test": "list",
    "parameters": {"Ec_GPa": {"value": 16}, "kn_ks": {"value": 1.45}, "mu": {"value": 0.5}, "G_Pa": {"value": 3e7}},
    "contacts": {
        "ucs": {"particle-particle": {"model": "parallel_bond", "parameters": {
            "modulus_pa": "Ec_GPa*1e9", "kn_ks": "kn_ks", "friction": "mu", "bond_modulus_pa": "Ec_GPa*1e9",
            "bond_kn_ks": "kn_ks", "tensile_strength_pa": 1e7, "shear_strength_pa": 3e7, "radius_multiplier": 0.8}}},
        "heap": {"particle-particle": {"model": "hertz_mindlin", "parameters": {
            "shear_modulus_pa": "G_Pa", "poisson": 0.3, "restitution": 0.5, "friction": "mu"}},
                 "particle-platen": {"model": "linear", "parameters": {"kn_n_m": 1e8, "ks_n_m": 5e7, "friction": 0.2}}}},
}


def test_every_exporter_takes_a_test_list_with_models_it_cannot_translate(peers):
    # A Hertz contact has no counterpart: said, not a traceback; stiffness-given springs go to PFC's kn and ks.
    pfc = export.export_text(HERTZ_LIST, {"x": {}}, "pfc", peers)
    assert "# heap.particle-particle: model hertz_mindlin has no PFC counterpart in this exporter" in pfc
    assert 'model linear property kn 100000000 ks 50000000 fric 0.2")' in pfc
    assert "pb_rmul 0.8" in pfc  # the bond radius multiplier carries over
    yade = export.export_text(HERTZ_LIST, {"x": {}}, "yade", peers)
    compile(yade, "yade.py", "exec")  # labelled roles are Python names
    assert "ucs_particle_particle = dict(" in yade
    ligggghts = export.export_text(HERTZ_LIST, {"x": {}}, "liggghts", peers)
    ids = [l.split()[1] for l in ligggghts.splitlines() if l.startswith("fix ")]
    assert len(ids) == len(set(ids)) and "youngsModulus_ucs_particle_particle" in ids  # no fix id defined twice


def test_liggghts_gets_a_hertz_contacts_youngs_modulus_from_its_shear_modulus_and_poisson_ratio(peers):
    text = export.export_text(HERTZ_LIST, {"x": {}}, "liggghts", peers)
    fixes = {l.split()[1]: l.split()[-1] for l in text.splitlines() if l.startswith("fix ")}
    assert float(fixes["youngsModulus_heap_particle_particle"]) == pytest.approx(2 * 3e7 * 1.3, rel=1e-9)
    assert float(fixes["coefficientRestitution_heap_particle_particle"]) == 0.5
    assert "peratomtypepair 1 0.5" in text


def test_no_key_of_any_model_is_dropped_silently(peers, bin_dir):
    # Every key a model takes is either written under the other program's name or said not to carry over.
    done = subprocess.run([os.path.join(bin_dir, "demcal-dem"), "describe", "--registries"], capture_output=True,
                          text=True, check=True)
    registries = json.loads(done.stdout)["contact_model_parameters"]
    assert set(peers) == set(registries)
    for dim, keys in registries.items():
        assert set(peers[dim]) == set(keys)
        for model, model_keys in keys.items():
            # Scene parameters p0, p1 ... (not the keys' names, which would then appear in the header anyway); kn_ks
            # near 0.3: no Hertz-Mindlin Poisson's ratio, which must be said too.
            scene = {"scene": "s.json", "test": "ucs" if dim == "2d" else "ucs_3d", "dimension": int(dim[0]),
                     "parameters": {f"p{i}": {"value": 0.3 + 0.01 * i} for i in range(len(model_keys))},
                     "contacts": {"particle-particle": {"model": model, "parameters": {
                         k: f"p{i}" for i, k in enumerate(model_keys)}}}}
            for to in export.TARGETS:
                if to == ("pfc3d" if dim == "2d" else "pfc"):
                    with pytest.raises(StudyError, match="use --to pfc"):
                        export.export_text(scene, {"x": {}}, to, peers)
                    continue
                text = export.export_text(scene, {"x": {}}, to, peers)
                table = peers[dim][model].get("pfc" if to == "pfc3d" else to)
                if table is None:
                    assert f"model {model} has no" in text
                    continue
                translated = {k["key"]: k["name"] for k in table["keywords"] if "key" in k}
                for key in model_keys:
                    said = re.search(rf"^# {key}\b", text, re.M)
                    written = key in translated and re.search(rf"\b{translated[key]}\b", text)
                    assert said or written, (dim, model, to, key)