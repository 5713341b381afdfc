"""The report of a calibration (report.md and a self-contained report.html): the final parameter set first (one
copyable block, and parameters.json beside the report), then the problem as the search saw it (with an exact scale
factor, the scene's parameters as ratios to the scale parameter; without one, as they are), each round on specimen 1,
each verification, the solution with the local model's prediction interval beside the DEM's 95 % interval, each
test's curves and a biaxial series' Mohr circles over the final verification's runs, and the cost. Numbers, names,
verdicts and paths are written as report_text.py says."""
import os

from . import executables
from .calibrate_report_posterior import posterior_lines
from .errors import StudyError, load_json
from .files import write_target
from .mohr import mohr_section
from .plots import NO_CURVES, axes_of, curves_png
from .report_text import (code, md, num, parameter_block_lines, parameter_entries, percent, result_words, scene_text,
                          shown_path, verdict_words, verification_lines, without_paths, write_parameters)
from .to_html import to_html


def pct(value, spec):
    """A percentage for a progress line; "-" when demcal-verify had too few runs to give one."""
    return "-" if value is None else format(value, spec)


def correction_text(correction):
    """A correction's starting residuals and the change its step expects, in %; empty after the last verification."""
    if not correction:
        return ""

    def listed(values):
        return ", ".join(f"{md(n)} {percent(v)}" for n, v in values.items())
    text = f"from {listed(correction['from_pct'])}: model {listed(correction['model_change_pct'])}"
    if "secant_change_pct" in correction:
        text += f"; secant {listed(correction['secant_change_pct'])}"
    return text


def final_runs_lines(runs_dir, out, axes):
    """Each test's stress-strain curves over the final verification's runs (none when no run stored a curve, as an
    external program's), and the Mohr circles of a biaxial series among them (its mean peaks and envelope)."""
    lines = []
    h5, runs_csv = os.path.join(runs_dir, "runs.h5"), os.path.join(runs_dir, "runs.csv")
    if os.path.exists(h5):
        why = curves_png(h5, os.path.join(out, "verification_curves.png"), axes)
        if why != NO_CURVES:
            lines += ["", "## Curves of the final verification", "",
                      "![stress-strain curves of the final verification](verification_curves.png)" if why is None
                      else why]
    if os.path.exists(runs_csv):
        mohr = mohr_section(runs_csv, out)
        if mohr:
            lines += [""] + mohr
    return lines


def check_lines(k, check, out):
    """A test run at the solution but not calibrated on: its outputs over fresh seeds, curves and Mohr circles."""
    lines = ["", f"## Check {k}: {code(shown_path(check['scene'], out))} at the solution (not a target)", "",
             f"{check['ok']} of {check['runs']} runs ok on seeds {check['first_seed']}-"
             f"{check['first_seed'] + check['seeds'] - 1} ({check['note']}).", "",
             "| output | mean | SD | runs |", "|---|---|---|---|"]
    lines += [f"| {md(o)} | {num(s['mean'])} | {num(s['sd'])} | {s['n']} |" for o, s in sorted(check["outputs"].items())]
    folder = os.path.join(out, check["folder"])
    h5 = os.path.join(folder, "responses.h5")
    if os.path.exists(h5):
        png = f"check{k}_curves.png"
        why = curves_png(h5, os.path.join(out, png), axes_of(check["scene"]))
        if why != NO_CURVES:
            lines += ["", f"![curves of check {k}]({png})" if why is None else why]
    table = os.path.join(folder, "responses.csv")
    if os.path.exists(table):
        mohr = mohr_section(table, out, heading="###", png_prefix=f"check{k}_mohr")
        if mohr:
            lines += [""] + mohr
    return lines


def scene_parameters_of(config, solution):
    """{name: {"value", "unit"}} of the scene: stored with the solution; for a calibration stored before that, asked
    of demcal-dem (empty when it cannot answer: the block then lists the solution's values without units)."""
    if isinstance(solution.get("scene_parameters"), dict):
        return solution["scene_parameters"]
    try:
        described = executables.describe(config["scene"])["parameters"]
    except (StudyError, OSError, KeyError, TypeError):
        return {}
    return {n: {"value": q.get("value"), "unit": q.get("unit", "")} for n, q in described.items()}


