"""Sections of the report (Markdown lines): the screening, the stability checks, cost and accuracy. Numbers, names,
verdicts and paths are written as report_text.py says."""
import csv
import os

from .cost import study_cost
from .outputs import stem, tests_per_point
from .errors import load_json
from .plots import comparison_png
from .report_text import code, md, md_embedded, num, percent, shown_path, verdict_words, without_paths


def screening_section(study, out):
    """The screening's range analysis and ANOVA with their plots, then (when surfaces follow) the factors
    kept for each surface and how they were chosen."""
    if "screening" not in study:
        return []
    d = os.path.join(out, "screening")
    sc = study["screening"]
    with open(os.path.join(d, "screening.csv")) as f:
        rows = list(csv.DictReader(f))
    failed = [r for r in rows if r["status"] != "ok"]
    lines = ["## Screening", "",
             f"Orthogonal plan of {sc['design'].get('runs', '?')} runs over the whole space "
             f"({sc['design'].get('blank', 0)} blank column(s)), {sc.get('seeds', 1)} seed(s) per point: "
             f"{len(rows)} DEM runs" + (f" of {tests_per_point(study['scene'])} tests each "
                                          f"({len(rows) * tests_per_point(study['scene'])} test runs)"
                                          if tests_per_point(study["scene"]) > 1 else "")
             + f", {len(failed)} failed" + (" (left out of the analysis)" if failed else "") + ".", ""]
    # demcal-analyze's tables, their text escaped: an interaction A*B and the marks ** and * stay as written.
    with open(os.path.join(d, "range.md")) as f:
        lines += md_embedded(f.read().rstrip()).split("\n")
    for o in sc["outputs"]:
        if os.path.exists(os.path.join(d, f"main_effects_{stem(o)}.png")):
            lines += ["", f"![main effects on {md(o)}](screening/main_effects_{stem(o)}.png)"]
    with open(os.path.join(d, "anova.md")) as f:
        lines += [""] + md_embedded(f.read().rstrip()).split("\n")
    for o in sc["outputs"]:
        if os.path.exists(os.path.join(d, f"pareto_{stem(o)}.png")):
            lines += ["", f"![Pareto chart of F for {md(o)}](screening/pareto_{stem(o)}.png)"]
    if "surfaces" not in study:
        return lines + [""]
    lines += ["", "### Factors kept for the response surfaces", "",
              "| surface | outputs | factors | how chosen |", "|---|---|---|---|"]
    chosen_path = os.path.join(out, "config", "factors.json")
    chosen = load_json(chosen_path, "chosen factors") if os.path.exists(chosen_path) else {}
    for k, surface in enumerate(study.get("surfaces", []), start=1):
        c = chosen.get(f"g{k}")
        if c:
            how = (f"screening ANOVA, p < {num(c['threshold'])}: " +
                   ", ".join(f"{md(n)} (p = {num(c['p'][n])})" for n in c["factors"]) +
                   (f"; {md(c['note'])}" if c["note"] else ""))
            factors = c["factors"]
        else:
            how, factors = "listed in the study", surface["factors"]
        lines.append(f"| g{k} | {', '.join(md(o) for o in surface['outputs'])} | {', '.join(md(f) for f in factors)} | "
                     f"{how} |")
    return lines + [""]


def significance_section(out):
    """Per output, the factors the screening ANOVA finds significant, strongest (largest F) first."""
    anova = load_json(os.path.join(out, "screening", "anova.json"), "screening ANOVA")
    lines = ["## Significant factors", "",
             "| response | significant at p < 0.01 (\\*\\*) or p < 0.05 (\\*), by F |", "|---|---|"]
    for response, rows in anova.items():
        marks = [(row.get("F") or 0, md(name) + md(row["significance"])) for name, row in rows.items()
                 if name != "error" and row.get("significance")]
        lines.append(f"| {md(response)} | {', '.join(m for _, m in sorted(marks, reverse=True)) or 'none'} |")
    return lines + [""]


