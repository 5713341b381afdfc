"""The report of a calibration (report.md and a self-contained report.html): the problem in both forms (the scene's
parameters and the dimensionless ratios), each round on specimen 1, each verification, the solution with the local
model's prediction interval beside the DEM's 95 % interval, each test's curves and a biaxial series' Mohr circles over
the final verification's runs, and the cost."""
import os

from .errors import load_json
from .files import write_target
from .mohr import mohr_section
from .plots import curves_png
from .to_html import to_html


def pct(value, spec):
    """A percentage for a table or progress line; "-" when demcal-verify had too few runs to give one."""
    return "-" if value is None else format(value, spec)


def _g(x):
    return "-" if x is None else f"{x:.4g}"


def correction_text(correction):
    """A correction's starting residuals and the change its step expects, in %; empty after the last verification."""
    if not correction:
        return ""

    def listed(values):
        return ", ".join(f"{n} {v:+.1f}" for n, v in values.items())
    text = f"from {listed(correction['from_pct'])}: model {listed(correction['model_change_pct'])}"
    if "secant_change_pct" in correction:
        text += f"; secant {listed(correction['secant_change_pct'])}"
    return text


def final_runs_lines(runs_dir, out):
    """Each test's stress-strain curves over the final verification's runs, and the Mohr circles of a biaxial series
    among them (its mean peaks and envelope)."""
    lines = []
    h5, runs_csv = os.path.join(runs_dir, "runs.h5"), os.path.join(runs_dir, "runs.csv")
    if os.path.exists(h5):
        why = curves_png(h5, os.path.join(out, "verification_curves.png"))
        lines += ["", "## Curves of the final verification", "",
                  "![stress-strain curves of the final verification](verification_curves.png)" if why is None else why]
    if os.path.exists(runs_csv):
        mohr = mohr_section(runs_csv, out)
        if mohr:
            lines += [""] + mohr
    return lines


def check_lines(k, check, out):
    """A test run at the solution but not calibrated on: its outputs over fresh seeds, curves and Mohr circles."""
    lines = ["", f"## Check {k}: `{check['scene']}` at the solution (not a target)", "",
             f"{check['ok']} of {check['runs']} runs ok on seeds {check['first_seed']}-"
             f"{check['first_seed'] + check['seeds'] - 1} ({check['note']}).", "",
             "| output | mean | SD | runs |", "|---|---|---|---|"]
    lines += [f"| {o} | {_g(s['mean'])} | {_g(s['sd'])} | {s['n']} |" for o, s in sorted(check["outputs"].items())]
    folder = os.path.join(out, check["folder"])
    h5 = os.path.join(folder, "responses.h5")
    if os.path.exists(h5):
        png = f"check{k}_curves.png"
        why = curves_png(h5, os.path.join(out, png))
        lines += ["", f"![curves of check {k}]({png})" if why is None else why]
    table = os.path.join(folder, "responses.csv")
    if os.path.exists(table):
        mohr = mohr_section(table, out, heading="###", png_prefix=f"check{k}_mohr")
        if mohr:
            lines += [""] + mohr
    return lines


