"""values.choose_factors on a hand-made screening ANOVA: threshold, max_factors, too few significant, the
design kind's largest factor count."""
import pytest

from demcal_study.errors import StudyError
from demcal_study.values import choose_factors

SPACE = {"parameters": [{"name": n} for n in ("a", "b", "c", "d", "e")]}
KINDS = {"ccd": {"title": "central composite", "min_factors": 2, "max_factors": 10},
         "bbd": {"title": "Box-Behnken", "min_factors": 3, "max_factors": 7},
         "lhs": {"title": "Latin hypercube", "min_factors": 1, "max_factors": None}}
ANOVA = {
    "sigma_u_MPa": {"a": {"F": 50.0, "p": 0.001}, "b": {"F": 20.0, "p": 0.01}, "c": {"F": 5.0, "p": 0.03},
                    "d": {"F": 1.2, "p": 0.4}, "e": {"F": 0.5, "p": 0.7},
                    "blank1": {"F": 90.0, "p": 0.0001},  # not a parameter of the space: never chosen
                    "error": {"F": None, "p": None}},
    "E_GPa": {"a": {"F": 2.0, "p": 0.2}, "d": {"F": 80.0, "p": 0.0001}, "e": {"F": 0.1, "p": 0.9}},
}


def study(outputs=("sigma_u_MPa",), kind="ccd", **screening):
    return {"screening": dict({"outputs": list(outputs)}, **screening),
            "surfaces": [{"outputs": list(outputs), "factors": "auto", "design": {"kind": kind}}]}


def test_parameters_below_the_threshold_strongest_first():
    chosen = choose_factors(study(p_threshold=0.05), SPACE, ANOVA, KINDS)["g1"]
    assert chosen["factors"] == ["a", "b", "c"]
    assert chosen["note"] == ""
    assert chosen["p"]["d"] == 0.4 and "blank1" not in chosen["p"]


def test_a_lower_threshold_keeps_fewer():
    assert choose_factors(study(p_threshold=0.02), SPACE, ANOVA, KINDS)["g1"]["factors"] == ["a", "b"]


def test_max_factors_keeps_the_strongest_and_says_so():
    chosen = choose_factors(study(max_factors=2), SPACE, ANOVA, KINDS)["g1"]
    assert chosen["factors"] == ["a", "b"]
    assert "3 parameters pass p < 0.05; the 2 strongest are kept" in chosen["note"]


def test_each_parameter_counts_with_its_strongest_output():
    chosen = choose_factors(study(outputs=("sigma_u_MPa", "E_GPa")), SPACE, ANOVA, KINDS)["g1"]
    assert chosen["factors"] == ["d", "a", "b", "c"]
    assert chosen["F"]["a"] == 50.0


def test_too_few_significant_the_next_strongest_join():
    chosen = choose_factors(study(kind="bbd", p_threshold=0.005), SPACE, ANOVA, KINDS)["g1"]
    assert chosen["factors"] == ["a", "b", "c"]
    assert "only 1 parameter(s) pass p < 0.005; a bbd needs 3, so b, c (the next strongest) joined" == chosen["note"]


def test_the_design_kind_caps_the_count():
    kinds = dict(KINDS, bbd=dict(KINDS["bbd"], max_factors=3))
    chosen = choose_factors(study(outputs=("sigma_u_MPa", "E_GPa"), kind="bbd"), SPACE, ANOVA, kinds)["g1"]
    assert chosen["factors"] == ["d", "a", "b"]
    assert chosen["note"].endswith("a Box-Behnken design takes at most 3: the 3 strongest are kept")


def test_a_design_the_ranked_parameters_cannot_fill_is_refused():
    kinds = dict(KINDS, bbd=dict(KINDS["bbd"], min_factors=6))
    with pytest.raises(StudyError, match=r"surfaces\[0\]: the screening ANOVA ranks only 5 parameter\(s\)"):
        choose_factors(study(kind="bbd"), SPACE, ANOVA, kinds)


def test_only_auto_surfaces_are_chosen_and_keep_their_number():
    s = study()
    s["surfaces"].insert(0, {"outputs": ["nu"], "factors": ["a", "b"], "design": {"kind": "ccd"}})
    chosen = choose_factors(s, SPACE, ANOVA, KINDS)
    assert list(chosen) == ["g2"]