def stability_section(out):
    path = os.path.join(out, "stability.json")
    if not os.path.exists(path):
        return []
    st = load_json(path, "stability record")

    def said(text):  # a tool's message: its absolute paths made relative to the report's folder
        return md(without_paths(text, out))

    def errors(case):
        if "verified" in case:
            return ", ".join(f"{md(o)} {percent(e)} %" for o, e in case["verified"].items())
        return said(case.get("verify_message", "not verified"))

    lines = ["## Stability", "",
             "The same calibration repeated with other optimiser seeds, on the surrogates it ended with (the design is "
             "kept: another design seed would mean a new DEM batch), each solution verified in DEM:",
             "", "| seed | status | solution | verified relative errors | passed |", "|---|---|---|---|---|"]
    for c in st["seeds"]:
        x = ", ".join(f"{md(k)} {num(v)}" for k, v in c.get("x", {}).items())
        lines.append(f"| {c['seed']} | {said(c.get('status', c['message']))} | {x} | {errors(c)} | "
                     f"{'yes' if c.get('passed') else 'no'} |")
    e = st.get("edge")
    if e:
        lines += ["", f"A target near the edge: {md(e['output'])} = {num(e['targets'][e['output']])}, at "
                  f"{num(100 * e['fraction'])} % of its attainable range [{num(e['attainable'][0])}, "
                  f"{num(e['attainable'][1])}] (the other targets unchanged): inversion status "
                  f"**{md(e.get('status', '-'))}**"
                  + (f" ({said(e['message'])})" if e.get("message") else "") + "; verified: " + errors(e) + "."]
    lines += ["", "Deliberately small designs (the first runs of the first surface's design, refitted):", "",
              "| design | fit | predicted R^2 | inversion | verified relative errors |", "|---|---|---|---|---|"]
    for c in st["small_design"]:
        if "fit_exit" in c:
            lines.append(f"| {md(c['case'])} | refused: {said(c['message'])} | - | - | - |")
            continue
        r2 = ", ".join(f"{md(o)} {num(v)}" for o, v in c.get("r2_pred", {}).items())
        lines.append(f"| {md(c['case'])} | ok | {r2} | {said(c.get('status', c.get('message', '-')))} | {errors(c)} |")
    return lines + [""]


def comparison_section(study, out):
    rows = [study_cost(out)]
    missing = []
    for other in study.get("compare_with", []):
        d = os.path.join(os.path.dirname(out), os.path.splitext(os.path.basename(other))[0])
        if os.path.exists(os.path.join(d, "refined.json")):
            rows.append(study_cost(d))
        else:
            missing.append(other)
    minimised = rows[0]["minimised"]
    lines = minimised_table(rows) if minimised else accuracy_table(rows)
    against = f"the verified {md(minimised['output'])}" if minimised else "the verified error"
    if len(rows) > 1 and comparison_png(rows, os.path.join(out, "speed_accuracy.png")) is None:
        lines += ["", f"![DEM runs and wall time against {against}](speed_accuracy.png)"]
    if missing:
        lines += ["", "Not run yet (run `make study STUDY=...` on them for the comparison): " +
                  ", ".join(code(shown_path(m, out)) for m in missing) + "."]
    return lines + [""]


def wall_minutes(row):
    return num(row["wall_s"] / 60) if row["wall_s"] is not None else "not recorded"


def accuracy_table(rows):
    """Each study's cost and the largest relative error of its final verification."""
    lines = ["## Cost and accuracy", "",
             "DEM runs of the calibration (screening, designs, DEM in the loop, verification and refinement; not the "
             "stability checks), wall time of `make study` summed over its runs, and the largest relative error of the "
             "final verification:", "",
             "| study | strategy | DEM runs | wall time (min) | largest verified error (%) | passed |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {md(r['name'])} | {md(r['strategy'])} | {r['dem_runs']} | {wall_minutes(r)} | "
                     f"{num(r['max_error_pct'])} | {'yes' if r['passed'] else 'no'} |")
    return lines


