"""commands: each builder's plan.mk recipe is its direct argument list once make has expanded its variables;
BIN, JOBS and CACHE are honoured by every builder and by the stages that run the tools (design included)."""
import json
import os
import re
import shlex
import stat

import pytest

from conftest import REPO, run_study_layer
from demcal_study import commands, executables
from demcal_study.commands import IN_MAKE, Tools, for_make
from demcal_study.design import design

TOOLS = Tools(bin="/opt/demcal/bin", jobs="7", cache="/var/cache/dem", python="/usr/bin/python3")
MAKE_VARIABLES = {"BIN": TOOLS.bin, "JOBS": TOOLS.jobs, "CACHE": TOOLS.cache, "PY": TOOLS.python}
INVERSION = {"algorithm": "ga", "objective": "sum-rel", "restarts": 5, "polish": True, "seed": 3,
             "extra": ["--set", "population=300", "--budget", "800"]}
VERIFICATION = {"seeds": 5, "tolerance": 0.05, "first_seed": 2}


def expand(recipe, variables):
    """What make hands the shell for a recipe line: `$$` made `$`, every other `$` a variable reference ($(X),
    ${X} or one character, $< $@ $1 ...), which an unset variable expands to nothing."""
    def one(m):
        return "$" if m.group(0) == "$$" else variables.get(m.group(1) or m.group(2) or m.group(3), "")
    return re.sub(r"\$\$|\$\(([^)]*)\)|\$\{([^}]*)\}|\$(.)", one, recipe)


# Each builder called as plan() calls it (make variables) and as a stage calls it (real paths).
BUILDERS = {
    "doe": lambda t, d: commands.doe(t, {"kind": "ccd", "center": 2, "alpha": "face"}, f"{d}/config/space g1.json",
                                     f"{d}/g1/design.csv"),
    "dem_batch": lambda t, d: commands.dem_batch(t, "data/scenes/ucs_rock_pb.json", f"{d}/g1/design.csv",
                                                 f"{d}/g1/responses.h5", f"{d}/g1/responses.partial.csv", 3),
    "fit": lambda t, d: commands.fit(t, "quadratic", f"{d}/g1/responses.csv", ["a", "b"], "sigma_u_MPa",
                                     f"{d}/config/space_g1.json", f"{d}/models/s.json", report=f"{d}/models/s.md",
                                     residuals=f"{d}/models/s_residuals.csv"),
    "invert": lambda t, d: commands.invert(t, INVERSION, {"sigma_u_MPa": 25, "nu": 0.2}, f"{d}/config/space.json",
                                           f"{d}/solution.json", models=[f"{d}/models/s.json"],
                                           history=f"{d}/history.csv"),
    "invert_dem": lambda t, d: commands.invert(t, dict(INVERSION, polish=False), {"E_GPa": 14.3},
                                               f"{d}/config/space.json", f"{d}/solution.json",
                                               dem={"scene": "data/scenes/ucs_rock_cb.json", "seeds": 2}),
    "verify": lambda t, d: commands.verify(t, f"{d}/solution.json", "data/scenes/ucs_rock_pb.json",
                                           f"{d}/config/space.json", VERIFICATION, f"{d}/verification",
                                           f"{d}/verification.json", md=f"{d}/verification.md",
                                           csv=f"{d}/verification.csv"),
    "analyze": lambda t, d: commands.analyze(t, "anova", f"{d}/screening/screening.csv", ["a", "blank1"], ["nu"],
                                             "json", f"{d}/screening/anova.json", error="column:blank1"),
    "plot": lambda t, d: commands.plot(t, "fit", f"{d}/models/s_residuals.csv", f"{d}/models/s fit$1.png"),
    "stage": lambda t, d: commands.stage(t, "report", d),
}


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_the_recipe_is_the_direct_argument_list(name):
    # make pastes variable values in as they are (paths without spaces, as plan.mk's D); the builders' own
    # arguments are quoted: a space and a `$` in them survive make and the shell.
    out = "/tmp/study-out"
    recipe = for_make(BUILDERS[name](IN_MAKE, "$(D)"))
    assert shlex.split(expand(recipe, dict(MAKE_VARIABLES, D=out))) == BUILDERS[name](TOOLS, out)


@pytest.mark.parametrize("name", sorted(BUILDERS))
def test_every_builder_honours_the_tools(name):
    args = BUILDERS[name](TOOLS, "/o")
    assert args[0] == TOOLS.python if name in ("plot", "stage") else args[0].startswith(TOOLS.bin + "/")
    for option, value in (("--jobs", TOOLS.jobs), ("--cache", TOOLS.cache)):
        if option in args:
            assert args[args.index(option) + 1] == value


def test_from_environment_reads_bin_jobs_and_cache(monkeypatch):
    monkeypatch.setenv("BIN", "/x/bin")
    monkeypatch.setenv("JOBS", "5")
    monkeypatch.setenv("CACHE", "/x/cache")
    tools = commands.from_environment()
    assert (tools.bin, tools.jobs, tools.cache) == ("/x/bin", "5", "/x/cache")


