"""The verification curves of the report: one panel per test of a test list, a biaxial series drawn one specimen
at a time."""
import h5py
import numpy as np

from demcal_study import plots


def stored(path, groups):
    with h5py.File(path, "w") as f:
        for name, datasets in groups.items():
            g = f.create_group(f"points/{name}")
            for key, values in datasets.items():
                g.create_dataset(key, data=np.asarray(values, float))


def test_a_test_list_gets_a_panel_per_test_and_a_series_splits_per_specimen(tmp_path):
    runs = tmp_path / "runs.h5"
    series = {"curve_biaxial.axial_strain": [0, 1e-3, 2e-3, 0, 1e-3], "curve_biaxial.stress_MPa": [0, 5, 4, 0, 7],
              "curve_biaxial.confining_stress_MPa": [1, 1, 1, 4, 4]}
    stored(runs, {"run1_seed1": dict(series, **{"curve_ucs.axial_strain": [0, 1e-3], "curve_ucs.stress_MPa": [0, 9]}),
                  "run1_seed2": {"curve_ucs.axial_strain": [0, 1e-3], "curve_ucs.stress_MPa": [0, 8]}})
    with h5py.File(runs, "r") as f:
        sets = plots.curve_sets(f["points/run1_seed1"])
        assert sorted(sets) == ["biaxial", "ucs"]
        assert plots.confined(f["points/run1_seed1"], "biaxial") and not plots.confined(f["points/run1_seed1"], "ucs")
    assert [len(s) for s, _ in plots.pieces(*sets["biaxial"])] == [3, 2]
    out = tmp_path / "curves.png"
    axes = plots.curve_axes({"test": "list", "tests": [
        {"label": "biaxial", "curve_axes": {"x": "axial strain", "y": "deviatoric stress (MPa)"}},
        {"label": "ucs", "curve_axes": {"x": "axial strain", "y": "axial stress (MPa)"}}]})
    assert plots.curves_png(str(runs), str(out), axes) is None and out.stat().st_size > 0
    # The axes come from the scene's description (demcal-dem describe): without them, no plot and why.
    assert "could not be described" in plots.curves_png(str(runs), str(out), None)


def test_a_scene_keeps_its_one_panel_and_no_curve_says_so(tmp_path):
    runs = tmp_path / "runs.h5"
    stored(runs, {"run1_seed1": {"curve_axial_strain": [0, 1e-3], "curve_stress_MPa": [0, 9]}})
    with h5py.File(runs, "r") as f:
        assert list(plots.curve_sets(f["points/run1_seed1"])) == [""]
    one = plots.curve_axes({"test": "ucs", "curve_axes": {"x": "axial strain", "y": "axial stress (MPa)"}})
    assert plots.curves_png(str(runs), str(tmp_path / "c.png"), one) is None
    empty = tmp_path / "empty.h5"
    stored(empty, {"run1_seed1": {"run": [1]}})
    assert plots.curves_png(str(empty), str(tmp_path / "e.png"), one) == "(no curves stored)"
    # A test whose record is not a curve (a heap's profile) is left out.
    assert plots.curves_png(str(runs), str(tmp_path / "h.png"), {"": None}) == "(no curves stored)"