def report(out):
    config = load_json(os.path.join(out, "calibration.json"), "calibration")
    solution = load_json(os.path.join(out, "solution.json"), "calibration solution")
    problem = solution["problem"]
    lines = [f"# Calibration {os.path.basename(out.rstrip('/'))}", "",
             f"Scene `{config['scene']}`" + (f", space `{config['space']}`" if config.get("space") else
                                              " over its physical bounds") +
             f"; tolerance {100 * config['tolerance']:g} %, budget {config['budget']} DEM runs.", "",
             f"**Result: {solution['status']}** ({solution['why']}); exit code {solution['exit_code']}; "
             f"{solution['dem_runs']} DEM runs, {solution.get('wall_s_total', solution['wall_s']) / 60:.1f} min"
             + (f" over {len(solution['wall_s_parts'])} invocations" if len(solution.get("wall_s_parts", [])) > 1
                else "") + ".", ""]
    study_json = os.path.join(out, "config", "study.json")  # a "trust_region" study's calibration
    if os.path.exists(study_json):
        study = load_json(study_json, "study")
        lines += [f"Study `{study['name']}`: {study.get('description', '')}", ""]
    lines += ["## The problem in dimensionless form", "",
              f"Scale parameter `{problem['scale_parameter']}` (reference {_g(problem['scale_reference'])}), met "
              f"through the scale target `{problem['scale_target']}` by an exact scale factor: every stress-like "
              "parameter times s gives every stress output times s (docs/calibration.md).", "",
              "| target | value |", "|---|---|"]
    lines += [f"| {k} | {_g(v)} |" for k, v in problem["dimensionless_targets"].items()]
    lines += ["", "| coordinate | kind | low | high | reference | coding |", "|---|---|---|---|---|---|"]
    lines += [f"| {c['name']} | {c['kind']} | {_g(c['low'])} | {_g(c['high'])} | {_g(c['reference'])} | "
              f"{'log' if c['log_scale'] else 'linear'} |" for c in problem["coordinates"]]
    if problem["fixed"]:
        lines += ["", "Fixed: " + ", ".join(f"{k} = {_g(v)}" for k, v in sorted(problem["fixed"].items())) + "."]
    names = problem["residuals"]
    lines += ["", "## Rounds on specimen 1 (common random numbers)", "",
              "Errors of the dimensionless targets after the exact scale factor, in %." +
              (f" Rounds b2, b3, ...: the scale factor {problem['scale_target']} wanted left the bounds, so the search "
               f"went on with the scale at its bound and {problem['scale_target']} as one more residual (log)."
               if solution.get("bounded_scale") else ""), "",
              "| round | centre | candidate | predicted | accepted | radius after | runs |", "|---|---|---|---|---|---|---|"]

    def errs(values):
        return "-" if values is None else ", ".join(f"{n} {x:+.1f}" for n, x in zip(names, values))
    for r in solution["rounds"]:
        lines.append(f"| {r['round']} | {errs(r['centre_residuals_pct'])} | {errs(r['candidate_residuals_pct'])} | "
                     f"{errs(r['predicted_residuals_pct'])} | {'yes' if r['accepted'] else 'no'} | {r['radius']:.3g} | "
                     f"{r['runs']} |")
    if solution["verifications"]:
        lines += ["", "## Verifications on fresh seeds", "",
                  "| verification | seeds | errors % (95 % half-width) | verdict | met | runs after | the correction after it "
                  "expects (specimen 1's model; secant: measured between two verifications) |",
                  "|---|---|---|---|---|---|---|"]
        for v in solution["verifications"]:
            e = ", ".join(f"{o} {pct(v['errors_pct'][o], '+.2f')} (+-{pct(v['half_width_pct'][o], '.2f')})"
                          for o in v["errors_pct"])
            lines.append(f"| {v['round']} | {v['first_seed']}-{v['first_seed'] + v['seeds'] - 1} | {e} | {v['verdict']} "
                         f"| {'yes' if v['met'] else 'no'} | {v['runs']} | {correction_text(v.get('correction'))} |")
    if "x" in solution:
        lines += ["", "## Solution", "", f"Scale factor {solution['scale_factor']:.5g} (the bounds allow "
                  f"{solution['scale_interval'][0]:.4g} to {solution['scale_interval'][1]:.4g}).", "",
                  "| parameter | value | ratio to the scale parameter |", "|---|---|---|"]
        for k, v in sorted(solution["x"].items()):
            ratio = solution["ratios"].get(k)
            lines.append(f"| {k} | {_g(v)} | {_g(ratio) if ratio is not None else ''} |")
        lines += ["", "| output | target | local model (seed-1 model + offset) | its 95 % prediction interval (one specimen) |",
                  "|---|---|---|---|"]
        for o, value in sorted(solution["predicted"].items()):
            lo, hi = solution["prediction_interval_95"][o]
            lines.append(f"| {o} | {_g(solution['targets'][o])} | {_g(value)} | {_g(lo)} to {_g(hi)} |")
    last = solution["verifications"][-1]["folder"] if solution["verifications"] else None
    if last and os.path.exists(os.path.join(out, last, "verification.md")):
        with open(os.path.join(out, last, "verification.md")) as f:
            lines += ["", "## The final verification (DEM mean over fresh seeds, 95 % interval)", "", f.read().strip()]
    if last:
        lines += final_runs_lines(os.path.join(out, last, "runs"), out)
    for k, c in enumerate(solution.get("checks", [])):
        lines += check_lines(k + 1, c, out)
    if solution.get("reachable"):
        lines += ["", "## What specimen 1 reached", "", "Lowest and highest error of each dimensionless target over "
                  "every point run, in %.", "", "| target | lowest | highest |", "|---|---|---|"]
        lines += [f"| {n} | {r['lowest_error_pct']:+.1f} | {r['highest_error_pct']:+.1f} |"
                  for n, r in solution["reachable"].items()]
    md = "\n".join(lines) + "\n"
    write_target(os.path.join(out, "report.md"), md)
    write_target(os.path.join(out, "report.html"), to_html(md, out))
