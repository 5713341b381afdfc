"""Shared by the study layer's tests: the package on sys.path, the source tree, the built executables."""
import os
import subprocess
import sys

import pytest

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


def run_study_layer(args, bin_dir="", cwd=REPO):
    """python -m demcal_study ARGS from the source tree, as plan.mk and run_study.sh run it."""
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR, BIN=bin_dir or os.path.join(REPO, "no-executables-needed"))
    return subprocess.run([sys.executable, "-m", "demcal_study"] + args, cwd=cwd, env=env,
                          capture_output=True, text=True)
