"""Shared by the study layer's tests: the package on sys.path, the source tree, the built executables."""
import json
import os
import subprocess
import sys

import pytest

# As the package does on import, but before any test module imports numpy: one BLAS thread, the same bits as a
# user's run, and no threads spinning against the DEM jobs of a parallel ctest (a search's MCMC ran 12x slower so).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PYTHON_DIR = os.path.join(REPO, "python")
sys.path.insert(0, PYTHON_DIR)


@pytest.fixture
def bin_dir():
    """The executables (BIN, default build/bin); tests that ask them skip when they are not built."""
    path = os.path.abspath(os.environ.get("BIN", os.path.join(REPO, "build", "bin")))
    if not os.access(os.path.join(path, "demcal-dem"), os.X_OK):
        pytest.skip(f"the executables are not built in {path} (make build, or set BIN)")
    return path


def load_script(name):
    """scripts/NAME.py as a module, for the functions a script keeps (its command line is tested by running it)."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(name, os.path.join(REPO, "scripts", f"{name}.py"))
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    return m


def run_study_layer(args, bin_dir="", cwd=REPO):
    """python -m demcal_study ARGS from the source tree, as plan.mk and run_study.sh run it."""
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR, BIN=bin_dir or os.path.join(REPO, "no-executables-needed"))
    return subprocess.run([sys.executable, "-m", "demcal_study"] + args, cwd=cwd, env=env,
                          capture_output=True, text=True)


def fake_describing_bin(folder, description, fail_on=None):
    """A BIN folder whose demcal-dem only answers `describe` with `description` (for the checks a command makes
    before it runs anything: no build needed); with `fail_on` {path: message}, describing that scene or space fails
    as the real one does (exit 2, one line)."""
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "description.json"), "w") as f:
        json.dump({"description": description, "fail_on": fail_on or {}}, f)
    program = os.path.join(folder, "demcal-dem")
    with open(program, "w") as f:
        f.write(f"""#!{sys.executable}
import json, os, sys
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "description.json")) as f:
    stored = json.load(f)
if sys.argv[1:2] != ["describe"]:
    sys.exit("demcal-dem: error: only describe is faked here")
for path, message in stored["fail_on"].items():
    if path in sys.argv:
        sys.exit("demcal-dem: error: " + message)
print(json.dumps(stored["description"]))
""")
    os.chmod(program, 0o755)
    return folder
