#!/usr/bin/python3
"""Runs the corpus of bad inputs (cases.json): every case must exit with code 2 and print exactly one non-empty
line on stderr that names the bad file (and holds the case's `message`, if any), or, for a command that reports
several problems at once, the case's `lines` lines (one per problem). No crash, no HDF5 error stack.

    /usr/bin/python3 tests/bad_inputs/run_bad_inputs.py BIN_DIR SRC_DIR [--sanitized] [ID_PREFIX ...]

Prints one line per failing case and a summary; exits 1 if any case fails. --sanitized: binaries built with
-DDEMCAL_SANITIZE=ON (a sanitizer report fails the case like any other extra line; the timeout is four times longer).
ID_PREFIX: run only the cases whose id starts with one of them (e.g. scene/ model/gabp).
"""
import json
import os
import subprocess
import sys
import tempfile

TIMEOUT_S = 60


STUDY = ["/usr/bin/python3", "-m", "demcal_study"]  # the study layer (PYTHONPATH=SRC/python)


def expand(command, bin_dir, src, tmp):
    out = []
    for arg in command:
        if arg == "{study}":
            out += STUDY
        else:
            out.append(arg.replace("{bin}", bin_dir).replace("{src}", src).replace("{tmp}", tmp))
    return out


def problems(case, code, lines):
    """What is wrong with one run: an empty list when the case passes."""
    found = []
    if code != 2:
        found.append(f"exit {code}" + (" (killed by signal %d)" % -code if code < 0 else "") + ", expected 2")
    if any(b"HDF5-DIAG" in line for line in lines):
        found.append("HDF5 error stack on stderr")
    if any(b"Sanitizer" in line or b"runtime error:" in line for line in lines):
        found.append("sanitizer report")
    expected = case.get("lines", 1)
    if len(lines) != expected:
        found.append(f"{len(lines)} stderr lines, expected {expected}")
    elif case["file"].encode() not in lines[0]:
        found.append(f"the message does not name {case['file']}")
    elif "message" in case and case["message"].encode() not in b"\n".join(lines):
        found.append(f"the message lacks \"{case['message']}\"")
    return found


def main():
    args = [a for a in sys.argv[1:] if a and a != "--sanitized"]  # "" : an empty CMake generator expression
    sanitized = "--sanitized" in sys.argv[1:]
    if len(args) < 2:
        sys.exit(__doc__)
    bin_dir, src, prefixes = os.path.abspath(args[0]), os.path.abspath(args[1]), args[2:]
    with open(os.path.join(src, "tests", "bad_inputs", "cases.json")) as f:
        cases = [c for c in json.load(f)["cases"] if not prefixes or c["id"].startswith(tuple(prefixes))]
    env = dict(os.environ, BIN=bin_dir, PYTHONPATH=os.path.join(src, "python"))
    timeout = TIMEOUT_S * (4 if sanitized else 1)
    failed = 0
    for case in cases:
        with tempfile.TemporaryDirectory(prefix="bad_input.") as tmp:
            command = expand(case["command"], bin_dir, src, tmp)
            try:
                done = subprocess.run(command, cwd=src, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.PIPE, timeout=timeout)
                lines = [line for line in done.stderr.split(b"\n") if line.strip()]
                found = problems(case, done.returncode, lines)
            except subprocess.TimeoutExpired as e:
                lines = [line for line in (e.stderr or b"").split(b"\n") if line.strip()]
                found = [f"timeout after {timeout} s"]
            except OSError as e:
                lines, found = [], [f"cannot run {command[0]} ({e.strerror})"]
        if found:
            failed += 1
            shown = " | ".join(line.decode(errors="replace") for line in lines[:6]) + (" | ..." if len(lines) > 6 else "")
            print(f"FAIL {case['id']}: {'; '.join(found)}; stderr: {shown or '(empty)'}")
    print(f"{len(cases) - failed} of {len(cases)} bad-input cases passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
