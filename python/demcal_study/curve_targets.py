"""A measured stress-strain curve as a target: the curve becomes a few scalar targets, the measured stress (and
lateral strain, when given) at evenly spaced strains over a window of the measured peak strain, and every search,
the Bayesian one included, meets those as it meets any target.

The curve file is CSV with a header, `axial_strain,axial_stress_MPa[,lateral_strain][,sd_MPa]`, compression
positive and strains as fractions (so a specimen that swells has a negative lateral strain), one row per
measurement, strains increasing. The window `A:B` is given in fractions of the measured peak strain (the strain at
the largest stress). A `specimen` column (instead of `sd_MPa`) holds several specimens' curves: the window is then
taken on their mean curve, each point is their mean with their SD and count, and the points' correlation over the
specimens is kept for the Bayesian likelihood. The points' names say where they are: `curve_MPa@0.0021` (a stress at axial strain 0.0021),
`curve_lateral@0.0021`, prefixed by the test's label in a test list (`ucs.curve_MPa@0.0021`).

A confined test's curve (a biaxial or triaxial series) adds the column `confining_stress_MPa`, the lab's sigma_3,
the same on every row; its `axial_stress_MPa` is then the axial stress sigma_1. It is compared with the piece of
the series' curve run at that sigma_3 (the scene must run it), the DEM's sigma_1 being its deviator plus its
measured sigma_3; its points' names carry sigma_3 (`curve_s3_10_MPa@0.0021`, `curve_lateral_s3_10@0.0021`; 2.5 MPa
is written 2p5).

The DEM's curve is read at the same strains by linear interpolation; past the end of a DEM curve (a specimen that
failed and stopped earlier) the curve's last value stands, which is what the failed specimen carries."""
import csv
import math
import os

import numpy as np

from .point_results import read_point_result

POINTS = 8             # strains a curve is compared at
DEFAULT_WINDOW = (0.1, 1.0)
MIN_ROWS = 5
STRESS, LATERAL = "curve_MPa", "curve_lateral"
CONFINEMENT_MATCH = 0.01  # a lab curve's sigma_3 and a scene's confinement within this share of each other


def parse_spec(spec):
    """`[LABEL:]PATH` -> (label or None, path). A path may hold a colon only when a label is given."""
    if ":" in spec and not os.path.exists(spec):
        label, path = spec.split(":", 1)
        return label, path
    return None, spec


def parse_window(text, where, problems):
    """`A:B` (fractions of the peak strain, 0 <= A < B) -> (A, B), or None with a problem added."""
    parts = str(text).split(":")
    try:
        a, b = (float(x) for x in parts) if len(parts) == 2 else (None, None)
    except ValueError:
        a = b = None
    if a is None or not (math.isfinite(a) and math.isfinite(b)) or not 0 <= a < b:
        problems.add(f"{where}: \"{text}\" is not A:B with 0 <= A < B (fractions of the peak strain, e.g. 0.1:1.0)")
        return None
    return a, b


