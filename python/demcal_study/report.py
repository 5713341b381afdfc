"""report: OUT_DIR/report.md and a self-contained report.html (figures inlined): the calibration from targets
to verification, refinement, stability and cost, its final parameter set first (one copyable block, and
parameters.json beside the report); or, for a screening alone, the screening and its cost. Numbers, names, verdicts
and paths are written as report_text.py says."""
import os

from . import executables, strategy
from .candidates import other_outputs
from .cost import count_rows, make_wall_s
from .outputs import stem, tests_per_point
from .errors import StudyError, load_json
from .files import write_if_changed
from .plots import convergence_png, curves_png, axes_of
from .report_text import (code, md, num, parameter_block_lines, parameter_entries, percent, scene_text, shown_path,
                          verification_lines as verification_table, without_paths, write_parameters)
from .sections import (candidates_lines, comparison_section, design_range_lines, holdout_lines, screening_section,
                       significance_section, sobol_lines, stability_section)
from .to_html import to_html


def report(out):
    study = load_json(os.path.join(out, "config", "study.json"), "study")
    if strategy.trust_region(study):
        # The calibration wrote its own report into the study's folder; write it again (run_study.sh calls this
        # once the wall time of make is known, which the calibration records itself).
        from .calibrate_report import report as calibration_report_of
        calibration_report_of(out)
        print(os.path.join(out, "report.md"))
        print(os.path.join(out, "report.html"))
        return
    lines = screening_report(study, out) if strategy.screening_only(study) else calibration_report(study, out)
    text = "\n".join(lines) + "\n"
    write_if_changed(os.path.join(out, "report.md"), text)
    write_if_changed(os.path.join(out, "report.html"), to_html(text, out))
    print(os.path.join(out, "report.md"))
    print(os.path.join(out, "report.html"))


def space_lines(space):
    lines = ["| varied parameter | low | high | unit |", "|---|---|---|---|"]
    lines += [f"| {md(p['name'])} | {num(p['low'])} | {num(p['high'])} | {md(p.get('unit') or '-')} |"
              for p in space["parameters"]]
    fixed = space.get("fixed", {})
    return lines + ["", "Fixed: " + (", ".join(f"{md(k)} = {num(v)}" for k, v in fixed.items()) or "none") + ".", ""]


def screening_report(study, out):
    space = load_json(os.path.join(out, "config", "screening_space.json"), "space")
    lines = [f"# Screening report: {md(study['name'])}", "", md(study.get("description", "")), "",
             f"Scene {scene_text(study['scene'], out)}, space {code(shown_path(study['space'], out))}.", "",
             "## Parameter space", ""]
    lines += space_lines(space) + screening_section(study, out) + significance_section(out)
    wall = make_wall_s(out)
    runs = count_rows(os.path.join(out, "screening", "responses.csv")) * tests_per_point(study["scene"])
    lines += ["## Cost", "",
              f"{runs} DEM runs; wall time of `make study` summed over its runs: "
              + (f"{num(wall / 60)} min" if wall is not None else "not recorded") + ".", ""]
    return lines


def calibration_report(study, out):
    refined = load_json(os.path.join(out, "refined.json"), "refinement record")
    final = refined["final"]
    first = load_json(os.path.join(out, "verification.json"), "verification")
    solution = load_json(final["solution"], "solution")
    # A minimisation has references (each output is divided by its own), not targets to meet.
    minimise = solution.get("objective_kind") == "minimise"
    goal = "reference (minimised over)" if minimise else "target"
    space = load_json(os.path.join(out, "config", "space_inversion.json"), "space")
    final_verification = load_json(final["verification"], "verification")
    lines = [f"# Calibration report: {md(study['name'])}", "", md(study.get("description", "")), "",
             f"Scene {scene_text(study['scene'], out)}, space {code(shown_path(study['space'], out))}.", ""]
    lines += final_parameter_lines(study, space, solution, final_verification, out)
    lines += ["## " + ("Output minimised" if minimise else "Targets") + " and parameter space", "",
              f"| output | {goal} |", "|---|---|"]
    lines += [f"| {md(k)} | {num(v)} |" for k, v in study["targets"].items()]
    lines += [""] + space_lines(space)
    lines += screening_section(study, out)
    loop = strategy.in_the_loop(study)
    if not loop:
        lines += design_range_lines(study, out)
    lines += loop_lines(study, solution, out) if loop else surrogate_lines(study, solution, out)
    if refined["rounds"]:
        lines.insert(len(lines) - 3, f"(The solution of the last refinement round, {len(refined['rounds'])}; its surrogates "
                                     "were refitted with the verification runs added.)")
        lines.insert(len(lines) - 3, "")
    for name, value in solution["x"].items():
        s = solution.get("spread", {}).get(name)
        spread = f"{num(s['min'])} - {num(s['max'])}" if s else ""
        ident = ("yes" if s["identified"] else "no") if s else ""
        lines.append(f"| {md(name)} | {num(value)} | {spread} | {ident} |")
    source = "DEM run at the solution" if loop else "surrogate at the solution"
    lines += ["", f"| output | {goal} | {source} | attainable range |", "|---|---|---|---|"]
    for o, t in solution["targets"].items():
        a = solution["attainable"].get(o)
        attainable = f"{num(a['min'])} - {num(a['max'])}" if a else "not assessed"
        lines.append(f"| {md(o)} | {num(t)} | {num(solution['predicted'].get(o))} | {attainable} |")
    if solution.get("unidentified"):
        lines += ["", "Not identified by these targets (restarts that meet them spread over more than half the range): "
                  + ", ".join(md(n) for n in solution["unidentified"]) + "."]
    lines += verification_lines(refined, first, out, axes_of(study["scene"])) + candidates_lines(out)
    lines += [""] + stability_section(out) + comparison_section(study, out)
    return lines