def fake_program(folder, name, script):
    path = folder / name
    path.write_text("#!/bin/sh\n" + script)
    path.chmod(path.stat().st_mode | stat.S_IEXEC)
    return path


def test_design_runs_demcal_doe_from_bin(tmp_path, monkeypatch):
    """The design stage asks $BIN/demcal-doe (a stand-in here that writes two runs) and adds the fixed values."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    fake_program(bin_dir, "demcal-doe", f'echo "$@" > {tmp_path}/doe_args\n'
                 'while [ "$1" != --out ]; do shift; done\nprintf "run,a\\n1,0.5\\n2,1.5\\n" > "$2"\n')
    config = tmp_path / "design.json"
    config.write_text(json.dumps({"space": "space.json", "design": {"kind": "lhs", "runs": 2}, "fixed": {"b": 3}}))
    monkeypatch.setenv("BIN", str(bin_dir))
    design(str(config), str(tmp_path / "g1" / "design.csv"))
    assert (tmp_path / "doe_args").read_text().split() == [
        "lhs", "--space", "space.json", "--out", str(tmp_path / "g1" / "design.csv.tmp.csv"), "--quiet", "--runs", "2"]
    assert (tmp_path / "g1" / "design.csv").read_text().splitlines() == ["run,a,b", "1,0.5,3.0", "2,1.5,3.0"]


def test_ask_runs_the_executable_from_bin(tmp_path, monkeypatch):
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    fake_program(bin_dir, "demcal-invert", 'echo \'{"algorithms": ["only-this"], "objectives": ["sum-rel"]}\'\n')
    monkeypatch.setenv("BIN", str(bin_dir))
    assert executables.inversion_choices()["algorithms"] == ["only-this"]


def parse_plan(path):
    """{target: (prerequisites, recipe lines)} of a plan.mk."""
    rules, target = {}, None
    for line in open(path).read().split("\n"):
        if line.startswith("\t") and target:
            rules[target][1].append(line[1:].lstrip("@"))
        elif re.match(r"^\$\(D\)/\S+:", line):
            target, _, prerequisites = line.partition(": ")
            rules[target] = (prerequisites.split(), [])
        else:
            target = None
    return rules


def test_plan_recipes_are_what_the_stages_would_run(tmp_path, bin_dir, monkeypatch):
    """A real plan: each tool's recipe, expanded as make expands it, equals the builder fed with the stage configs
    the plan wrote, as refinement and stability feed it."""
    out = str(tmp_path / "s")
    done = run_study_layer(["plan", "tests/data/study_small.json", out], bin_dir)
    assert done.returncode == 0, done.stderr
    monkeypatch.setenv("BIN", bin_dir)
    monkeypatch.setenv("JOBS", "2")
    monkeypatch.setenv("CACHE", "build/cache")
    tools = commands.from_environment()
    variables = {"BIN": bin_dir, "JOBS": "2", "CACHE": "build/cache", "PY": commands.PYTHON, "D": out}
    rules = parse_plan(os.path.join(out, "plan.mk"))

    def direct(target, line=0):
        prerequisites, recipe = rules["$(D)/" + target]
        text = recipe[line].split(" || ")[0].split(" > /dev/null")[0]
        return shlex.split(expand(text, dict(variables, **{"<": expand(prerequisites[0], variables),
                                                           "@": os.path.join(out, target)})))

    cfg = os.path.join(out, "config")
    with open(os.path.join(cfg, "inversion.json")) as f:
        inversion = json.load(f)
    with open(os.path.join(cfg, "verification.json")) as f:
        verification = json.load(f)
    with open(os.path.join(REPO, "tests", "data", "study_small.json")) as f:
        study = json.load(f)
    space = os.path.join(cfg, "space_inversion.json")
    model = os.path.join(out, "models", "sigma_u_MPa.json")
    assert direct("g1/design.csv") == commands.stage(tools, "design", os.path.join(cfg, "design_g1.json"),
                                                     os.path.join(out, "g1", "design.csv"))
    assert direct("g1/responses.csv") == commands.dem_batch(
        tools, study["scene"], os.path.join(out, "g1", "design.csv"), os.path.join(out, "g1", "responses.h5"),
        os.path.join(out, "g1", "responses.partial.csv"), 1)
    assert direct("models/sigma_u_MPa.json", 1) == commands.fit(
        tools, "quadratic", os.path.join(out, "g1", "responses.csv"), study["surfaces"][0]["factors"], "sigma_u_MPa",
        os.path.join(cfg, "space_g1.json"), model, report=os.path.join(out, "models", "sigma_u_MPa.md"),
        residuals=os.path.join(out, "models", "sigma_u_MPa_residuals.csv"))
    assert direct("solution.json") == commands.invert(
        tools, inversion, study["targets"], space, os.path.join(out, "solution.json"), models=[model],
        history=os.path.join(out, "inversion_history.csv"))
    assert direct("verification.json") == commands.verify(
        tools, os.path.join(out, "solution.json"), study["scene"], space, verification,
        os.path.join(out, "verification"), os.path.join(out, "verification.json"),
        md=os.path.join(out, "verification.md"), csv=os.path.join(out, "verification.csv"))
    assert direct("refined.json") == commands.stage(tools, "refine", out)