def read_curve(path, where, problems):
    """The measured curve as {column: numpy array}; with a `specimen` column, {"specimens": [one such curve per
    specimen, in the file's order]}; or None with one problem per defect."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        problems.add(f"{where}: {path}: cannot be read ({e.strerror})")
        return None
    if not rows:
        problems.add(f"{where}: {path}: empty; give the header axial_strain,axial_stress_MPa[,lateral_strain][,sd_MPa]"
                     "[,confining_stress_MPa][,specimen]")
        return None
    header = [h.strip() for h in rows[0]]
    known = ("axial_strain", "axial_stress_MPa", "lateral_strain", "sd_MPa", "confining_stress_MPa", "specimen")
    bad = [h for h in header if h not in known]
    if bad or "axial_strain" not in header or "axial_stress_MPa" not in header:
        problems.add(f"{where}: {path}: header {','.join(header)}: give axial_strain,axial_stress_MPa and optionally "
                     "lateral_strain, sd_MPa, confining_stress_MPa and specimen" +
                     (f" (unknown: {', '.join(bad)})" if bad else ""))
        return None
    if "specimen" in header and "sd_MPa" in header:
        problems.add(f"{where}: {path}: give a specimen column or an sd_MPa column, not both (the specimens give the SD)")
        return None
    numeric = [h for h in header if h != "specimen"]
    columns, lines, specimen_of = {h: [] for h in numeric}, [], []
    for k, row in enumerate(rows[1:], start=2):
        if not any(cell.strip() for cell in row):
            continue
        if len(row) != len(header):
            problems.add(f"{where}: {path}: line {k} has {len(row)} values, the header {len(header)}")
            return None
        for h, cell in zip(header, row):
            if h == "specimen":
                if not cell.strip():
                    problems.add(f"{where}: {path}: line {k}: specimen is empty")
                    return None
                specimen_of.append(cell.strip())
                continue
            try:
                x = float(cell)
            except ValueError:
                x = float("nan")
            if not math.isfinite(x):
                problems.add(f"{where}: {path}: line {k}: {h} \"{cell.strip()}\" is not a number")
                return None
            columns[h].append(x)
        lines.append(k)
    if "confining_stress_MPa" in columns and columns["confining_stress_MPa"]:
        s3 = np.array(columns["confining_stress_MPa"])
        if np.any(s3 <= 0) or np.ptp(s3) > CONFINEMENT_MATCH * float(np.max(s3)):
            problems.add(f"{where}: {path}: confining_stress_MPa must be one positive sigma_3 on every line (one "
                         f"confinement per file; it spans {float(np.min(s3)):g} to {float(np.max(s3)):g})")
            return None
    if "specimen" not in header:
        return checked_curve({h: np.array(v) for h, v in columns.items()}, lines, f"{where}: {path}", problems)
    specimens = []
    for name in dict.fromkeys(specimen_of):  # in the file's order
        rows_of = [i for i, s in enumerate(specimen_of) if s == name]
        one = checked_curve({h: np.array([v[i] for i in rows_of]) for h, v in columns.items()},
                            [lines[i] for i in rows_of], f"{where}: {path}: specimen {name}", problems)
        if one is None:
            return None
        specimens.append(one)
    if len(specimens) < 2:
        problems.add(f"{where}: {path}: one specimen gives no scatter; give at least 2 (or an sd_MPa column)")
        return None
    return {"specimens": specimens, "specimen_names": list(dict.fromkeys(specimen_of))}


def checked_curve(curve, lines, where, problems):
    """One curve's checks (enough points, strains increasing, a positive SD); the curve, or None with a problem."""
    n = len(curve["axial_strain"])
    if n < MIN_ROWS:
        problems.add(f"{where}: {n} point(s); a curve needs at least {MIN_ROWS}")
        return None
    steps = np.diff(curve["axial_strain"])
    if np.any(steps <= 0):
        k = int(np.argmax(steps <= 0)) + 1  # the first strain not above the one before
        problems.add(f"{where}: line {lines[k]}: axial_strain {curve['axial_strain'][k]:g} is not above the one "
                     f"before ({curve['axial_strain'][k - 1]:g}): strains must increase")
        return None
    if "sd_MPa" in curve and np.any(curve["sd_MPa"] <= 0):
        problems.add(f"{where}: sd_MPa must be positive on every line")
        return None
    return curve


def point_names(label, strains, lateral, confining_mpa=None):
    """The targets' names, stress points first: each strain with the digits that tell it from its neighbours; a
    confined curve's names carry its sigma_3 (a point in it written as p: no dot, which separates a label)."""
    prefix = f"{label}." if label else ""
    for digits in range(4, 12):
        texts = [f"{e:.{digits}g}" for e in strains]
        if len(set(texts)) == len(texts):
            break
    stress, lateral_name = STRESS, LATERAL
    if confining_mpa is not None:
        s3 = f"{confining_mpa:g}".replace(".", "p")
        stress, lateral_name = f"curve_s3_{s3}_MPa", f"{LATERAL}_s3_{s3}"
    names = [f"{prefix}{stress}@{t}" for t in texts]
    if lateral:
        names += [f"{prefix}{lateral_name}@{t}" for t in texts]
    return names


