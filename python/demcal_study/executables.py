"""What the executables say about themselves: a scene's parameters and outputs (demcal-dem describe), the design
kinds and their factor limits (demcal-doe --list-kinds), the inversion algorithms and objectives (demcal-invert
--list-algorithms). They are the one source of truth; the study layer keeps no copy."""
import json
import subprocess

from . import commands
from .errors import StudyError, fail

_ASKED = {}


class ToolError(StudyError):
    """The executable ran and refused (its own error line is the message)."""


def ask(program, *args):
    """The JSON `program` (in $BIN, default build/bin) prints for `args`; asked once per command line."""
    cmd = [commands.from_environment().program(program)] + list(args)
    key = tuple(cmd)
    if key not in _ASKED:
        try:
            done = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as e:
            fail(f"cannot run {cmd[0]} ({e.strerror}): build first (make build) or set BIN")
        if done.returncode != 0:
            raise ToolError(done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"{' '.join(cmd)} failed")
        try:
            _ASKED[key] = json.loads(done.stdout)
        except ValueError:
            fail(f"{' '.join(cmd)} did not print JSON: rebuild it (make build)")
    return _ASKED[key]


def describe(scene_path, space_path=None):
    """What the scene has (parameters, outputs, ...); with a space, demcal-dem also checks that it narrows the
    scene (and names the field when it does not)."""
    return ask("demcal-dem", "describe", "--scene", scene_path, *(["--space", space_path] if space_path else []))


def registries():
    """demcal-dem's registries: lab tests and contact models, each model's keys and its names in other programs."""
    return ask("demcal-dem", "describe", "--registries")


def design_kinds():
    """Every design kind of demcal-doe: {kind: {title, min_factors, max_factors (null: no limit), options, ...}}."""
    return ask("demcal-doe", "--list-kinds")["kinds"]


def inversion_choices():
    """{"algorithms": [...], "objectives": [...]} of demcal-invert."""
    return ask("demcal-invert", "--list-algorithms")