def loop_lines(study, solution, out):
    """The DEM in the loop: its runs, its convergence, then the head of the inversion table."""
    dem = solution.get("dem", {})
    lines = ["## DEM in the loop", "",
             f"No surrogate: every evaluation of {solution['algorithm']} was a DEM run of {code(shown_path(study['scene'], out))} "
             f"({dem.get('seeds_per_point', 1)} specimen(s) per point, {dem.get('jobs', 1)} at once). "
             f"{solution['evaluations']} evaluations asked for {dem.get('points', 0)} distinct points: "
             f"**{dem.get('runs', 0)} DEM runs** ({dem.get('runs_failed', 0)} failed"
             + (f"; each ran {tests_per_point(study['scene'])} tests, "
                f"{dem.get('runs', 0) * tests_per_point(study['scene'])} test runs" if tests_per_point(study['scene']) > 1 else "")
             + "), "
             f"{num(dem.get('dem_wall_s', 0) / 60)} min of DEM wall time"
             + (f"; {dem['runs_reused']} of them were made by an interrupted earlier attempt and reused"
                if dem.get("runs_reused") else "") + ". The verification below uses other specimens (seeds "
             f"{dem.get('seeds_per_point', 1) + 1} onwards) than the one(s) the optimiser saw.", ""]
    chosen = os.path.join(out, "config", "seeds.json")
    if os.path.exists(chosen):
        c = load_json(chosen, "specimens per point")
        lines += [f"The {c['seeds_per_point']} specimens per point were chosen from the scatter of the targets over "
                  f"{c.get('scatter_seeds', 0)} specimens at the reference point (CV "
                  + ", ".join(f"{md(o)} {num(v)} %" for o, v in sorted(c["cv_pct"].items()))
                  + f"): the smallest number whose standard error is at most a third of the tolerance "
                  f"({num(c.get('allowed_pct', 0))} %)"
                  + (f"; capped at {c['seeds_per_point']}, the standard error is {num(c['standard_error_pct'])} %"
                     if c.get("capped") else "") + ".", ""]
    history = os.path.join(out, "inversion_history.csv")
    if os.path.exists(history) and convergence_png(history, os.path.join(out, "convergence.png"),
                                                   solution.get("objective_kind", "")) is None:
        lines += ["![best objective against DEM evaluations](convergence.png)", ""]
    return lines + ["## Inversion", "",
                    f"{solution['algorithm']}, objective {solution['objective_kind']}, {len(solution['restarts'])} run(s), "
                    f"status **{md(solution['status'])}**" + (f": {md(without_paths(solution.get('reason', ''), out))}" if solution['status'] != 'ok' else "")
                    + ".", "", "| parameter | value | spread over restarts (min - max) | identified |", "|---|---|---|---|"]