def curve_target(spec, window, where, problems):
    """A curve target as the calibration stores it: {"spec", "label", "path", "window", "peak_strain",
    "points": [{"name", "strain", "kind", "value", "sd"}]}, or None with problems added. A confined curve adds
    "confining_stress_MPa" and "piece" (its piece of the series' curve, set by check_against_scene). From several
    specimens, each point is their mean with their SD and their number "n", and the target adds "specimens" and
    "by_specimen", each specimen's values ({specimen: {point name: value}}), whose correlation the Bayesian
    likelihood takes."""
    label, path = parse_spec(spec)
    curve = read_curve(path, where, problems)
    if curve is None or window is None:
        return None
    specimens = curve.get("specimens")
    if specimens:
        # The mean curve over the strains every specimen reached sets the peak and bounds the window.
        first = max(float(c["axial_strain"][0]) for c in specimens)
        last = min(float(c["axial_strain"][-1]) for c in specimens)
        if not last > first:
            problems.add(f"{where}: {path}: the specimens' curves share no strains")
            return None
        strain = np.linspace(first, last, 401)
        stress = np.mean([np.interp(strain, c["axial_strain"], c["axial_stress_MPa"]) for c in specimens], axis=0)
        one = specimens[0]
    else:
        strain, stress, one = curve["axial_strain"], curve["axial_stress_MPa"], curve
    peak = float(strain[int(np.argmax(stress))])
    if peak <= 0:
        problems.add(f"{where}: {path}: the peak stress is at strain {peak:g}; a curve needs its peak at a positive strain")
        return None
    lo, hi = window[0] * peak, window[1] * peak
    if lo < strain[0] or hi > strain[-1]:
        whose = "the specimens' common" if specimens else "the curve's"
        problems.add(f"{where}: {path}: the window {window[0]:g}:{window[1]:g} of the peak strain {peak:g} spans "
                     f"strains {lo:g} to {hi:g}, outside {whose} {strain[0]:g} to {strain[-1]:g}")
        return None
    at = np.linspace(lo, hi, POINTS)
    lateral = "lateral_strain" in one
    confining = float(np.mean(one["confining_stress_MPa"])) if "confining_stress_MPa" in one else None
    names = point_names(label, at, lateral, confining)
    kinds = ["stress"] * POINTS + ["lateral"] * (POINTS if lateral else 0)
    by_specimen = None
    if specimens:
        # Each specimen's values at the points: stresses, then lateral strains.
        values = np.array([np.concatenate([np.interp(at, c["axial_strain"], c["axial_stress_MPa"])] +
                                          ([np.interp(at, c["axial_strain"], c["lateral_strain"])] if lateral else []))
                           for c in specimens])
        mean, sd = values.mean(axis=0), values.std(axis=0, ddof=1)
        for q, s in zip(names, sd):
            if not s > 0:
                problems.add(f"{where}: {path}: every specimen gives the same value at {q}: no scatter to weigh it by")
                return None
        by_specimen = {sid: {n: float(v) for n, v in zip(names, row)}
                       for sid, row in zip(curve["specimen_names"], values)}
        points = [{"name": n, "strain": float(e), "kind": k, "value": float(v), "sd": float(d), "n": len(specimens)}
                  for n, e, k, v, d in zip(names, np.concatenate([at] * (2 if lateral else 1)), kinds, mean, sd)]
    else:
        sd = np.interp(at, strain, curve["sd_MPa"]) if "sd_MPa" in curve else [None] * POINTS
        points = [{"name": n, "strain": float(e), "kind": "stress", "value": float(v),
                   "sd": None if d is None else float(d)}
                  for n, e, v, d in zip(names, at, np.interp(at, strain, stress), sd)]
        if lateral:
            points += [{"name": n, "strain": float(e), "kind": "lateral", "value": float(v), "sd": None}
                       for n, e, v in zip(names[POINTS:], at, np.interp(at, strain, curve["lateral_strain"]))]
    for q in points:
        if q["value"] == 0:
            problems.add(f"{where}: {path}: the {q['kind']} at strain {q['strain']:g} is 0; a target must be non-zero "
                         "(start the window later)")
            return None
    target = {"spec": spec, "label": label, "path": path, "window": list(window), "peak_strain": peak,
              "points": points}
    # Only what a curve has (a stored calibration of a plain curve keeps its settings, and resumes).
    if confining is not None:
        target.update(confining_stress_MPa=confining, piece=None)
    if specimens:
        target.update(specimens=len(specimens), by_specimen=by_specimen)
    return target