def problem_lines(problem, out):
    """The problem as the search saw it: with an exact scale factor, in dimensionless form; without one (a scene that
    declares no exact scaling, a stress-like value held fixed, no stress-like parameter varied), as it is."""
    scale, target = problem.get("scale_parameter"), problem.get("scale_target")
    units = {c["name"]: c.get("unit") for c in problem["coordinates"]}
    if scale is not None:
        lines = ["## The problem in dimensionless form", ""]
        if target is not None:
            lines.append(f"Scale parameter {code(scale)} (reference {num(problem['scale_reference'])}), met through "
                         f"the scale target {code(target)} by an exact scale factor: every stress-like parameter times "
                         "s gives every stress output times s (docs/explanation/calibration_method.md).")
        else:
            lines.append(f"Scale parameter {code(scale)} held at its reference {num(problem['scale_reference'])}: no "
                         "target is a stress, so no scale factor applies; the other stress-like parameters are searched "
                         "as ratios to it.")
    else:
        lines = ["## The problem", ""]
        if not problem.get("exact_scaling", True):
            lines.append("The scene does not declare exact scaling (an external program's outputs need not scale with "
                         "its stress-like parameters): every parameter is searched at its own value, in its own unit, "
                         "and every target is met as it is; no scale factor.")
        elif problem.get("held_stress_like"):
            lines.append(", ".join(code(n) for n in problem["held_stress_like"]) + " held fixed and stress-like: the "
                         "scaling is then not exact, so every parameter is searched at its own value and every target "
                         "is met as it is; no scale factor.")
        else:
            lines.append("No stress-like parameter varies: every parameter is searched at its own value; no scale "
                         "factor.")
    lines += ["", "| target | value |", "|---|---|"]
    lines += [f"| {md(k)} | {num(v)} |" for k, v in problem["dimensionless_targets"].items()]
    lines += ["", "| coordinate | kind | unit | low | high | reference | coding |", "|---|---|---|---|---|---|---|"]
    lines += [f"| {md(c['name'])} | {c['kind']} | {md(units.get(c['name']) or '-')} | {num(c['low'])} | "
              f"{num(c['high'])} | {num(c['reference'])} | {'log' if c['log_scale'] else 'linear'} |"
              for c in problem["coordinates"]]
    if problem["fixed"]:
        lines += ["", "Fixed: " + ", ".join(f"{md(k)} = {num(v)}" for k, v in sorted(problem["fixed"].items())) + "."]
    return lines


