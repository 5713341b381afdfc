#!/usr/bin/python3
"""Writes the corpus of bad inputs (tests/bad_inputs/<reader>/...) and its manifest cases.json.

    /usr/bin/python3 tests/bad_inputs/make_corpus.py BIN_DIR SRC_DIR

Every file is a valid input broken in one way: the valid scene, space, study and solution come from tests/data/,
the models from demcal-fit on data/literature/su2021_CCD2_sigma_u.csv (so BIN_DIR is needed), the HDF5 files are
written with h5py. The corpus is committed; rerun this only to change it (the output is deterministic, except the
bytes HDF5 writes). run_bad_inputs.py runs the cases.
"""
import copy
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

BIN, SRC = sys.argv[1], sys.argv[2]
HERE = "tests/bad_inputs"  # paths in the manifest are relative to SRC_DIR, as the runner runs from there
CASES = []


def path(reader, name):
    return f"{HERE}/{reader}/{name}"


def write(reader, name, content):
    """content: bytes, str, or a JSON value (dumped with indent 1). Returns the path relative to SRC."""
    p = path(reader, name)
    os.makedirs(os.path.join(SRC, os.path.dirname(p)), exist_ok=True)
    if not isinstance(content, (bytes, str)):
        content = json.dumps(content, indent=1) + "\n"
    with open(os.path.join(SRC, p), "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())
    return p


def garbage(n, seed):
    """n deterministic pseudo-random bytes (NUL, 0xff and control bytes included)."""
    out = b""
    block = seed.encode()
    while len(out) < n:
        block = hashlib.sha256(block).digest()
        out += block
    return out[:n]


def case(id, command, file, message=None, note=None, lines=None):
    c = {"id": id, "command": command, "file": file}
    if message:
        c["message"] = message
    if note:
        c["note"] = note
    if lines:
        c["lines"] = lines  # a command that reports several problems at once, one line each
    CASES.append(c)


def load(p):
    with open(os.path.join(SRC, p)) as f:
        return json.load(f)


def edited(base, change):
    d = copy.deepcopy(base)
    change(d)
    return d


def directory(name):
    """A directory named like a file (git keeps it through a .gitkeep)."""
    p = f"{HERE}/dir/{name}"
    os.makedirs(os.path.join(SRC, p), exist_ok=True)
    open(os.path.join(SRC, p, ".gitkeep"), "w").close()
    return p


def missing(reader, name):
    p = path(reader, name)
    assert not os.path.exists(os.path.join(SRC, p)), p
    return p


# ---------------------------------------------------------------- scene JSON (demcal-dem describe / run)
def describe(f):
    return ["{bin}/demcal-dem", "describe", "--scene", f]


def run(f):
    return ["{bin}/demcal-dem", "run", "--scene", f, "--quiet", "--cache", "{tmp}/cache"]


scene = load("tests/data/ucs_small.json")
scene_text = json.dumps(scene, indent=1)
S = "scene"
case("scene/empty", describe(write(S, "empty.json", b"")), path(S, "empty.json"), "not valid JSON")
case("scene/binary", run(write(S, "binary.json", garbage(512, "scene"))), path(S, "binary.json"), "not valid JSON")
case("scene/truncated", describe(write(S, "truncated.json", scene_text[:400])), path(S, "truncated.json"),
     "not valid JSON")
case("scene/top_level_array", describe(write(S, "top_level_array.json", [scene])), path(S, "top_level_array.json"),
     "JSON object")
case("scene/name_number", describe(write(S, "name_number.json", edited(scene, lambda d: d.update(name=5)))),
     path(S, "name_number.json"), "name")
case("scene/parameter_not_object",
     describe(write(S, "parameter_not_object.json", edited(scene, lambda d: d["parameters"].update(Ec_GPa=16)))),
     path(S, "parameter_not_object.json"), "Ec_GPa")
case("scene/number_overflow",
     describe(write(S, "number_overflow.json", scene_text.replace('"porosity": 0.16', '"porosity": 1e999'))),
     path(S, "number_overflow.json"))
case("scene/nan_token", run(write(S, "nan_token.json", scene_text.replace('"porosity": 0.16', '"porosity": NaN'))),
     path(S, "nan_token.json"), "not valid JSON")
case("scene/unknown_field",
     describe(write(S, "unknown_field.json", edited(scene, lambda d: d.update(loadng=d.pop("loading"))))),
     path(S, "unknown_field.json"), "loadng")
case("scene/specimen_field_typo",
     run(write(S, "specimen_field_typo.json",
               edited(scene, lambda d: d["specimen"].update(widht_m=d["specimen"].pop("width_m"))))),
     path(S, "specimen_field_typo.json"), "widht_m")
case("scene/missing_test", describe(write(S, "missing_test.json", edited(scene, lambda d: d.pop("test")))),
     path(S, "missing_test.json"), "test")
case("scene/unknown_test", run(write(S, "unknown_test.json", edited(scene, lambda d: d.update(test="triaxial")))),
     path(S, "unknown_test.json"), "triaxial")
case("scene/contacts_array", describe(write(S, "contacts_array.json", edited(scene, lambda d: d.update(contacts=[])))),
     path(S, "contacts_array.json"), "contacts")
case("scene/missing_contact_role",
     run(write(S, "missing_contact_role.json", edited(scene, lambda d: d["contacts"].pop("particle-platen")))),
     path(S, "missing_contact_role.json"), "particle-platen")
case("scene/unknown_contact_model",
     describe(write(S, "unknown_contact_model.json",
                    edited(scene, lambda d: d["contacts"]["particle-particle"].update(model="hertz")))),
     path(S, "unknown_contact_model.json"), "hertz")
case("scene/expression_typo",
     run(write(S, "expression_typo.json",
               edited(scene, lambda d: d["contacts"]["particle-particle"]["parameters"].update(modulus_pa="Ec_GPA*1e9")))),
     path(S, "expression_typo.json"), "Ec_GPA")
case("scene/negative_friction",
     describe(write(S, "negative_friction.json",
                    edited(scene, lambda d: d["contacts"]["particle-particle"]["parameters"].update(friction=-1)))),
     path(S, "negative_friction.json"), "friction")
case("scene/parameter_value_string",
     describe(write(S, "parameter_value_string.json", edited(scene, lambda d: d["parameters"]["Ec_GPa"].update(value="16")))),
     path(S, "parameter_value_string.json"), "value")
case("scene/parameter_unknown_unit",
     describe(write(S, "parameter_unknown_unit.json", edited(scene, lambda d: d["parameters"]["Ec_GPa"].update(unit="psi")))),
     path(S, "parameter_unknown_unit.json"), "psi")
case("scene/parameter_outside_bounds",
     run(write(S, "parameter_outside_bounds.json", edited(scene, lambda d: d["parameters"]["Ec_GPa"].update(value=600)))),
     path(S, "parameter_outside_bounds.json"), "Ec_GPa")
case("scene/porosity_out_of_range",
     run(write(S, "porosity_out_of_range.json", edited(scene, lambda d: d["specimen"].update(porosity=0.9)))),
     path(S, "porosity_out_of_range.json"), "porosity")
case("scene/negative_width",
     describe(write(S, "negative_width.json", edited(scene, lambda d: d["specimen"].update(width_m=-0.01)))),
     path(S, "negative_width.json"), "width_m")
case("scene/huge_specimen",
     describe(write(S, "huge_specimen.json", edited(scene, lambda d: d["specimen"].update(width_m=1e308, height_m=1e308)))),
     path(S, "huge_specimen.json"))
case("scene/negative_velocity",
     run(write(S, "negative_velocity.json", edited(scene, lambda d: d["loading"].update(platen_velocity_m_s=-0.05)))),
     path(S, "negative_velocity.json"), "platen_velocity_m_s")
case("scene/huge_velocity",
     run(write(S, "huge_velocity.json", edited(scene, lambda d: d["loading"].update(platen_velocity_m_s=1e308)))),
     path(S, "huge_velocity.json"), "platen_velocity_m_s")
case("scene/negative_max_wall",
     run(write(S, "negative_max_wall.json", edited(scene, lambda d: d["loading"].update(max_wall_s=-1)))),
     path(S, "negative_max_wall.json"), "max_wall_s")
case("scene/aggregates_string", describe(write(S, "aggregates_string.json", edited(scene, lambda d: d.update(aggregates="yes")))),
     path(S, "aggregates_string.json"), "aggregates")
case("scene/aggregate_sides_fraction",
     describe(write(S, "aggregate_sides_fraction.json", edited(scene, lambda d: d.update(aggregates={"sides": [4.5, 6]})))),
     path(S, "aggregate_sides_fraction.json"), "sides")
case("scene/aggregate_bins_huge",
     describe(write(S, "aggregate_bins_huge.json", edited(scene, lambda d: d.update(aggregates={"bins": 1e308})))),
     path(S, "aggregate_bins_huge.json"), "bins")
# "extends": relative to the extending file.
case("scene/extends_missing_base",
     describe(write(S, "extends_missing_base.json", {"extends": "no_such_base.json", "name": "variant"})),
     path(S, "extends_missing_base.json"))
write(S, "extends_cycle_b.json", {"extends": "extends_cycle_a.json"})
case("scene/extends_cycle", describe(write(S, "extends_cycle_a.json", {"extends": "extends_cycle_b.json"})),
     path(S, "extends_cycle_a.json"), "extends")
write(S, "extends_cycle3_b.json", {"extends": "extends_cycle3_c.json"})
write(S, "extends_cycle3_c.json", {"extends": "extends_cycle3_a.json"})
case("scene/extends_cycle_of_three", describe(write(S, "extends_cycle3_a.json", {"extends": "extends_cycle3_b.json"})),
     path(S, "extends_cycle3_a.json"), "extends")
case("scene/extends_number", describe(write(S, "extends_number.json", {"extends": 5})), path(S, "extends_number.json"),
     "extends")
case("scene/extends_directory", describe(write(S, "extends_directory.json", {"extends": "../dir/as_file.json"})),
     path(S, "extends_directory.json"))
case("scene/extends_bad_patch",
     run(write(S, "extends_bad_patch.json", {"extends": "../../data/ucs_small.json", "loading": {"strain_limit": 0.9}})),
     path(S, "extends_bad_patch.json"), "strain_limit")
case("scene/does_not_exist", describe(missing(S, "does_not_exist.json")), path(S, "does_not_exist.json"), "cannot open")
case("scene/directory", describe(directory("as_file.json")), f"{HERE}/dir/as_file.json")
# 3D scenes: each test checks its contact models against its own engine's registry.
scene3d = load("tests/data/ucs_small_3d.json")
case("scene/2d_three_d_only_model",
     describe(write(S, "2d_three_d_only_model.json",
                    edited(scene, lambda d: d["contacts"]["particle-particle"].update(model="sjkr")))),
     path(S, "2d_three_d_only_model.json"), "sjkr")
case("scene/3d_bond_without_its_modulus",
     describe(write(S, "3d_bond_without_its_modulus.json",
                    edited(scene3d, lambda d: d["contacts"]["particle-particle"]["parameters"].pop("bond_modulus_pa")))),
     path(S, "3d_bond_without_its_modulus.json"), "bond_modulus_pa")
case("scene/3d_box_for_a_cylinder_test",
     describe(write(S, "3d_box_for_a_cylinder_test.json",
                    edited(scene3d, lambda d: d["specimen"].update(shape="box", width_m=0.01, depth_m=0.01)
                           or d["specimen"].pop("diameter_m")))),
     path(S, "3d_box_for_a_cylinder_test.json"), "shape")
case("scene/3d_negative_diameter",
     describe(write(S, "3d_negative_diameter.json", edited(scene3d, lambda d: d["specimen"].update(diameter_m=-0.01)))),
     path(S, "3d_negative_diameter.json"), "diameter_m")
tension3d = load("tests/data/tension_small_3d.json")
tension3d["extends"] = "../../data/ucs_small_3d.json"
case("scene/3d_tension_grip_of_no_length",
     describe(write(S, "3d_tension_grip_of_no_length.json",
                    edited(tension3d, lambda d: d.update(grips={"length_m": 0})))),
     path(S, "3d_tension_grip_of_no_length.json"), "grips.length_m")
triaxial3d = load("tests/data/triaxial_small_3d.json")
triaxial3d["extends"] = "../../data/ucs_small_3d.json"
case("scene/3d_confining_stress_zero",
     describe(write(S, "3d_confining_stress_zero.json",
                    edited(triaxial3d, lambda d: d["loading"].update(confining_stresses_MPa=[0, 4])))),
     path(S, "3d_confining_stress_zero.json"), "confining_stresses_MPa")
case("scene/3d_porosity_out_of_range",
     describe(write(S, "3d_porosity_out_of_range.json", edited(scene3d, lambda d: d["specimen"].update(porosity=0.9)))),
     path(S, "3d_porosity_out_of_range.json"), "porosity")
case("scene/3d_locked_in_stress_negative",
     describe(write(S, "3d_locked_in_stress_negative.json",
                    edited(scene3d, lambda d: d["specimen"].update(locked_in_stress_pa=-1e5)))),
     path(S, "3d_locked_in_stress_negative.json"), "locked_in_stress_pa")
fj3d = load("data/scenes/ucs_rock_fj_3d.json")
fj3d["specimen"] = scene3d["specimen"]
case("scene/3d_locked_in_stress_with_flat_joints",
     describe(write(S, "3d_locked_in_stress_with_flat_joints.json",
                    edited(fj3d, lambda d: d["specimen"].update(locked_in_stress_pa=1e5)))),
     path(S, "3d_locked_in_stress_with_flat_joints.json"), "locked_in_stress_pa")

heap3d = load("tests/invariants/scenes/heap_small_3d.json")
case("scene/3d_heap_negative_surface_energy",
     describe(write(S, "3d_heap_negative_surface_energy.json",
                    edited(heap3d, lambda d: d["parameters"]["w_N_m"].update(value=-0.1, low=-1)))),
     path(S, "3d_heap_negative_surface_energy.json"), "work_of_adhesion_j_m2")
case("scene/3d_heap_restitution_above_one",
     describe(write(S, "3d_heap_restitution_above_one.json",
                    edited(heap3d, lambda d: d["parameters"]["e"].update(value=1.2, high=2)))),
     path(S, "3d_heap_restitution_above_one.json"), "restitution")
case("scene/3d_heap_fill_does_not_fit",
     run(write(S, "3d_heap_fill_does_not_fit.json",
               edited(heap3d, lambda d: d["funnel"].update(solids_fraction=0.35, fill_height_m=0.004)))),
     path(S, "3d_heap_fill_does_not_fit.json"), "does not fit its vessel")

drum3d = load("tests/invariants/scenes/drum_small_3d.json")
case("scene/3d_drum_centrifuges",
     describe(write(S, "3d_drum_centrifuges.json", edited(drum3d, lambda d: d["drum"].update(speed_rpm=300)))),
     path(S, "3d_drum_centrifuges.json"), "centrifuges the powder")

baffle3d = load("tests/invariants/scenes/baffle_small_3d.json")
case("scene/3d_baffle_does_not_rise",
     describe(write(S, "3d_baffle_does_not_rise.json", edited(baffle3d, lambda d: d["baffle"].update(lift_speed_m_s=0)))),
     path(S, "3d_baffle_does_not_rise.json"), "baffle.lift_speed_m_s must be positive")
case("scene/3d_baffle_fill_does_not_fit",
     run(write(S, "3d_baffle_fill_does_not_fit.json",
               edited(baffle3d, lambda d: d["box"].update(solids_fraction=0.35, fill_height_m=0.007)))),
     path(S, "3d_baffle_fill_does_not_fit.json"), "does not fit its vessel")

# The slope: patches of the small slope (tests/data/slope_small.json), read from this folder.
def slope(name, patch):
    d = {"extends": "../../data/slope_small.json"}
    d.update(patch)
    return write(S, name, d)


case("scene/slope_profile_crosses_itself",
     describe(slope("slope_profile_crosses_itself.json",
                    {"slope": {"bedrock": {"surface": [[0, 40], [60, 20], [50, 25], [120, 20]]}}})),
     path(S, "slope_profile_crosses_itself.json"), "slope.bedrock.surface[2]: x 50 m does not exceed")
case("scene/slope_monitor_outside_the_model",
     describe(slope("slope_monitor_outside_the_model.json",
                    {"monitors": {"points": [{"label": "A", "x_m": 100, "y_m": 35}]}})),
     path(S, "slope_monitor_outside_the_model.json"), "monitors.points[0]: (100, 35 m) lies outside the model")
case("scene/slope_input_not_on_an_edge",
     describe(slope("slope_input_not_on_an_edge.json", {"boundaries": {"top": {"type": "input", "xi": 1, "eta": 1}}})),
     path(S, "slope_input_not_on_an_edge.json"), "boundaries.top: a slope's top is its free surface")
write(S, "slope_record_not_numeric.dat", "# in g\n 0.01 0.02 0.03\n 0.04 O.05 0.06\n")
case("scene/slope_record_not_numeric",
     describe(slope("slope_record_not_numeric.json",
                    {"pulse": None, "earthquake": {"record_file": "slope_record_not_numeric.dat", "time_step_s": 0.02}})),
     path(S, "slope_record_not_numeric.dat"), "slope_record_not_numeric.dat: line 3: \"O.05\" is not a number")
write(S, "slope_record_uneven_step.dat", "0.00 0.01\n0.02 0.02\n0.04 0.03\n0.05 0.01\n")
case("scene/slope_record_uneven_step",
     describe(slope("slope_record_uneven_step.json",
                    {"pulse": None, "earthquake": {"record_file": "slope_record_uneven_step.dat", "format": "time_value"}})),
     path(S, "slope_record_uneven_step.dat"), "line 4: uneven time step")

# ---------------------------------------------------------------- parameter space JSON (demcal-doe, describe --space)
def doe(f):
    return ["{bin}/demcal-doe", "ccd", "--space", f, "--out", "{tmp}/design.csv"]


def in_scene(f):
    return ["{bin}/demcal-dem", "describe", "--scene", "data/scenes/ucs_rock_pb.json", "--space", f]


space = load("tests/data/space_small.json")
space_text = json.dumps(space, indent=1)
P = "space"


def space_case(name, command, content, message=None):
    case(f"space/{name.rsplit('.', 1)[0]}", command(write(P, name, content)), path(P, name), message)


def p0(**fields):
    return edited(space, lambda d: d["parameters"][0].update(fields))


space_case("empty.json", doe, b"", "not valid JSON")
space_case("binary.json", doe, garbage(300, "space"), "not valid JSON")
space_case("truncated.json", in_scene, space_text[:90], "not valid JSON")
space_case("top_level_string.json", doe, '"pb_sigma_c_MPa"\n', "JSON object")
space_case("parameters_object.json", doe, edited(space, lambda d: d.update(parameters={"pb_sigma_c_MPa": [8, 16]})),
           "parameters")
space_case("name_number.json", doe, p0(name=5), "name")
space_case("low_string.json", in_scene, p0(low="8"), "low")
space_case("high_overflow.json", doe, space_text.replace('"high": 16', '"high": 1e999'))
space_case("high_nan.json", doe, space_text.replace('"high": 16', '"high": NaN'), "not valid JSON")
space_case("huge_range.json", doe, p0(low=-1e308, high=1e308), "pb_sigma_c_MPa")
space_case("field_typo.json", doe, edited(space, lambda d: d["parameters"][0].update(hihg=d["parameters"][0].pop("high"))),
           "hihg")
space_case("missing_high.json", in_scene, edited(space, lambda d: d["parameters"][0].pop("high")), "high")
space_case("low_above_high.json", doe, p0(low=20), "low")
space_case("level_outside.json", doe, p0(levels=[8, 20]), "levels")
space_case("log_scale_string.json", doe, p0(log_scale="yes"), "log_scale")
space_case("log_scale_zero_low.json", in_scene, p0(log_scale=True, low=0), "log_scale")
space_case("duplicate_name.json", doe, edited(space, lambda d: d["parameters"][1].update(name="pb_sigma_c_MPa")),
           "twice")
space_case("no_parameters.json", doe, edited(space, lambda d: d.update(parameters=[])), "parameters")
space_case("fixed_string.json", doe, edited(space, lambda d: d.update(fixed={"Ec_GPa": "16"})), "Ec_GPa")
space_case("tied_unknown_source.json", in_scene,
           edited(space, lambda d: d.update(tied=[{"name": "kn_ks", "source": "Ec_GP"}])), "Ec_GP")
space_case("unknown_parameter.json", in_scene, p0(name="pb_sigma_MPa"), "pb_sigma_MPa")
space_case("outside_scene_bounds.json", in_scene, p0(high=2000), "pb_sigma_c_MPa")
space_case("negative_low.json", in_scene, p0(low=-5), "pb_sigma_c_MPa")
space_case("unit_disagrees.json", in_scene, p0(unit="GPa"), "unit")
space_case("fixed_outside_scene.json", in_scene, edited(space, lambda d: d.update(fixed={"Ec_GPa": 900})), "Ec_GPa")
case("space/does_not_exist", doe(missing(P, "does_not_exist.json")), path(P, "does_not_exist.json"), "cannot open")
case("space/directory", doe(f"{HERE}/dir/as_file.json"), f"{HERE}/dir/as_file.json")

# ---------------------------------------------------------------- design CSV / HDF5 (demcal-dem batch)
def batch(f):
    return ["{bin}/demcal-dem", "batch", "--scene", "tests/data/ucs_small.json", "--design", f,
            "--out", "{tmp}/responses.h5", "--quiet", "--cache", "{tmp}/cache"]


D = "design"
HEADER = "run,pb_sigma_c_MPa,pb_tau_c_MPa\n"


def design_case(name, content, message=None, note=None):
    case(f"design/{name.replace('.', '_')}", batch(write(D, name, content)), path(D, name), message, note)


design_case("empty.csv", b"", "empty")
design_case("blank_lines.csv", "\n  \n\t\n", "empty")
design_case("header_only.csv", HEADER, note="no design point: nothing to run")
design_case("unknown_column.csv", "run,pb_sigma_MPa,pb_tau_c_MPa\n1,10,30\n", "pb_sigma_MPa")
design_case("no_parameter_column.csv", "run,blank_1\n1,2\n", "no column")
design_case("non_numeric.csv", HEADER + "1,ten,30\n", "ten")
design_case("nan_cell.csv", HEADER + "1,nan,30\n", "pb_sigma_c_MPa")
design_case("inf_cell.csv", HEADER + "1,10,inf\n", "pb_tau_c_MPa")
design_case("empty_cell.csv", HEADER + "1,,30\n", "pb_sigma_c_MPa")
# A finite value outside the scene's bounds is not a bad file: that point is recorded as failed with its
# reason and the batch goes on (tests/dem/test_batch.cpp, ABadDesignPointIsRecordedAsFailed...).
design_case("ragged.csv", HEADER + "1,10,30\n2,12\n", "fields")
design_case("binary.csv", garbage(700, "design csv"))
# A spreadsheet's "Unicode text" (UTF-16); a UTF-8 byte-order mark and ';' with decimal commas are read
# (tests/core/test_table.cpp).
design_case("utf16.csv", (HEADER + "1,10,30\n").encode("utf-16"), "UTF-16")
design_case("duplicate_run.csv", HEADER + "1,10,30\n1,12,30\n", "run", note="two points would share run1_seed1.json")
design_case("run_not_integer.csv", HEADER + "1.5,10,30\n", "1.5")
design_case("run_overflow.csv", HEADER + "99999999999,10,30\n", "99999999999")
design_case("duplicate_column.csv", "run,pb_sigma_c_MPa,pb_sigma_c_MPa\n1,10,12\n", "twice")
case("design/does_not_exist_csv", batch(missing(D, "does_not_exist.csv")), path(D, "does_not_exist.csv"))
case("design/directory_csv", batch(directory("as_file.csv")), f"{HERE}/dir/as_file.csv")
# Several problems at once: a circumscribed CCD whose axial points make five parameters negative names each on its
# own line, then the fix (1 + 5 + 1 lines).
case("design/ccd_leaves_the_physical_range", ["{bin}/demcal-doe", "ccd", "--space", "data/spaces/su2021_bbd_E.json",
                                              "--out", "{tmp}/design.csv"],
     "data/spaces/su2021_bbd_E.json", "--type inscribed", lines=7)


def h5(name, build):
    p = path(D, name)
    os.makedirs(os.path.join(SRC, os.path.dirname(p)), exist_ok=True)
    with h5py.File(os.path.join(SRC, p), "w") as f:
        build(f)
    return p


def good_design(f, runs=(1,), sigma=(10.0,), tau=(30.0,)):
    g = f.create_group("design")
    g.create_dataset("run", data=np.array(runs, dtype=np.int64))
    g.create_dataset("pb_sigma_c_MPa", data=np.array(sigma, dtype=np.float64))
    g.create_dataset("pb_tau_c_MPa", data=np.array(tau, dtype=np.float64))
    g.attrs["columns"] = np.bytes_("pb_sigma_c_MPa\npb_tau_c_MPa")
    return g


def h5_case(name, build, message=None, note=None):
    case(f"design/{name.replace('.', '_')}", batch(h5(name, build)), path(D, name), message, note)


h5_case("no_design_group.h5", lambda f: f.create_group("points").create_dataset("x", data=[1.0]), "/design")
h5_case("design_is_dataset.h5", lambda f: f.create_dataset("design", data=np.zeros((1, 2))), "design")
h5_case("column_missing.h5", lambda f: good_design(f).attrs.modify("columns", np.bytes_("pb_sigma_c_MPa\npb_tau_c")),
        "pb_tau_c")


def column_2d(f):
    g = good_design(f)
    del g["pb_tau_c_MPa"]
    g.create_dataset("pb_tau_c_MPa", data=np.full((1, 2), 30.0))


h5_case("column_2d.h5", column_2d, "pb_tau_c_MPa")


def column_strings(f):
    g = good_design(f)
    del g["pb_tau_c_MPa"]
    g.create_dataset("pb_tau_c_MPa", data=np.array([b"thirty"]))


h5_case("column_strings.h5", column_strings, "pb_tau_c_MPa")
def columns_number(f):
    g = good_design(f)
    del g.attrs["columns"]
    g.attrs["columns"] = 7


h5_case("columns_attribute_number.h5", columns_number, "columns")
h5_case("ragged_columns.h5", lambda f: good_design(f, runs=(1, 2), sigma=(10.0, 12.0), tau=(30.0,)), "pb_tau_c_MPa")
h5_case("nan_value.h5", lambda f: good_design(f, sigma=(float("nan"),)), "pb_sigma_c_MPa")
h5_case("zero_rows.h5", lambda f: good_design(f, runs=(), sigma=(), tau=()), note="no design point: nothing to run")


def run_float(f):
    g = good_design(f)
    del g["run"]
    g.create_dataset("run", data=np.array([1.5]))


h5_case("run_float.h5", run_float, "run", note="run ids 1.5: HDF5 converts them to 1 silently")

valid_h5 = h5("valid_design.h5.tmp", good_design)
with open(os.path.join(SRC, valid_h5), "rb") as f:
    valid_bytes = f.read()
os.remove(os.path.join(SRC, valid_h5))
design_case("truncated.h5", valid_bytes[: len(valid_bytes) // 2])
design_case("empty.h5", b"")
design_case("not_hdf5.h5", garbage(2048, "design h5"))
design_case("corrupt_signature.h5", b"\x89HDX" + valid_bytes[4:])
design_case("corrupt_body.h5", valid_bytes[:96] + garbage(len(valid_bytes) - 96, "design h5 body"))
case("design/does_not_exist_h5", batch(missing(D, "does_not_exist.h5")), path(D, "does_not_exist.h5"))
case("design/directory_h5", batch(directory("as_file.h5")), f"{HERE}/dir/as_file.h5")

# ---------------------------------------------------------------- data CSV (demcal-fit, demcal-analyze)
def fit(f):
    return ["{bin}/demcal-fit", "quadratic", "--data", f, "--x", "pb_sigma_c_MPa,pb_tau_c_MPa", "--y", "sigma_u_MPa",
            "--out", "{tmp}/model.json", "--quiet"]


def anova(f):
    return ["{bin}/demcal-analyze", "anova", "--data", f, "--factors", "Ec_GPa,kn_ks,pb_sigma_c_MPa,pb_tau_c_MPa",
            "--responses", "sigma_u_MPa"]


with open(os.path.join(SRC, "data/literature/su2021_CCD2_sigma_u.csv")) as f:
    ccd_lines = f.read().splitlines()
with open(os.path.join(SRC, "data/literature/su2021_L64_orthogonal.csv")) as f:
    l64_lines = f.read().splitlines()
ccd = "\n".join(ccd_lines) + "\n"
l64 = "\n".join(l64_lines) + "\n"
A = "data"


def data_case(name, command, content, message=None, note=None):
    case(f"data/{name.rsplit('.', 1)[0]}", command(write(A, name, content)), path(A, name), message, note)


def l64_cell(row, column, value):
    """The L64 table with one cell replaced (row 1 = first data row)."""
    lines = list(l64_lines)
    cells = lines[row].split(",")
    cells[lines[0].split(",").index(column)] = value
    lines[row] = ",".join(cells)
    return "\n".join(lines) + "\n"


data_case("empty.csv", fit, b"", "empty")
data_case("header_only.csv", fit, ccd_lines[0] + "\n", note="no data row")
data_case("header_only_anova.csv", anova, l64_lines[0] + "\n", note="no data row")
# Five runs that vary in both inputs: a quadratic in two inputs needs seven.
data_case("too_few_rows.csv", fit, "\n".join(ccd_lines[:1] + ccd_lines[3:8]) + "\n", "runs")
data_case("non_numeric.csv", fit, ccd.replace("42.23", "42x23"), "42x23")
data_case("nan_response.csv", fit, ccd.replace("42.23", "nan"), "sigma_u_MPa")
data_case("overflow.csv", anova, l64_cell(1, "sigma_u_MPa", "1e999"), "sigma_u_MPa")
data_case("inf_factor.csv", anova, l64_cell(2, "kn_ks", "-inf"), "kn_ks")
data_case("ragged.csv", anova, l64.replace("\n2,", "\n2,99,", 1), "fields")
data_case("missing_column.csv", fit, "\n".join(",".join(l.split(",")[:2] + l.split(",")[3:]) for l in ccd_lines) + "\n",
          "pb_tau_c_MPa")
data_case("duplicate_header.csv", fit, ccd.replace("point_type", "sigma_u_MPa", 1), "twice")
data_case("binary.csv", anova, garbage(900, "data csv"))
data_case("nul_bytes.csv", fit, ccd.replace("pb_tau_c_MPa", "pb_tau\0_c_MPa", 1).encode(), "pb_tau_c_MPa")
data_case("unnamed_column.csv", fit, "," + ccd.split(",", 1)[1], "no name")
data_case("constant_input.csv", fit, "\n".join(ccd_lines[:1] + [",".join(l.split(",")[:2] + ["20"] + l.split(",")[3:])
                                                                  for l in ccd_lines[1:]]) + "\n", "constant")
data_case("all_failed.csv", anova, "\n".join([l64_lines[0].replace("run,", "run,status,", 1)] +
                                            [l.replace(",", ",failed: unstable,", 1) for l in l64_lines[1:]]) + "\n",
          "status")
# Ec_GPa made continuous (64 distinct values): not a categorical design column.
data_case("not_categorical.csv", anova, "\n".join(
    [l64_lines[0]] + [",".join([l.split(",")[0], f"{10 + i / 7:.4f}"] + l.split(",")[2:])
                      for i, l in enumerate(l64_lines[1:], 1)]) + "\n", "Ec_GPa")
data_case("run_not_integer.csv", anova, l64.replace("\n3,", "\n3.5,", 1), "3.5")
data_case("utf16.csv", fit, ccd.encode("utf-16"), "UTF-16")
case("data/does_not_exist", fit(missing(A, "does_not_exist.csv")), path(A, "does_not_exist.csv"), "cannot open")
case("data/directory", anova(f"{HERE}/dir/as_file.csv"), f"{HERE}/dir/as_file.csv")

# ---------------------------------------------------------------- model JSON (demcal-predict, demcal-invert)
def predict(f):
    return ["{bin}/demcal-predict", "--model", f, "--data", "data/literature/su2021_CCD2_sigma_u.csv",
            "--out", "{tmp}/predictions.csv"]


def invert(f):
    return ["{bin}/demcal-invert", "--model", f, "--target", "sigma_u_MPa=40", "--out", "{tmp}/solution.json"]


work = tempfile.mkdtemp()
common = ["--data", "data/literature/su2021_CCD2_sigma_u.csv", "--x", "pb_sigma_c_MPa,pb_tau_c_MPa",
          "--y", "sigma_u_MPa", "--quiet"]
subprocess.run([f"{BIN}/demcal-fit", "quadratic", *common, "--out", f"{work}/quadratic.json"], cwd=SRC, check=True)
subprocess.run([f"{BIN}/demcal-fit", "gabp", *common, "--hidden", "3", "--ga-population", "10", "--ga-generations", "5",
                "--out", f"{work}/gabp.json"], cwd=SRC, check=True)
with open(f"{work}/quadratic.json") as f:
    quadratic = json.load(f)
with open(f"{work}/gabp.json") as f:
    gabp = json.load(f)
shutil.rmtree(work)
for r in quadratic["responses"]:  # the tables a loader does not read: smaller files
    for key in ("natural_table", "coded_coefficients", "anova"):
        r.pop(key)
for key in ("hidden_search", "training", "validation", "validation_rows", "settings"):
    gabp.pop(key)
quadratic_text = json.dumps(quadratic, indent=1)
gabp_text = json.dumps(gabp, indent=1)
M = "model"
b0 = quadratic["responses"][0]["coefficients"]["1"]
w3 = gabp["network"]["parameters"][3]


def model_case(name, command, content, message=None, note=None):
    case(f"model/{name.rsplit('.', 1)[0]}", command(write(M, name, content)), path(M, name), message, note)


def response(**fields):
    return edited(quadratic, lambda d: d["responses"][0].update(fields))


def coefficient(value):
    return edited(quadratic, lambda d: d["responses"][0]["coefficients"].update({"1": value}))


def network(**fields):
    return edited(gabp, lambda d: d["network"].update(fields))


model_case("empty.json", predict, b"", "not valid JSON")
model_case("binary.json", invert, garbage(400, "model"), "not valid JSON")
model_case("truncated.json", predict, quadratic_text[: len(quadratic_text) // 2], "not valid JSON")
model_case("top_level_array.json", invert, [quadratic], "kind")
model_case("unknown_kind.json", predict, edited(quadratic, lambda d: d.update(kind="cubic")), "cubic")
model_case("kind_number.json", invert, edited(quadratic, lambda d: d.update(kind=2)), "kind")
model_case("format_unknown.json", predict, edited(quadratic, lambda d: d.update(format="demcal-model/99")), "format",
           note="a model format this reader does not know")
model_case("missing_coefficients.json", predict, edited(quadratic, lambda d: d["responses"][0].pop("coefficients")),
           "coefficients")
model_case("coefficient_null.json", invert, coefficient(None), "number")
model_case("coefficient_nan_token.json", predict, quadratic_text.replace(f'"1": {b0!r}', '"1": NaN'), "not valid JSON")
model_case("coefficient_string.json", invert, coefficient(str(b0)), "number")
model_case("coefficient_overflow.json", predict, quadratic_text.replace(f'"1": {b0!r}', '"1": 1e999'))
model_case("coefficient_huge.json", predict,
           edited(quadratic, lambda d: d["responses"][0]["coefficients"].update({"1": 1e308, "pb_sigma_c_MPa": 1e308})),
           note="predictions overflow to inf")
model_case("domain_low_above_high.json", invert, edited(quadratic, lambda d: d["inputs"][0].update(low=50)),
           "pb_sigma_c_MPa")
model_case("domain_huge.json", invert, edited(quadratic, lambda d: d["inputs"][0].update(low=-1e308, high=1e308)),
           "pb_sigma_c_MPa")
model_case("inputs_object.json", predict, edited(quadratic, lambda d: d.update(inputs={"pb_sigma_c_MPa": [5, 35]})),
           "inputs")
model_case("no_inputs.json", invert, edited(quadratic, lambda d: d.update(inputs=[])), "inputs")
model_case("no_responses.json", predict, edited(quadratic, lambda d: d.update(responses=[])), "responses")
model_case("term_unknown_input.json", invert,
           edited(quadratic, lambda d: d["responses"][0]["terms"][1].update(inputs=["pb_sigma_MPa"])), "pb_sigma_MPa")
model_case("duplicate_response.json", invert,
           edited(quadratic, lambda d: d["responses"].append(copy.deepcopy(d["responses"][0]))), "sigma_u_MPa")
model_case("outputs_disagree.json", predict, edited(quadratic, lambda d: d.update(outputs=["E_GPa"])), "outputs",
           note="\"outputs\" names E_GPa, the response is sigma_u_MPa")
model_case("gabp_weight_null.json", predict, edited(gabp, lambda d: d["network"]["parameters"].__setitem__(3, None)),
           "number")
model_case("gabp_weight_nan_token.json", invert, gabp_text.replace(repr(w3), "NaN", 1), "not valid JSON")
model_case("gabp_weights_short.json", predict, network(parameters=gabp["network"]["parameters"][:-1]), "parameters")
model_case("gabp_hidden_negative.json", invert, network(hidden=-2), "hidden")
model_case("gabp_hidden_huge.json", predict, network(hidden=2000000000), "hidden")
model_case("gabp_activation_relu.json", invert, network(activation="relu"), "tanh")
model_case("gabp_scaling_zero_range.json", predict,
           edited(gabp, lambda d: d["scaling"].update(input_max=d["scaling"]["input_min"])), "scaling",
           note="input_min == input_max: every input scales to inf or nan")
model_case("gabp_outputs_string.json", invert, edited(gabp, lambda d: d.update(outputs="sigma_u_MPa")), "outputs")
model_case("gabp_missing_network.json", predict, edited(gabp, lambda d: d.pop("network")), "network")
case("model/does_not_exist", invert(missing(M, "does_not_exist.json")), path(M, "does_not_exist.json"), "cannot open")
case("model/directory", predict(f"{HERE}/dir/as_file.json"), f"{HERE}/dir/as_file.json")

# ---------------------------------------------------------------- solution JSON (demcal-verify)
def verify(f):
    return ["{bin}/demcal-verify", "--solution", f, "--scene", "tests/data/ucs_small.json", "--out", "{tmp}/verify.json",
            "--seeds", "2", "--quiet", "--cache", "{tmp}/cache"]


solution = {"status": "ok", "x": {"pb_sigma_c_MPa": 11.5, "pb_tau_c_MPa": 25.0}, "targets": {"sigma_u_MPa": 12.0},
            "predicted": {"sigma_u_MPa": 12.0}, "objective": 1e-9}
solution_text = json.dumps(solution, indent=1)
V = "solution"


def solution_case(name, content, message=None, note=None):
    case(f"solution/{name.rsplit('.', 1)[0]}", verify(write(V, name, content)), path(V, name), message, note)


def x(**values):
    return edited(solution, lambda d: d["x"].update(values))


solution_case("empty.json", b"", "not valid JSON")
solution_case("binary.json", garbage(256, "solution"), "not valid JSON")
solution_case("truncated.json", solution_text[:60], "not valid JSON")
solution_case("top_level_array.json", [solution], "x")
solution_case("missing_x.json", edited(solution, lambda d: d.pop("x")), "x")
solution_case("missing_targets.json", edited(solution, lambda d: d.pop("targets")), "targets")
solution_case("x_array.json", edited(solution, lambda d: d.update(x=[11.5, 25.0])), "x")
solution_case("x_empty.json", edited(solution, lambda d: d.update(x={})), "x", note="no parameter to verify")
solution_case("x_value_string.json", x(pb_sigma_c_MPa="11.5"), "pb_sigma_c_MPa")
solution_case("x_value_null.json", x(pb_sigma_c_MPa=None), "pb_sigma_c_MPa")
solution_case("x_nan_token.json", solution_text.replace("11.5", "NaN"), "not valid JSON")
solution_case("x_overflow.json", solution_text.replace("11.5", "1e999"))
solution_case("x_unknown_parameter.json", edited(solution, lambda d: d["x"].update(pb_sigma_MPa=d["x"].pop("pb_sigma_c_MPa"))),
              "pb_sigma_MPa")
solution_case("x_outside_scene.json", x(pb_sigma_c_MPa=1e308), "pb_sigma_c_MPa")
solution_case("x_negative.json", x(pb_tau_c_MPa=-25.0), "pb_tau_c_MPa")
solution_case("status_number.json", edited(solution, lambda d: d.update(status=0)), "status")
solution_case("targets_value_string.json", edited(solution, lambda d: d.update(targets={"sigma_u_MPa": "12"})),
              "sigma_u_MPa")
solution_case("targets_array.json", edited(solution, lambda d: d.update(targets=[12.0])), "targets")
solution_case("target_unknown_output.json", edited(solution, lambda d: d.update(targets={"density": 2400})), "density")
solution_case("predicted_array.json", edited(solution, lambda d: d.update(predicted=[12.0])), "predicted")
case("solution/does_not_exist", verify(missing(V, "does_not_exist.json")), path(V, "does_not_exist.json"), "cannot open")
case("solution/directory", verify(f"{HERE}/dir/as_file.json"), f"{HERE}/dir/as_file.json")

# ---------------------------------------------------------------- study JSON (demcal_study plan)
def plan(f):
    return ["{study}", "plan", f, "{tmp}/plan"]


study = load("tests/data/study_small.json")
study_text = json.dumps(study, indent=1)
T = "study"


def study_case(name, content, message=None, note=None):
    case(f"study/{name.rsplit('.', 1)[0]}", plan(write(T, name, content)), path(T, name), message, note)


def surface0(**fields):
    return edited(study, lambda d: d["surfaces"][0].update(fields))


study_case("empty.json", b"", "not valid JSON")
study_case("binary.json", garbage(333, "study"), "JSON")
study_case("truncated.json", study_text[:500], "not valid JSON")
study_case("top_level_array.json", [study])
study_case("unknown_field.json", edited(study, lambda d: d.update(surogate=d.pop("surrogate"))), "surogate")
study_case("missing_scene.json", edited(study, lambda d: d.pop("scene")), "scene")
study_case("name_number.json", edited(study, lambda d: d.update(name=5)), "name")
# The study's own target as written, so the token cases edit it whatever its value (a replace that finds
# nothing would leave a valid study).
target_text = f'"sigma_u_MPa": {json.dumps(study["targets"]["sigma_u_MPa"])}'
assert target_text in study_text, target_text
study_case("target_nan_token.json", study_text.replace(target_text, '"sigma_u_MPa": NaN'), "sigma_u_MPa",
           note="Python's json reads NaN")
study_case("target_overflow.json", study_text.replace(target_text, '"sigma_u_MPa": 1e999'), "sigma_u_MPa",
           note="Python's json reads 1e999 as inf")
study_case("target_string.json", edited(study, lambda d: d.update(targets={"sigma_u_MPa": "12"})), "sigma_u_MPa")
study_case("target_unknown_output.json", edited(study, lambda d: d.update(targets={"density": 2400})), "density")
study_case("scene_file_missing.json", edited(study, lambda d: d.update(scene="tests/bad_inputs/study/no_such_scene.json")),
           "no_such_scene.json")
study_case("factor_typo.json", surface0(factors=["pb_sigma_c_MPa", "pb_tau_MPa"]), "pb_tau_MPa")
study_case("surfaces_object.json", edited(study, lambda d: d.update(surfaces={"sigma_u_MPa": d["surfaces"][0]})),
           "surfaces")
study_case("design_kind_unknown.json", surface0(design={"kind": "pb"}), "kind")
study_case("design_string.json", surface0(design="ccd"), "design")
study_case("verification_seeds_string.json", edited(study, lambda d: d["verification"].update(seeds="two")), "seeds")
study_case("verification_one_seed.json", edited(study, lambda d: d["verification"].update(seeds=1)), "seeds")
study_case("restarts_negative.json", edited(study, lambda d: d["inversion"].update(restarts=-1)), "restarts")
study_case("refinement_negative.json", edited(study, lambda d: d.update(refinement={"rounds": -1})), "refinement")
study_case("compare_with_missing.json", edited(study, lambda d: d.update(compare_with=["tests/data/no_such_study.json"])),
           "compare_with")
study_case("fixed_unknown.json", edited(study, lambda d: d.update(fixed={"Ec_GP": 16})), "Ec_GP")
study_case("loop_with_surfaces.json", edited(study, lambda d: d.update(strategy="dem_in_the_loop",
                                                                        factors=["pb_sigma_c_MPa"])), "surfaces")
case("study/does_not_exist", plan(missing(T, "does_not_exist.json")), path(T, "does_not_exist.json"), "cannot open")
case("study/directory", plan(f"{HERE}/dir/as_file.json"), f"{HERE}/dir/as_file.json")

manifest = {
    "description": "Bad inputs: each case must exit with code 2 and print exactly one non-empty line on stderr that "
                   "contains `file` (the path as given on the command line) and, if given, `message`. Run from "
                   "SRC_DIR by run_bad_inputs.py; written by make_corpus.py. `note`: what is wrong, where the file does not say it.",
    "placeholders": {"{bin}": "BIN_DIR", "{src}": "SRC_DIR", "{tmp}": "a fresh temporary folder per case",
                     "{study}": "the study layer: `/usr/bin/python3 -m demcal_study` (PYTHONPATH=SRC_DIR/python); "
                                "BIN=BIN_DIR is set for every case"},
    "cases": CASES,
}
ids = [c["id"] for c in CASES]
assert len(ids) == len(set(ids)), "duplicate case ids"
with open(os.path.join(SRC, HERE, "cases.json"), "w") as f:  # one case a line
    head = json.dumps({k: v for k, v in manifest.items() if k != "cases"}, indent=1)[:-2]
    f.write(head + ',\n "cases": [\n  ' + ",\n  ".join(json.dumps(c) for c in CASES) + "\n ]\n}\n")
print(f"{len(CASES)} cases written to {HERE}/cases.json")
