"""How every report writes what it shows, in one place: numbers to four significant digits (one function, `num`),
names escaped for Markdown, verdicts and results in words, paths relative to the report's folder, and the final
parameter set as one copyable block with parameters.json beside the report."""
import json
import math
import os
import re

DIGITS = 4  # significant digits of every number a report shows (percentages included)


def num(value, digits=DIGITS, signed=False):
    """A number as every report shows it: `digits` significant digits (an exponent only below 1e-4 or from 10^digits
    on, as %g), a sign when `signed`; counts (ints) as they are; "-" for a missing or non-finite value."""
    if value is None or isinstance(value, bool):
        return "-"
    if isinstance(value, int):
        return f"{value:+d}" if signed else str(value)
    try:
        x = float(value)
    except (TypeError, ValueError):
        return "-"
    if not math.isfinite(x):
        return "-"
    text = format(x, f"{'+' if signed else ''}.{digits}g")
    if text.lstrip("+-") == "0":  # -0 from a tiny negative
        return "+0" if signed else "0"
    return text


def percent(value):
    """A relative error in % (signed), as num but no finer than 0.01 %: "+2.43", "-14.2", "+118.9", "+0"."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        value = round(float(value), 2)
    return num(value, signed=True)


# -- Markdown -------------------------------------------------------------------------------------------------------
_ALWAYS = re.compile(r"([\\`*\[\]|])")
# An underscore starts or ends emphasis only at a word's edge (sigma_u_MPa stays as it is, _x_ does not).
_EDGE_UNDERSCORE = re.compile(r"(?<![A-Za-z0-9])_|_(?![A-Za-z0-9])")
_TAG = re.compile(r"<(?=[A-Za-z/!?])")


def md(text):
    """Text from a name or a tool (a parameter, an interaction term a*b, a reason) as Markdown shows it literally:
    *, `, [, ], |, \\ and an underscore at a word's edge escaped, and no HTML tag."""
    text = _ALWAYS.sub(r"\\\1", str(text))
    text = _EDGE_UNDERSCORE.sub(r"\\_", text)
    return _TAG.sub("&lt;", text)


def md_embedded(text):
    """Markdown written by an executable (demcal-analyze's tables): its headings and tables kept, the text of each
    line and cell escaped (an interaction A*B, the marks ** and *)."""
    lines = []
    for line in text.split("\n"):
        stripped = line.strip()
        if stripped.startswith("|"):
            if re.fullmatch(r"\|(\s*:?-+:?\s*\|)+", stripped):
                lines.append(line)
            else:
                cells = stripped.strip("|").split("|")
                lines.append("| " + " | ".join(md(c.strip()) for c in cells) + " |")
        elif stripped.startswith("#"):
            hashes, _, rest = stripped.partition(" ")
            lines.append(f"{hashes} {md(rest)}")
        else:
            lines.append(md(line))
    return "\n".join(lines)


def code(text):
    """A name or path as inline code (shown literally; only a backtick inside needs a longer fence)."""
    text = str(text)
    fence = "``" if "`" in text else "`"
    return f"{fence}{text}{fence}" if fence == "`" else f"{fence} {text} {fence}"


# -- words --------------------------------------------------------------------------------------------------------
VERDICTS = {
    "interval_inside_band": "the mean and its whole 95 % interval lie within the tolerance",
    "mean_inside_band": "the mean lies within the tolerance, but its 95 % interval reaches beyond it",
    "outside": "the mean lies outside the tolerance, or fewer than two seeds ran",
}


def verdict_words(verdict):
    """demcal-verify's verdict as a sentence (without its full stop)."""
    return VERDICTS.get(verdict, str(verdict).replace("_", " ") if verdict else "-")


RESULTS = {
    "met": "met",
    "noisy": "not met: the means are within the tolerance, but the specimens scatter too much",
    "budget": "not met: the budget of DEM runs is spent",
    "unreachable": "not met: a target lies outside what the scene reaches",
    "failed": "failed: no DEM point ran",
}


def result_words(status):
    return RESULTS.get(status, str(status).replace("_", " "))


# -- paths -----------------------------------------------------------------------------------------------------------
def shown_path(path, report_dir):
    """A file path as a report shows it: relative to the report's folder (never absolute, never from wherever the
    report was made)."""
    if not path:
        return path
    return os.path.relpath(os.path.abspath(str(path)), os.path.abspath(report_dir))


