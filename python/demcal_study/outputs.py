"""Outputs a study or a calibration may name: a DEM output as `demcal-dem describe` lists it, or a ratio A/B of
two (sigma_t_MPa/sigma_u_MPa), which the executables form per run (the ratio of the numbers as reported, so
sigma_u_MPa/E_GPa is in MPa per GPa); and how many lab tests one point of a scene runs."""
from .errors import fail, load_json


def ratio_parts(name, where):
    """(A, B) of "A/B"; None for a plain name."""
    if "/" not in name:
        return None
    a, _, b = name.partition("/")
    if not a or not b or "/" in b:
        fail(f"{where}: \"{name}\" is not an output or a ratio A/B of two outputs")
    return a, b


def stem(name):
    """An output's name as part of a file name: a ratio's '/' becomes '_over_' (sigma_t_MPa_over_sigma_u_MPa)."""
    return name.replace("/", "_over_")


def is_output(outputs, name, where):
    """Whether `name` is one of `outputs` (describe's dict) or a ratio of two of them."""
    parts = ratio_parts(name, where)
    return all(p in outputs for p in parts) if parts else name in outputs


def output_info(outputs, name, where):
    """describe's entry of an output; for a ratio: stress-like when only its numerator is, dimensionless when both
    or neither are (a stress over a pure number would be stress-like; a pure number over a stress is refused)."""
    parts = ratio_parts(name, where)
    if not parts:
        return outputs[name]
    a, b = (outputs[p] for p in parts)
    if b["stress_like"] and not a["stress_like"]:
        fail(f"{where}: {name}: a pure number over a stress has no unit demcal can scale; use its inverse")
    stress = a["stress_like"] and not b["stress_like"]
    return {"unit": f"{a['unit']}/{b['unit']}", "stress_like": stress, "si_factor": a["si_factor"] / b["si_factor"],
            "description": f"{parts[0]} over {parts[1]}, per run"}


def with_ratios(values, names):
    """`values` ({output: number}) with each ratio in `names` added where both parts are there."""
    out = dict(values)
    for name in names:
        parts = ratio_parts(name, name)
        if parts and name not in out and all(isinstance(out.get(p), (int, float)) for p in parts):
            b = out[parts[1]]
            out[name] = out[parts[0]] / b if b != 0 else float("nan")  # as the executables: no number
    return out


def tests_described(description):
    """Lab tests one design point runs, from `demcal-dem describe`'s JSON of its scene or test list."""
    return len(description["tests"]) if description.get("test") == "list" else 1


def tests_per_point(scene_path):
    """Lab tests one design point runs: the length of a test list, 1 for a scene."""
    scene = load_json(scene_path, "scene file")
    tests = scene.get("tests") if isinstance(scene, dict) else None
    return len(tests) if isinstance(tests, list) and tests else 1
