"""What refinement and stability refit a surface on: its factors (listed, or chosen by the screening) and
the DEM rows of its design with the verification runs added."""
import csv
import os

from .errors import load_json


def factors_of(out, g, surface):
    """A surface's factors: listed in the study, or chosen by the screening (config/factors.json)."""
    if surface["factors"] != "auto":
        return surface["factors"]
    return load_json(os.path.join(out, "config", "factors.json"), "chosen factors")[f"g{g}"]["factors"]


def design_data(out, g):
    """The DEM rows surface g is fitted on: its whole design, or the points not held out (holdout.py)."""
    train = os.path.join(out, f"g{g}", "train.csv")
    return train if os.path.exists(train) else os.path.join(out, f"g{g}", "responses.csv")


def merged_rows(paths):
    """Rows of several DEM response CSVs (different column orders), status ok only; `paths` are
    (csv, run offset) so runs of different batches keep distinct numbers."""
    rows = []
    for path, run_offset in paths:
        with open(path) as f:
            for row in csv.DictReader(f):
                if row.get("status") != "ok":
                    continue
                row["run"] = str(int(row["run"]) + run_offset + int(row.get("seed", 1)))
                rows.append(row)
    return rows