_ABSOLUTE = re.compile(r"(?<![\w.~/-])(/[^\s'\"`,;:()\[\]]+)")


def without_paths(text, report_dir):
    """Free text from a tool (a failed seed's reason, why a calibration stopped) with every absolute path in it
    made relative to the report's folder."""
    return _ABSOLUTE.sub(lambda m: shown_path(m.group(1), report_dir), str(text))


# -- the final parameter set -----------------------------------------------------------------------------------------
HOW = {"calibrated": "calibrated", "fixed": "fixed", "tied": "tied to another", "scene": "the scene's value"}


def parameter_entries(scene_parameters, values, fixed=(), tied=()):
    """[(name, value, unit, how)] of every parameter: `scene_parameters` {name: {"value", "unit"}} (may be empty when
    the scene could not be described), `values` (the solution's, fixed ones included) over them; `how` says which
    were calibrated, fixed, tied or left at the scene's value."""
    fixed, tied = set(fixed), set(tied)
    out = []
    for name in sorted(set(scene_parameters) | set(values)):
        entry = scene_parameters.get(name, {})
        value = values.get(name, entry.get("value"))
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            continue
        how = "fixed" if name in fixed else "tied" if name in tied else "calibrated" if name in values else "scene"
        out.append((name, float(value), entry.get("unit", ""), how))
    return out


def parameters_json(entries, scene, status, note=""):
    """parameters.json: name -> value with its unit (and how it was set), the scene it belongs to (relative to the
    file's folder); `python -m demcal_study export --solution parameters.json` reads it."""
    return {"description": "the final parameter set" + (f" ({note})" if note else "") +
            "; export it with python -m demcal_study export --solution parameters.json --scene SCENE --to "
            "pfc|yade|liggghts", "scene": scene, "status": status,
            "parameters": {n: {"value": v, "unit": u, "set": HOW[h]} for n, v, u, h in entries}}


def write_parameters(out, entries, scene, status, note=""):
    from .files import write_target
    path = os.path.join(out, "parameters.json")
    write_target(path, json.dumps(parameters_json(entries, shown_path(scene, out), status, note), indent=1) + "\n")
    return path


PROGRAM_OF = {"pfc": "PFC2D", "pfc3d": "PFC3D"}


def scene_dimension(scene):
    """2 or 3: the engine of the scene's test (a test list: 3 when every test is 3D)."""
    from . import executables
    d = executables.describe(scene)
    if d.get("test") == "list":
        dims = {t.get("dimension") for t in d.get("tests", [])}
        return 3 if dims == {3} else 2
    return d.get("dimension") or 2


def parameter_block_lines(entries, scene, out, heading="## Final parameter set"):
    """The report's first section: every parameter in one copyable block (exact values, as the DEM ran them), and how
    to export it."""
    if not entries:
        return [heading, "", "No parameter set: no DEM point gave one.", ""]
    width = max(len(n) for n, _, _, _ in entries)
    block = [f"{n:<{width}} = {v!r}  # {(u + ', ') if u and u != '1' else ''}{HOW[h]}" for n, v, u, h in entries]
    # The export command, run from this report's folder: the study layer's package and the scene relative to it,
    # and Debian's interpreter (the one with the study layer's packages).
    package = os.path.relpath(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), os.path.abspath(out))
    scene_shown = shown_path(scene, out)
    pfc = "pfc3d" if scene_dimension(scene) == 3 else "pfc"
    return [heading, "",
            "Every parameter of the scene (fixed ones included), exact as the DEM ran them; also in "
            "[parameters.json](parameters.json) beside this report (name, value, unit).", "",
            "```text"] + block + ["```", "",
                                  f"Export it to {PROGRAM_OF[pfc]}, YADE or LIGGGHTS from this report's folder: "
                                  f"`PYTHONPATH={package} /usr/bin/python3 -m demcal_study export --solution "
                                  f"parameters.json --scene {scene_shown} --to {pfc}` (or `--to yade`, "
                                  "`--to liggghts`).", ""]