def read_curves(specs, window_text, problems, where, window_where, each_where=None, description=None):
    """The curves of `specs` over the window `window_text` (None: the default), each read as curve_target does
    (named by each_where(k), else `where`), checked against the scene's description when one is given; every
    defect a problem."""
    text = window_text if window_text is not None else "%g:%g" % DEFAULT_WINDOW
    window = parse_window(text, window_where, problems)
    curves = [c for c in (curve_target(spec, window, each_where(k) if each_where else where, problems)
                          for k, spec in enumerate(specs)) if c]
    if description:
        check_against_scene(curves, description, where, problems)
    return curves


def without_scatter(curve):
    """Whether a point of the curve has no SD from the lab (neither an sd_MPa column nor specimens, or a lateral
    strain without specimens: sd_MPa is the stress's), which the Bayesian search cannot weigh."""
    return any(q["sd"] is None for q in curve["points"])


def check_against_scene(curves, description, where, problems):
    """A curve must name a test of a list by its label (and a single test takes none). A curve without a
    confining_stress_MPa column needs a test whose curve is an axial stress against axial strain; one with it a
    confined series that runs its sigma_3, whose piece of the series' curve it then reads (c["piece"])."""
    tests = description.get("tests") if description.get("test") == "list" else None
    for c in curves:
        if tests is not None:
            labels = [t["label"] for t in tests]
            if c["label"] not in labels:
                problems.add(f"{where}: {c['spec']}: a test list's curve names its test, LABEL:{c['path']} "
                             f"(labels: {', '.join(labels)})")
                continue
            test = next(t for t in tests if t["label"] == c["label"])
        else:
            if c["label"] is not None:
                problems.add(f"{where}: {c['spec']}: the scene is a single test: give the curve without a label")
                continue
            test = description
        axes = test.get("curve_axes") or {}
        confinements = test.get("curve_confinements_MPa") or []
        x, y = axes.get("x", "none"), str(axes.get("y", "none"))
        s3 = c.get("confining_stress_MPa")
        if s3 is None:
            if x != "axial strain" or not y.startswith("axial stress"):
                problems.add(f"{where}: {c['spec']}: the test's curve is {y} against {x}; a measured curve is compared "
                             "with an axial stress against axial strain (a uniaxial test)" +
                             ("; a confined series' curve gives its sigma_3 in a confining_stress_MPa column"
                              if confinements else ""))
        elif not confinements or x != "axial strain" or not y.startswith("deviatoric stress"):
            problems.add(f"{where}: {c['spec']}: confining_stress_MPa {s3:g}: the test is not a confined series (its "
                         f"curve is {y} against {x})")
        else:
            match = [k for k, s in enumerate(confinements) if abs(s - s3) <= CONFINEMENT_MATCH * max(s, s3)]
            if not match:
                problems.add(f"{where}: {c['spec']}: confining_stress_MPa {s3:g}: the scene's series runs sigma_3 of "
                             f"{', '.join(f'{s:g}' for s in confinements)} MPa; add {s3:g} to its "
                             "loading.confining_stresses_MPa")
            else:
                c["piece"] = match[0]


def extend_description(description, curves):
    """describe's JSON with each curve point as an output: stresses stress-like (MPa), lateral strains pure
    numbers."""
    out = dict(description, outputs=dict(description["outputs"]))
    for c in curves:
        for q in c["points"]:
            out["outputs"][q["name"]] = (
                {"unit": "MPa", "stress_like": True, "si_factor": 1e6,
                 "description": f"measured curve's axial stress at axial strain {q['strain']:g}"}
                if q["kind"] == "stress" else
                {"unit": "1", "stress_like": False, "si_factor": 1.0,
                 "description": f"measured curve's lateral strain (compression positive) at axial strain {q['strain']:g}"})
    return out


