"""The result file demcal-dem batch keeps for every point and seed beside its responses, OUT.points/runR_seedS.json:
what a resumed batch reuses, with what the responses table does not hold (the curve, the failure's reason, the
specimen's figures)."""
import json
import os
import sys


def point_result_path(batch_out, seed, run=1):
    """The result file of design point `run` on `seed` of the batch that wrote `batch_out` (its responses.h5)."""
    return os.path.join(f"{batch_out}.points", f"run{run}_seed{seed}.json")


def read_point_result(batch_out, seed, run=1):
    """That point's stored result, or None when it is missing or not JSON (not run yet, or cut off)."""
    try:
        with open(point_result_path(batch_out, seed, run)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def stored_point_results(batch_out, seeds, who):
    """Design point 1's stored result on every one of `seeds`, for a script that needs them all: a missing one
    stops `who` with one line naming the file."""
    results = []
    for seed in seeds:
        r = read_point_result(batch_out, seed)
        if r is None:
            sys.exit(f"{who}: {point_result_path(batch_out, seed)} is missing or not JSON (its batch stopped early); "
                     "rerun to resume")
        results.append(r)
    return results
