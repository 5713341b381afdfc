"""values.fixed_values and values.subspace: what a design holds for the parameters it does not vary."""
from demcal_study.values import fixed_values, subspace

SCENE = {"parameters": {"a": {"value": 1}, "b": {"value": 2}, "c": {"value": 3}, "d": {"value": 4}}}
SPACE = {"parameters": [{"name": "a", "low": 0, "high": 20, "reference": 10},
                        {"name": "b", "low": 0, "high": 40, "reference": 20},
                        {"name": "c", "low": 0, "high": 6}],
         "fixed": {"e": 5}}


def test_study_fixed_beats_space_reference_beats_scene_default():
    values = fixed_values({"fixed": {"b": 200}}, SCENE, SPACE, ["a"])
    assert values == {"b": 200, "c": 3, "d": 4, "e": 5}


def test_reference_takes_the_space_reference_where_there_is_one():
    values = fixed_values({"fixed": "reference"}, SCENE, SPACE, ["c"])
    assert values == {"a": 10, "b": 20, "d": 4, "e": 5}


def test_varied_parameters_are_left_out_and_space_fixed_is_added_over_the_rest():
    space = dict(SPACE, fixed={"d": 40})
    values = fixed_values({}, SCENE, space, ["a", "b", "c"])
    assert values == {"d": 40}


def test_subspace_keeps_the_space_order_and_the_fixed_values():
    sub = subspace(SPACE, ["c", "a"], {"b": 20})
    assert [p["name"] for p in sub["parameters"]] == ["a", "c"]
    assert sub["fixed"] == {"b": 20}