def point_values(curve, curves):
    """The DEM run's values at every curve point, from its result's `curve` ({column: list}); a point the run has
    no curve for is left out."""
    out = {}
    for c in curves:
        prefix = f"{c['label']}." if c["label"] else ""
        strain = curve.get(prefix + "axial_strain") if curve else None
        stress = curve.get(prefix + "stress_MPa") if curve else None
        if not strain or not stress or len(strain) != len(stress):
            continue
        lateral = curve.get(prefix + "lateral_strain")
        if lateral is not None and len(lateral) != len(strain):
            lateral = None
        if c.get("confining_stress_MPa") is not None:
            piece = confined_piece(curve, prefix, c)
            if piece is None:
                continue
            strain, stress, lateral = piece
        # A strain-controlled test's strain only grows; should a recorded strain step back, the largest reached so
        # far stands, so that interpolation reads the curve in the order it was loaded.
        strain, stress = np.maximum.accumulate(np.asarray(strain, float)), np.asarray(stress, float)
        for q in c["points"]:
            if q["kind"] == "stress":
                out[q["name"]] = float(np.interp(q["strain"], strain, stress))
            elif lateral is not None:
                # The DEM counts a swelling specimen's lateral strain positive; the lab file compression positive.
                out[q["name"]] = -float(np.interp(q["strain"], strain, np.asarray(lateral, float)))
    return out


def confined_piece(curve, prefix, c):
    """(strains, sigma_1, lateral strains or None) of the piece of a confined series' DEM curve that the lab curve
    `c` is compared with (the series runs one specimen per confinement, each from zero strain, one after the other),
    sigma_1 the deviator plus the measured sigma_3; None when the run did not reach that piece."""
    strain = np.asarray(curve[prefix + "axial_strain"], float)
    # A piece starts where the strain falls back to well below the last (a step back within a piece is small).
    starts = [0] + [k for k in range(1, len(strain)) if strain[k] < 0.5 * strain[k - 1]]
    if c.get("piece") is None or c["piece"] >= len(starts):
        return None
    a = starts[c["piece"]]
    b = starts[c["piece"] + 1] if c["piece"] + 1 < len(starts) else len(strain)
    deviator = np.asarray(curve[prefix + "stress_MPa"], float)[a:b]
    measured = curve.get(prefix + "confining_stress_MPa")
    sigma_3 = (np.asarray(measured, float)[a:b] if measured is not None and len(measured) == len(strain)
               else np.full(b - a, c["confining_stress_MPa"]))
    lateral = curve.get(prefix + "lateral_strain")
    lateral = np.asarray(lateral, float)[a:b] if lateral is not None and len(lateral) == len(strain) else None
    return strain[a:b], deviator + sigma_3, lateral


def names(curves):
    return [q["name"] for c in curves for q in c["points"]]


VERDICTS = ("interval_inside_band", "mean_inside_band", "outside")  # best first, as demcal-verify ranks them


