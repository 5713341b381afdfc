"""design: a design config (config/design_g1.json, config/screening_design.json) into a CSV in natural
units by demcal-doe, with the study's fixed values added as columns, so each DEM run gets every parameter."""
import csv
import os
import subprocess

from . import commands
from .errors import fail, load_json


def design(config_path, out_csv):
    cfg = load_json(config_path, "design config")
    os.makedirs(os.path.dirname(out_csv) or ".", exist_ok=True)
    raw = out_csv + ".tmp.csv"
    # With the scene: a design that would leave a parameter's physical bounds is refused, naming the fix.
    if subprocess.run(commands.doe(commands.from_environment(), cfg["design"], cfg["space"], raw,
                                   scene=cfg.get("scene"))).returncode != 0:
        fail(f"demcal-doe failed for {config_path}")
    with open(raw) as f:
        rows = list(csv.reader(f))
    with open(out_csv + ".tmp2", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(rows[0] + list(cfg["fixed"]))
        for row in rows[1:]:
            w.writerow(row + [repr(float(v)) for v in cfg["fixed"].values()])
    os.replace(out_csv + ".tmp2", out_csv)
    os.remove(raw)
