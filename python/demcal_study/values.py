"""Pure functions of a study: the values of the parameters it does not vary, the sub-space it varies, and the
factors its screening ANOVA chooses for an "auto" surface."""
from .errors import fail


def fixed_values(study, scene, space, varied):
    """Every scene parameter not varied: the study's fixed value, else the space's reference, else the scene's
    value; the space's own fixed values are added over them."""
    values = {}
    refs = {p["name"]: p.get("reference") for p in space.get("parameters", [])}
    for name, spec in scene["parameters"].items():
        if name in varied:
            continue
        if isinstance(study.get("fixed"), dict) and name in study["fixed"]:
            values[name] = study["fixed"][name]
        elif refs.get(name) is not None:
            values[name] = refs[name]
        else:
            values[name] = spec["value"]
    values.update(space.get("fixed", {}))
    return values


def subspace(space, factors, fixed):
    """The space's parameters named in `factors` (in the space's order) with `fixed` as its fixed values."""
    params = [p for p in space["parameters"] if p["name"] in factors]
    return {"parameters": params, "fixed": dict(fixed)}


def choose_factors(study, space, anova, kinds):
    """Factors of each "auto" surface: the parameters whose screening ANOVA p lies below the threshold for any
    of its outputs, strongest (largest F) first, at most max_factors; when fewer pass than the design needs, the
    next strongest are added and the note says so. `kinds` holds the design kinds' factor limits
    (demcal-doe --list-kinds). Returns {"g1": {outputs, factors, threshold, p, F, note}, ...}."""
    screening = study["screening"]
    threshold = float(screening.get("p_threshold", 0.05))
    limit = int(screening.get("max_factors", 6))
    names = {p["name"] for p in space["parameters"]}
    chosen = {}
    for k, surface in enumerate(study["surfaces"]):
        if surface["factors"] != "auto":
            continue
        best = {}  # name: (F, p) of the output where it is strongest
        for o in surface["outputs"]:
            for name, row in anova.get(o, {}).items():
                if name in names and isinstance(row.get("F"), (int, float)) and isinstance(row.get("p"), (int, float)):
                    f, p = row["F"], row["p"]
                    if name not in best or f > best[name][0]:
                        best[name] = (f, p)
        ranked = sorted(best, key=lambda n: -best[n][0])
        significant = [n for n in ranked if best[n][1] < threshold]
        factors = significant[:limit]
        limits = kinds[surface["design"]["kind"]]
        need = limits["min_factors"]
        note = ""
        if len(significant) > limit:
            note = f"{len(significant)} parameters pass p < {threshold}; the {limit} strongest are kept (max_factors)"
        if len(factors) < need:
            added = [n for n in ranked if n not in factors][:need - len(factors)]
            note = (f"only {len(factors)} parameter(s) pass p < {threshold}; a {surface['design']['kind']} needs {need}, "
                    f"so {', '.join(added)} (the next strongest) joined")
            factors += added
        if len(factors) < need:
            fail(f"surfaces[{k}]: the screening ANOVA ranks only {len(factors)} parameter(s) for "
                 f"{', '.join(surface['outputs'])}; a {surface['design']['kind']} needs {need}")
        most = limits["max_factors"]
        if most and len(factors) > most:
            factors = factors[:most]
            note += f"; a {limits['title']} design takes at most {most}: the {most} strongest are kept"
        chosen[f"g{k + 1}"] = {"outputs": surface["outputs"], "factors": factors, "threshold": threshold,
                               "p": {n: best[n][1] for n in ranked}, "F": {n: best[n][0] for n in ranked}, "note": note}
    return chosen