def surrogate_lines(study, solution, out):
    """The surrogates' fit statistics and plots, then the head of the inversion table."""
    lines = ["## Surrogates", "",
             "| output | model | runs | R^2 | adjusted R^2 | predicted R^2 |", "|---|---|---|---|---|---|"]
    figures = []
    for surface in study["surfaces"]:
        for o in surface["outputs"]:
            m = load_json(os.path.join(out, "models", f"{stem(o)}.json"), "model")
            if m["kind"] == "gabp":
                # Training R^2 and the R^2 of the early-stopping split (rows it never trained on, though they
                # chose when to stop and the hidden size; the held-out points below chose nothing).
                t, v = m.get("training", {}), m.get("validation", {})
                lines.append(f"| {md(o)} | gabp | {t.get('rows', 0) + v.get('rows', 0)} | {num(t.get('r2', {}).get(o))} | "
                             f"- | {num(v.get('r2', {}).get(o))} (early-stopping split, {v.get('rows', 0)} rows) |")
                continue
            r = m["responses"][0] if "responses" in m else {}
            lines.append(f"| {md(o)} | {m['kind']} | {r.get('runs', '')} | {num(m.get('r2'))} | "
                         f"{num(m.get('r2_adj'))} | {num(m.get('r2_pred'))} |")
            figures.append(f"![fit of {md(o)}](models/{stem(o)}_fit.png)")
    lines += holdout_lines(study, out) + sobol_lines(study, out)
    return lines + [""] + figures + ["", "## Inversion", "",
                    f"{solution['algorithm']}, objective {solution['objective_kind']}, {len(solution['restarts'])} restarts, "
                    f"{solution['evaluations']} evaluations, status **{md(solution['status'])}**"
                    + (f": {md(without_paths(solution.get('reason', ''), out))}" if solution['status'] != 'ok' else "") + ".", "",
                    f"| parameter | value | spread over the {solution.get('spread_basis', 'restarts')} (min - max) | "
                    "identified |", "|---|---|---|---|"]


def verification_lines(refined, first, out, axes):
    """The first verification, the refinement rounds, the final verification table and its curves."""
    final = refined["final"]
    lines = ["", "## Verification in DEM", ""]
    if refined["rounds"]:
        lines += ["The first verification " + ("passed" if first["passed"] else "failed") + ": " +
                  ", ".join(f"{md(o)} {percent(r['relative_error_pct'])} %" for o, r in first["outputs"].items()) +
                  ". Refinement (its DEM runs added to the data, surrogates refitted, inverted and verified again):", "",
                  "| round | data points | DEM runs | relative errors | passed |", "|---|---|---|---|---|"]
        for r in refined["rounds"]:
            errors = ", ".join(f"{md(o)} {percent(e)} %" for o, e in r["relative_error_pct"].items())
            lines.append(f"| {r['round']} | {r['data_points']} | {r['dem_runs']} | {errors} | {'yes' if r['passed'] else 'no'} |")
        lines += ["", "The final round:", ""]
    verification = load_json(final["verification"], "verification")
    lines += verification_table(verification, out)
    others = other_outputs(final["runs"], set(verification["outputs"]))
    if others:
        lines += ["", "Other outputs at the answer (mean and SD over the final verification's seeds that ran): " + ", ".join(
            f"{md(n)} {num(v['mean'])} (SD {num(v['sd'])})" for n, v in others.items()) + "."]
    runs = os.path.join(os.path.dirname(final["runs"]), "runs.h5")
    if os.path.exists(runs) and curves_png(runs, os.path.join(out, "verification_curves.png"), axes) is None:
        lines += ["", "![stress-strain curves](verification_curves.png)"]
    return lines


def scene_parameters(scene):
    """{name: {"value", "unit"}} of the scene as demcal-dem describes it; empty when it cannot."""
    try:
        described = executables.describe(scene)["parameters"]
    except (StudyError, OSError, KeyError, TypeError):
        return {}
    return {n: {"value": q.get("value"), "unit": q.get("unit", "")} for n, q in described.items()}


def final_parameter_lines(study, space, solution, verification, out):
    """The study's final parameter set at the top of its report (and parameters.json beside it): the solution's
    values over the fixed ones and the scene's."""
    # As the runs had them (values.fixed_values): the study's fixed value, else the space's reference, else the
    # scene's value (filled in below); the space's fixed values over all.
    fixed = {p["name"]: p["reference"] for p in space.get("parameters", []) if p.get("reference") is not None}
    if isinstance(study.get("fixed"), dict):
        fixed.update(study["fixed"])
    fixed.update(space.get("fixed", {}))
    for name in solution.get("x", {}):  # calibrated, not fixed
        fixed.pop(name, None)
    known = scene_parameters(study["scene"])
    for p in space.get("parameters", []):  # a unit the scene could not tell (no executables): the space's
        known.setdefault(p["name"], {"unit": p.get("unit", "")})
    values = dict(fixed)
    values.update(solution.get("x", {}))
    entries = parameter_entries(known, values, fixed=fixed)
    status = "verified" if verification.get("passed") else "not verified: outside the tolerance"
    if entries:
        write_parameters(out, entries, study["scene"], status)
    block = parameter_block_lines(entries, study["scene"], out)
    if entries and not verification.get("passed"):
        block[2:2] = ["The final verification failed: this is the answer the study ended with, not a verified set.",
                      ""]
    return block
