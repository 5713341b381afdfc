"""seeds_per_point "auto" for the DEM in the loop: how many specimens each candidate must run on, from the
scatter of the targets over SCATTER_SEEDS specimens at the space's reference point. The objective is the mean over
K specimens with common random numbers (the same K for every candidate); K is the smallest number whose standard
error, CV / sqrt(K), is at most a third of the tolerance, capped at MAX_SEEDS_PER_POINT (the report says when the
cap bound)."""
import math

SCATTER_SEEDS = 5
MAX_SEEDS_PER_POINT = 10


def reference_point(study, scene, space):
    """The factors at the space's reference (else the scene's default), kept inside the space's range."""
    point = {}
    by_name = {p["name"]: p for p in space.get("parameters", [])}
    for name in study["factors"]:
        p = by_name[name]
        value = p.get("reference", scene["parameters"][name]["value"])
        point[name] = min(max(value, p["low"]), p["high"])
    return point


def seeds_per_point(verification, tolerance):
    """{"seeds_per_point": K, "cv_pct": {output: CV}, "capped": bool, ...} from the scatter verification."""
    cvs = {o: r["cv_pct"] for o, r in verification["outputs"].items() if r.get("cv_pct") is not None}
    if not cvs:
        return {"seeds_per_point": 1, "cv_pct": {}, "capped": False, "note": "no spread measured (runs failed)"}
    worst = max(cvs.values())
    allowed = 100.0 * tolerance / 3.0
    k = max(1, math.ceil((worst / allowed) ** 2))
    capped = k > MAX_SEEDS_PER_POINT
    return {"seeds_per_point": min(k, MAX_SEEDS_PER_POINT), "cv_pct": cvs, "capped": capped,
            "standard_error_pct": worst / math.sqrt(min(k, MAX_SEEDS_PER_POINT)), "allowed_pct": allowed,
            "scatter_seeds": len(verification["seeds"])}