def add_to_verification(v, seed_curves, curves, targets, predicted, intervals, tolerance):
    """demcal-verify's result `v` (which ran the scalar targets) with the curve points added as demcal-verify
    would: each seed's values at the points joined to its `macro`, and a row per point (mean, SD, CV, 95 % interval
    of the mean by Student's t, relative error, passed, verdict); `passed` and `verdict` then cover them.
    seed_curves: {seed: the run's curve}. Returns v."""
    from .trust_region import t975
    for s in v["seeds"]:
        if s.get("status") == "ok":
            s["macro"].update(point_values(seed_curves.get(s["seed"]), curves))
    rank = VERDICTS.index(v.get("verdict", VERDICTS[0])) if v.get("verdict") in VERDICTS else 0
    for name in names(curves):
        target = targets[name]
        x = np.array([s["macro"][name] for s in v["seeds"] if s.get("status") == "ok"
                      and isinstance(s["macro"].get(name), (int, float)) and math.isfinite(s["macro"][name])])
        n = len(x)
        mean = float(x.mean()) if n else float("nan")
        sd = float(x.std(ddof=1)) if n > 1 else float("nan")
        half = t975(n - 1) * sd / math.sqrt(n) if n > 1 else float("nan")
        err = 100.0 * (mean - target) / abs(target)
        passed = n >= 2 and abs(err) <= 100.0 * tolerance
        band = (target - tolerance * abs(target), target + tolerance * abs(target))
        verdict = VERDICTS[2] if not passed else (
            VERDICTS[0] if band[0] <= mean - half and mean + half <= band[1] else VERDICTS[1])
        pi = intervals.get(name) if intervals else None
        v["outputs"][name] = {"target": target, "predicted": predicted.get(name), "predicted_interval_95": pi,
                              "mean": _number(mean), "sd": _number(sd), "cv_pct": _number(100.0 * sd / abs(mean)),
                              "ci95_low": _number(mean - half), "ci95_high": _number(mean + half),
                              "half_width_pct": _number(100.0 * half / abs(target)),
                              "relative_error_pct": _number(err), "runs": n, "passed": bool(passed),
                              "verdict": verdict}
        v["passed"] = bool(v["passed"] and passed)
        rank = max(rank, VERDICTS.index(verdict))
    if curves:
        v["verdict"] = VERDICTS[rank]
    return v


def seeds_wanted(v, curves, tolerance, max_seeds):
    """The seeds a verification should run so that every curve point's 95 % half-width can come within the
    tolerance (by its SD so far, the rule demcal-verify applies to the scalar targets), or None when they already do
    or max_seeds are run."""
    from .trust_region import t975
    run = len(v["seeds"])
    failed = sum(1 for s in v["seeds"] if s.get("status") != "ok")
    wanted = 0
    for name in names(curves):
        r = v["outputs"].get(name, {})
        if r.get("half_width_pct") is not None and r["half_width_pct"] <= 100.0 * tolerance:
            continue
        n, sd = r.get("runs", 0), r.get("sd")
        if n < 2 or sd is None:
            wanted = max(wanted, run + 1)
            continue
        needed = math.ceil((t975(n - 1) * sd / (tolerance * abs(r["target"]))) ** 2)
        wanted = max(wanted, needed + failed, run + 1)
    if wanted == 0 or run >= max_seeds:
        return None
    return min(wanted, max_seeds)


def _number(x):
    """As demcal-verify writes a number: null when it is not finite."""
    return float(x) if math.isfinite(x) else None


def add_finer_shifts(v, finer_curves, curves):
    """demcal-verify's result `v` at a finer resolution (its `finer` block, the curve rows already added to
    `outputs`) with each curve point's shift, as demcal-verify gives the scalar targets': 100 (finer mean - mean) /
    |mean|, the finer mean over the finer seeds' curves ({seed: curve}); None when no finer seed gave the point.
    Returns v."""
    if "finer" not in v:
        return v
    finer = [point_values(c, curves) for c in finer_curves.values() if c]
    shifts = v["finer"].setdefault("shift_pct", {})
    for name in names(curves):
        x = [f[name] for f in finer if name in f and math.isfinite(f[name])]
        mean = v["outputs"].get(name, {}).get("mean")
        shifts[name] = (100.0 * (float(np.mean(x)) - mean) / abs(mean)
                        if x and isinstance(mean, (int, float)) and mean != 0 else None)
    return v


def read_seed_curves(runs_folder, seeds, batch="runs.h5"):
    """{seed: the `curve` of runs_folder/BATCH.points/run1_seedS.json} for the seeds whose file is there (the
    folder demcal-verify ran them in: runs.h5, or finer_runs.h5 for its finer resolution)."""
    out = {}
    for s in seeds:
        r = read_point_result(os.path.join(runs_folder, batch), s)
        if r is not None:
            out[s] = r.get("curve")
    return out