def minimised_table(rows):
    """A minimisation's cost and what it reached: the verified mean of the output it drove down (each study on its
    own verification specimens: in the loop, those after the ones its optimiser saw)."""
    output = md(rows[0]["minimised"]["output"])
    lines = ["## Cost and result", "",
             f"DEM runs of the calibration (designs, DEM in the loop, verification and refinement), wall time of "
             f"`make study` summed over its runs, and the verified mean of {output} at its answer with its 95 % "
             "interval; \"agrees\" says whether that mean lies within the tolerance of what the optimiser saw there:", "",
             f"| study | strategy | DEM runs | wall time (min) | verified {output} | 95 % interval | reference / mean | "
             "agrees |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        m = r["minimised"]
        if m is None or m["output"] != rows[0]["minimised"]["output"]:
            continue  # a study of another kind has no place in this table
        lines.append(f"| {md(r['name'])} | {md(r['strategy'])} | {r['dem_runs']} | {wall_minutes(r)} | {num(m['mean'])} | "
                     f"{num(m['ci95'][0])} - {num(m['ci95'][1])} | {num(m['reference'] / m['mean'])} | "
                     f"{'yes' if r['passed'] else 'no'} |")
    return lines


def design_range_lines(study, out):
    """What the DEM gave over each surface's design (status ok): the attainable range as measured, before any
    target is judged against a surrogate's range."""
    lines = []
    for g, surface in enumerate(study.get("surfaces", []), start=1):
        path = os.path.join(out, f"g{g}", "responses.csv")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            rows = list(csv.DictReader(f))
        ok = [r for r in rows if r.get("status") == "ok"]
        for o in surface["outputs"]:
            values = [float(r[o]) for r in ok if r.get(o) not in (None, "")]
            if values:
                lines.append(f"| {md(o)} | {len(values)} of {len(rows)} | {num(min(values))} - {num(max(values))} | "
                             f"{num(study['targets'].get(o))} |")
    if not lines:
        return []
    return ["## What the DEM reaches over the design", "",
            "| output | design runs that ran | range in DEM | target |", "|---|---|---|---|"] + lines + [""]


def holdout_lines(study, out):
    """Each model's R^2 on the design points held out of every choice of its fit (holdout.py)."""
    lines = []
    for g, surface in enumerate(study.get("surfaces", []), start=1):
        if "holdout" not in surface:
            continue
        split = load_json(os.path.join(out, f"g{g}", "split.json"), "held-out split")
        for o in surface["outputs"]:
            s = load_json(os.path.join(out, "models", f"{stem(o)}_holdout.json"), "held-out score")
            lines.append(f"| {md(o)} | {split['train_points']} ({split['train_rows_ok']} ran) | "
                         f"{split['held_out']} ({s['rows']} ran) | {num(s['r2'])} | {num(s['rmse'])} |")
    if not lines:
        return []
    return ["", "Held out: design points chosen at random (seed 1) before any fit and used by none of its choices "
            "(training, early stopping, hidden size); the model's R^2 on them:", "",
            "| output | points fitted on | points held out | R^2 held out | RMSE held out |", "|---|---|---|---|---|"] + lines


def sobol_lines(study, out):
    """A network's Sobol indices over its domain: which parameters drive each output."""
    lines = []
    for surface in study.get("surfaces", []):
        for o in surface["outputs"]:
            path = os.path.join(out, "models", f"{stem(o)}_sobol.json")
            if not os.path.exists(path):
                continue
            inputs = load_json(path, "Sobol indices").get(o, {}).get("inputs", {})
            for name, i in sorted(inputs.items(), key=lambda item: -(item[1].get("ST") or 0)):
                lines.append(f"| {md(o)} | {md(name)} | {num(i.get('S1'))} ± {num(i.get('S1_conf'))} | "
                             f"{num(i.get('ST'))} ± {num(i.get('ST_conf'))} |")
    if not lines:
        return []
    return ["", "## Sensitivity", "", "Sobol indices of the network over its domain (`demcal-analyze sobol`; first "
            "order: the share of the output's variance the parameter explains alone; total: with its interactions; ± the "
            "bootstrap 95 % half-width):",
            "", "| output | parameter | first order | total |", "|---|---|---|---|"] + lines


def candidates_lines(out):
    """A search's candidates with what the DEM gave at each (candidates.py), the chosen one marked."""
    path = os.path.join(out, "candidates.json")
    if not os.path.exists(path):
        return []
    rows = load_json(path, "candidates")["candidates"]
    names = list(rows[0]["x"])
    outputs = list(rows[0]["outputs"])
    head = (["candidate", "cluster size"] + [md(n) for n in names] + [f"{md(o)} predicted" for o in outputs]
            + [f"{md(o)} verified (95 % interval)" for o in outputs] + ["seeds that ran", "verdict", "chosen"])
    lines = ["", "## Candidates verified in DEM", "",
             "The search's mean-shift cluster centres, largest cluster first, each run in DEM over the verification's "
             "seeds; the chosen one (an interval inside the band first, then the fewest failed seeds, then the smallest "
             "error) is the answer above.",
             "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [str(r["rank"]), str(r["cluster_size"])] + [num(r["x"][n]) for n in names]
        cells += [num(r["predicted"][o]) for o in outputs]
        cells += [f"{num(r['outputs'][o]['mean'])} ({num(r['outputs'][o]['ci95_low'])} - "
                  f"{num(r['outputs'][o]['ci95_high'])})" for o in outputs]
        cells += [f"{r['seeds_run'] - r['seeds_failed']} of {r['seeds_run']}", verdict_words(r["verdict"]),
                  "yes" if r["chosen"] else ""]
        lines.append("| " + " | ".join(cells) + " |")
    # The other outputs (the heap's flow time, say) are given once, at the final answer (report.py's
    # verification section), which after a refinement round is no longer the chosen candidate.
    return lines
