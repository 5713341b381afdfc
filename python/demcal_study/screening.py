"""screen: range analysis and ANOVA of a screening batch (demcal-analyze), with main-effects and Pareto plots."""
import csv
import os
import subprocess

from . import commands
from .errors import fail, load_json


def screen(out):
    """The screening stage of a study: analyze_screening on its batch, into OUT_DIR/screening/."""
    cfg = load_json(os.path.join(out, "config", "screening.json"), "screening config")
    d = os.path.join(out, "screening")
    factors = [p["name"] for p in load_json(cfg["space"], "space")["parameters"]]
    analyze_screening(os.path.join(d, "design.csv"), os.path.join(d, "responses.csv"), factors, cfg["outputs"], d,
                      all_outputs=cfg.get("all_outputs", False))


def analyze_screening(design_csv, responses_csv, factors, outputs, folder, all_outputs=False):
    """Range analysis and ANOVA of a screening batch, with main-effects and Pareto plots, into
    folder/: screening.csv (design, blank columns joined from the design by run, responses; with
    all_outputs every other DEM output after them), range and anova as md and json. Returns the
    (run, status) of the points that failed."""
    tools = commands.from_environment()
    with open(design_csv) as f:
        design_rows = {row["run"]: row for row in csv.DictReader(f)}
    blanks = [c for c in next(iter(design_rows.values())) if c.startswith("blank")]
    table = os.path.join(folder, "screening.csv")
    failed = []
    with open(responses_csv) as f, open(table + ".tmp", "w", newline="") as o:
        reader = csv.DictReader(f)
        skip = set(factors) | set(outputs) | {"run", "seed", "status"}
        columns = list(outputs) + ([c for c in reader.fieldnames if c not in skip] if all_outputs else [])
        writer = csv.writer(o)
        writer.writerow(["run", "seed", "status"] + factors + blanks + columns)
        for row in reader:
            if row["status"] != "ok":
                failed.append((row["run"], row["status"]))
            writer.writerow([row["run"], row["seed"], row["status"]] + [row[c] for c in factors] +
                            [design_rows[row["run"]][c] for c in blanks] + [row.get(x, "nan") for x in columns])
    os.replace(table + ".tmp", table)
    # Blank columns enter as terms and the error is the residual (Minitab's GLM), unless the plan is
    # saturated (3 levels: 2 degrees of freedom a column): then the first blank column is the error.
    error = None
    if blanks and len(design_rows) - 1 - 2 * (len(factors) + len(blanks)) <= 0:
        error = f"column:{blanks[0]}"
    for kind in ("range", "anova"):
        for fmt in ("md", "json"):
            cmd = commands.analyze(tools, kind, table, factors + blanks, outputs, fmt,
                                   os.path.join(folder, f"{kind}.{fmt}"), error=error if kind == "anova" else None)
            if subprocess.run(cmd).returncode != 0:
                fail(f"demcal-analyze {kind} failed on {table}")
    subprocess.run(commands.plot(tools, "main-effects", os.path.join(folder, "range.json"),
                                 os.path.join(folder, "main_effects.png")), stdout=subprocess.DEVNULL)
    subprocess.run(commands.plot(tools, "pareto", os.path.join(folder, "anova.json"), os.path.join(folder, "pareto.png")),
                   stdout=subprocess.DEVNULL)
    return failed
