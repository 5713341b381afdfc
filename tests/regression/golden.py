#!/usr/bin/python3
"""Bit-identical check: the default UCS, the concrete scene, a Brazilian disc, a short wave strip and a small study give
exactly the numbers stored in tests/regression/golden/ (every float compared by its bits; timings left out).

    golden.py BIN_DIR SRC_DIR [CASE ...]            compare (exit 1 naming each difference)
    golden.py BIN_DIR SRC_DIR --update [CASE ...]   rewrite the stored numbers (a change of physics, said so
                                                    in its commit)

A refactor must keep this passing unchanged. A change that is meant to move numbers updates the golden files
in the same commit and says why.
"""
import csv
import hashlib
import json
import os
import subprocess
import sys
import tempfile

BIN_DIR = ""  # the executables under test (the study layer asks them about scenes, designs, algorithms)

# What depends on the machine's speed, not on the physics.
VOLATILE = {"wall_s", "test_wall_s", "particle_steps_per_s", "dem_wall_s", "elapsed_s", "wall_time_s",
            "threads", "thread_cuts"}  # threads, thread_cuts: how the run was spread over the machine, never what it gives


def strip(value):
    """The value without its timings (recursively)."""
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


def bits(value):
    """Floats as their shortest round-trip text, so equal text means equal bits."""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, dict):
        return {k: bits(v) for k, v in value.items()}
    if isinstance(value, list):
        return [bits(v) for v in value]
    return value


def csv_digest(path):
    """Rows of a CSV without its timing columns, columns in name order (their order is layout, not numbers):
    a hash and the row count (the whole table is too long to keep)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    keep = sorted((k for k, name in enumerate(rows[0]) if name not in VOLATILE), key=lambda k: rows[0][k])
    text = "\n".join(",".join(row[k] for k in keep) for row in rows)
    return {"rows": len(rows) - 1, "columns": [rows[0][k] for k in keep],
            "sha256": hashlib.sha256(text.encode()).hexdigest()}


def run(command, cwd):
    # The study layer is the package SRC/python/demcal_study.
    env = dict(os.environ, BIN=BIN_DIR, PYTHONPATH=os.path.join(cwd, "python"))
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"golden.py: {' '.join(command)} failed ({done.returncode}):\n{done.stdout}{done.stderr}")


def dem_run(bin_dir, src, work, scene, seed):
    out, curve = os.path.join(work, "result.json"), os.path.join(work, "curve.csv")
    run([os.path.join(bin_dir, "demcal-dem"), "run", "--scene", scene, "--seed", str(seed), "--cache",
         os.path.join(work, "cache"), "--out", out, "--curve", curve, "--quiet"], src)
    with open(out) as f:
        result = strip(json.load(f))
    return {"result": result, "curve": csv_digest(curve)}


def study(bin_dir, src, work, path):
    folder = os.path.join(work, "study")
    run(["/usr/bin/python3", "-m", "demcal_study", "plan", path, folder], src)
    run(["make", "--no-print-directory", "-f", os.path.join(folder, "plan.mk"), f"BIN={bin_dir}",
         f"CACHE={os.path.join(work, 'cache')}", "JOBS=2", "all"], src)
    with open(os.path.join(folder, "solution.json")) as f:
        solution = json.load(f)
    with open(os.path.join(folder, "verification.json")) as f:
        verification = json.load(f)
    return {"responses": csv_digest(os.path.join(folder, "g1", "responses.csv")),
            "solution": strip({k: solution.get(k) for k in ("status", "x", "predicted", "objective", "evaluations")}),
            "verification": strip(verification.get("outputs"))}


CASES = {
    "ucs_rock_pb": lambda b, s, w: dem_run(b, s, w, "data/scenes/ucs_rock_pb.json", 1),
    "ucs_concrete": lambda b, s, w: dem_run(b, s, w, "data/scenes/ucs_concrete.json", 1),
    "brazilian_rock_cb": lambda b, s, w: dem_run(b, s, w, "tests/data/brazilian_small.json", 2),
    "wave_strip": lambda b, s, w: dem_run(b, s, w, "tests/data/wave_strip_small.json", 1),
    "study_golden": lambda b, s, w: study(b, s, w, "tests/regression/study_golden.json"),
}


def differences(stored, now, where=""):
    if isinstance(stored, dict) and isinstance(now, dict):
        out = []
        for key in sorted(set(stored) | set(now)):
            if key not in now:
                out.append(f"{where}{key}: missing now")
            elif key not in stored:
                out.append(f"{where}{key}: new ({now[key]})")
            else:
                out += differences(stored[key], now[key], f"{where}{key}.")
        return out
    if stored != now:
        return [f"{where[:-1]}: stored {stored}, now {now}"]
    return []


def main():
    args = sys.argv[1:]
    update = "--update" in args
    args = [a for a in args if a != "--update"]
    if len(args) < 2:
        sys.exit(__doc__)
    global BIN_DIR
    bin_dir, src = os.path.abspath(args[0]), os.path.abspath(args[1])
    BIN_DIR = bin_dir
    names = args[2:] or list(CASES)
    failed = False
    for name in names:
        if name not in CASES:
            sys.exit(f"golden.py: unknown case {name} (cases: {', '.join(CASES)})")
        with tempfile.TemporaryDirectory() as work:
            now = bits(CASES[name](bin_dir, src, work))
        path = os.path.join(src, "tests", "regression", "golden", name + ".json")
        if update:
            with open(path, "w") as f:
                json.dump(now, f, indent=1, sort_keys=True)
                f.write("\n")
            print(f"{name}: stored")
            continue
        with open(path) as f:
            stored = json.load(f)
        diff = differences(stored, now)
        if diff:
            failed = True
            print(f"{name}: {len(diff)} difference(s) from {os.path.relpath(path, src)}:")
            for line in diff[:30]:
                print("  " + line)
        else:
            print(f"{name}: bit-identical")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