# -- the scene and the verification, as a report shows them --------------------------------------------------------
def scene_text(scene, out):
    """A scene as a report names it: its path relative to the report's folder, and for a test list its tests."""
    shown = code(shown_path(scene, out))
    try:
        with open(scene) as f:
            tests = json.load(f).get("tests")
    except (OSError, ValueError, AttributeError):
        return shown
    if not isinstance(tests, list) or not all(isinstance(t, str) for t in tests):
        return shown
    base = os.path.dirname(os.path.abspath(scene))
    return f"{shown} (tests " + ", ".join(code(shown_path(os.path.join(base, t), out)) for t in tests) + ")"


def interval_text(low, high):
    return f"{num(low)} to {num(high)}" if low is not None and high is not None else "-"


def verification_lines(v, out):
    """demcal-verify's verification.json as the reports show it: per output the target, the prediction, the DEM mean
    over fresh seeds with its 95 % interval and the verdict in words; the seeds that failed and why; a minimisation's
    references; the finer-resolution check."""
    rows = v.get("outputs", {})
    tolerance = v.get("tolerance")
    intervals = any(r.get("predicted_interval_95") for r in rows.values())
    head = (["output", "target", "predicted"] + (["its 95 % prediction interval"] if intervals else []) +
            ["DEM mean", "SD", "CV %", "95 % interval of the mean", "half-width %", "relative error %",
             f"within {num(100 * tolerance)} %" if isinstance(tolerance, (int, float)) else "within the tolerance",
             "verdict"])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for o, r in rows.items():
        cells = [md(o), num(r.get("target")), num(r.get("predicted"))]
        if intervals:
            pi = r.get("predicted_interval_95")
            cells.append(interval_text(*pi) if pi else "-")
        cells += [num(r.get("mean")), num(r.get("sd")), num(r.get("cv_pct")),
                  interval_text(r.get("ci95_low"), r.get("ci95_high")), num(r.get("half_width_pct")),
                  percent(r.get("relative_error_pct")), "yes" if r.get("passed") else "no",
                  verdict_words(r.get("verdict"))]
        lines.append("| " + " | ".join(cells) + " |")
    seeds = v.get("seeds", [])
    text = f"{sum(1 for s in seeds if s.get('status') == 'ok')} of {len(seeds)} DEM seeds ran" + "".join(
        f"; seed {s.get('seed')} failed: {md(without_paths(s.get('reason', ''), out))}"
        for s in seeds if s.get("status") != "ok")
    text += (". Verification " + ("passed" if v.get("passed") else "failed") +
             f": {verdict_words(v.get('verdict'))}" if "verdict" in v else "")
    if v.get("seeds_stop_reason"):
        text += f"; no more seeds: {md(v['seeds_stop_reason'])}"
    lines += ["", text + "."]
    references = v.get("references") if v.get("objective_kind") == "minimise" else None
    if references:
        lines += ["", "Minimised: the targets above are the values the optimiser saw at its answer; against the "
                  "references it minimised over:", "",
                  "| output | reference | verified mean | mean / reference | reference / mean |", "|---|---|---|---|---|"]
        for o, reference in references.items():
            mean = rows.get(o, {}).get("mean")
            ratio = mean / reference if isinstance(mean, (int, float)) and reference else None
            inverse = reference / mean if isinstance(mean, (int, float)) and mean else None
            lines.append(f"| {md(o)} | {num(reference)} | {num(mean)} | {num(ratio)} | {num(inverse)} |")
    finer = v.get("finer")
    if isinstance(finer, dict):
        fine_rows = finer.get("outputs", {})
        lines += ["", f"At a finer resolution (disk radii / {num(finer.get('factor'))}, "
                  f"{len(finer.get('seeds', []))} seeds):", "",
                  "| output | target | mean | finer mean | its 95 % interval | shift % | relative error % | within |",
                  "|---|---|---|---|---|---|---|---|"]
        for o, r in rows.items():
            f = fine_rows.get(o, {})
            lines.append(f"| {md(o)} | {num(r.get('target'))} | {num(r.get('mean'))} | {num(f.get('mean'))} | "
                         f"{interval_text(f.get('ci95_low'), f.get('ci95_high'))} | "
                         f"{percent(finer.get('shift_pct', {}).get(o))} | {percent(f.get('relative_error_pct'))} | "
                         f"{'yes' if f.get('passed') else 'no'} |")
    return lines