def report(out):
    config = load_json(os.path.join(out, "calibration.json"), "calibration")
    solution = load_json(os.path.join(out, "solution.json"), "calibration solution")
    problem = solution["problem"]
    scaled = problem.get("scale_parameter") is not None
    scene_parameters = scene_parameters_of(config, solution)
    units = {n: q.get("unit", "") for n, q in scene_parameters.items()}
    entries = []
    if "x" in solution:
        entries = parameter_entries(scene_parameters, solution["x"], fixed=problem["fixed"],
                                    tied=[t["name"] for t in problem.get("tied", [])])
        write_parameters(out, entries, config["scene"], solution["status"])
    elif os.path.exists(os.path.join(out, "parameters.json")):
        os.remove(os.path.join(out, "parameters.json"))  # no solution any more: no parameter set beside the report
    minutes = solution.get("wall_s_total", solution["wall_s"]) / 60
    lines = [f"# Calibration {md(os.path.basename(out.rstrip('/')))}", "",
             f"Scene {scene_text(config['scene'], out)}" +
             (f", space {code(shown_path(config['space'], out))}" if config.get("space") else " over its physical bounds")
             + f"; tolerance {num(100 * config['tolerance'])} %, budget {config['budget']} DEM runs.", "",
             f"**Result: {result_words(solution['status'])}** ({md(without_paths(solution['why'], out))}); exit code "
             f"{solution['exit_code']}; {solution['dem_runs']} DEM runs, {num(minutes)} min"
             + (f" over {len(solution['wall_s_parts'])} invocations" if len(solution.get("wall_s_parts", [])) > 1
                else "") + ".", ""]
    block = parameter_block_lines(entries, config["scene"], out)
    if entries and solution["status"] != "met":
        block.insert(2, f"The targets are not met ({result_words(solution['status'])}): this is the last point the "
                        "calibration verified or modelled, not a calibrated set.")
        block.insert(3, "")
    lines += block
    study_json = os.path.join(out, "config", "study.json")  # a "trust_region" study's calibration
    if os.path.exists(study_json):
        study = load_json(study_json, "study")
        lines += [f"Study {code(study['name'])}: {md(study.get('description', ''))}", ""]
    lines += problem_lines(problem, out)
    names = problem["residuals"]
    point_rounds = [r for r in solution["rounds"] if "bayes" not in r]  # the Bayesian search's: its own section
    lines += [] if not point_rounds else ["", "## Rounds on specimen 1 (common random numbers)", "",
              ("Errors of the dimensionless targets after the exact scale factor, in %." if scaled else
               "Relative errors of the targets, in %.") +
              (f" Rounds b2, b3, ...: the scale factor {md(problem['scale_target'])} wanted left the bounds, so the "
               f"search went on with the scale at its bound and {md(problem['scale_target'])} as one more residual "
               "(log)." if solution.get("bounded_scale") else ""), "",
              "| round | centre | candidate | predicted | accepted | radius after | runs |", "|---|---|---|---|---|---|---|"]

    def errs(values):
        return "-" if values is None else ", ".join(f"{md(n)} {percent(x)}" for n, x in zip(names, values))
    for r in point_rounds:
        lines.append(f"| {r['round']} | {errs(r['centre_residuals_pct'])} | {errs(r['candidate_residuals_pct'])} | "
                     f"{errs(r['predicted_residuals_pct'])} | {'yes' if r['accepted'] else 'no'} | {num(r['radius'])} | "
                     f"{r['runs']} |")
    if solution["verifications"]:
        lines += ["", "## Verifications on fresh seeds", "",
                  "| verification | seeds | errors % (95 % half-width) | verdict | met | runs after | the correction after it "
                  "expects (specimen 1's model; secant: measured between two verifications) |",
                  "|---|---|---|---|---|---|---|"]
        for v in solution["verifications"]:
            e = ", ".join(f"{md(o)} {percent(v['errors_pct'][o])} (+-{num(v['half_width_pct'][o])})"
                          for o in v["errors_pct"])
            lines.append(f"| {v['round']} | {v['first_seed']}-{v['first_seed'] + v['seeds'] - 1} | {e} | "
                         f"{verdict_words(v['verdict'])} | {'yes' if v['met'] else 'no'} | {v['runs']} | "
                         f"{correction_text(v.get('correction'))} |")
    if "x" in solution:
        lines += ["", "## Solution", ""]
        if scaled:
            lines += [f"Scale factor {num(solution['scale_factor'])} (the bounds allow "
                      f"{num(solution['scale_interval'][0])} to {num(solution['scale_interval'][1])}).", "",
                      "| parameter | value | unit | ratio to the scale parameter |", "|---|---|---|---|"]
        else:
            lines += ["| parameter | value | unit |", "|---|---|---|"]
        for k, v in sorted(solution["x"].items()):
            row = f"| {md(k)} | {num(v)} | {md(units.get(k) or '-')} |"
            if scaled:
                ratio = solution.get("ratios", {}).get(k)
                row += f" {num(ratio) if ratio is not None else ''} |"
            lines.append(row)
        lines += ["", "| output | target | local model (seed-1 model + offset) | its 95 % prediction interval (one specimen) |",
                  "|---|---|---|---|"]
        for o, value in sorted(solution["predicted"].items()):
            lo, hi = solution["prediction_interval_95"][o]
            lines.append(f"| {md(o)} | {num(solution['targets'][o])} | {num(value)} | {num(lo)} to {num(hi)} |")
    lines += posterior_lines(out, solution)
    last = solution["verifications"][-1]["folder"] if solution["verifications"] else None
    if last and os.path.exists(os.path.join(out, last, "verification.json")):
        verification = load_json(os.path.join(out, last, "verification.json"), "verification")
        lines += ["", "## The final verification (DEM mean over fresh seeds, 95 % interval)", ""]
        lines += verification_lines(verification, out)
    if last:
        lines += final_runs_lines(os.path.join(out, last, "runs"), out, axes_of(config["scene"]))
    for k, c in enumerate(solution.get("checks", [])):
        lines += check_lines(k + 1, c, out)
    if solution.get("reachable"):
        lines += ["", "## What specimen 1 reached", "", "Lowest and highest error of each "
                  + ("dimensionless " if scaled else "") + "target over every point run, in %.", "",
                  "| target | lowest | highest |", "|---|---|---|"]
        lines += [f"| {md(n)} | {percent(r['lowest_error_pct'])} | {percent(r['highest_error_pct'])} |"
                  for n, r in solution["reachable"].items()]
    text = "\n".join(lines) + "\n"
    write_target(os.path.join(out, "report.md"), text)
    write_target(os.path.join(out, "report.html"), to_html(text, out))
