"""The command line of every program the study layer runs, each built by one function.

plan.mk's recipes are these lists written for make (`for_make`), with make's variables ($(BIN), $(JOBS),
$(CACHE), $(D), $<, $@) left for make to expand; the stages that run the tools themselves (the screening
analysis, refinement, stability) pass the same lists to subprocess. One builder per program, so a recipe and a
direct call cannot drift apart.
"""
import os
import re
import shlex
from dataclasses import dataclass

PYTHON = "/usr/bin/python3"  # the project runs Debian's Python, which has its packages


@dataclass(frozen=True)
class Tools:
    """Where the executables are and how they run: the bin folder, parallel jobs, the specimen cache, Python."""
    bin: str
    jobs: str
    cache: str
    python: str

    def program(self, name):
        return os.path.join(self.bin, name)


# In plan.mk: make's own variables (set on make's command line by run_study.sh, or to the plan's defaults).
IN_MAKE = Tools(bin="$(BIN)", jobs="$(JOBS)", cache="$(CACHE)", python="$(PY)")


def from_environment():
    """For the stages' own calls: plan.mk exports BIN, JOBS and CACHE to them; the defaults are the plan's."""
    bin_dir = os.environ.get("BIN", "build/bin")
    # The cache sits beside the executables' folder (build/cache for build/bin), wherever the user stands.
    return Tools(bin=bin_dir, jobs=os.environ.get("JOBS", "2"),
                 cache=os.environ.get("CACHE", os.path.join(os.path.dirname(os.path.abspath(bin_dir)), "cache")),
                 python=PYTHON)


# The options of a design a study may give (study file: screening.design, surfaces[].design).
DESIGN_OPTIONS = ("center", "alpha", "runs", "criterion", "blank", "levels")


def doe(tools, design, space, out, scene=None):
    """demcal-doe: `design` ({"kind": ..., options}) over the parameter space file `space`, natural units
    (held to `scene`'s physical bounds when given)."""
    args = [tools.program("demcal-doe"), design["kind"], "--space", space, "--out", out, "--quiet"]
    if scene:
        args += ["--scene", scene]
    for key in DESIGN_OPTIONS:
        if key in design:
            args += [f"--{key}", str(design[key])]
    return args


def dem_batch(tools, scene, design, out, csv, seeds, first_seed=1):
    """demcal-dem batch: every point of `design` x `seeds` (resumable: out.points/ keeps the finished ones)."""
    return [tools.program("demcal-dem"), "batch", "--scene", scene, "--design", design, "--out", out, "--csv", csv,
            "--seeds", str(seeds), "--jobs", tools.jobs, "--cache", tools.cache] + (
        ["--first-seed", str(first_seed)] if first_seed != 1 else [])


def fit(tools, kind, data, factors, output, space, out, report=None, residuals=None):
    """demcal-fit of one output: response surfaces coded on their surface's space, GA-BP trained from seed 1."""
    coding = ["--seed", "1"] if kind == "gabp" else ["--space", space]
    args = [tools.program("demcal-fit"), kind, "--data", data, "--x", ",".join(factors), "--y", output] + coding
    args += ["--out", out]
    if report:
        args += ["--report", report]
    if residuals:
        args += ["--residuals", residuals]
    return args + ["--quiet"]


def predict(tools, model, data, out):
    """demcal-predict: a fitted model at every row of `data`."""
    return [tools.program("demcal-predict"), "--model", model, "--data", data, "--out", out, "--quiet"]


def sobol(tools, model, out):
    """demcal-analyze sobol: first-order and total Sobol indices of a fitted model over its domain (JSON)."""
    return [tools.program("demcal-analyze"), "sobol", "--model", model, "--format", "json", "--out", out]


def invert(tools, inversion, targets, space, out, models=(), dem=None, seed=None, history=None, quiet=False):
    """demcal-invert with the study's inversion settings (config/inversion.json): on the surrogate `models`, or,
    with dem = {"scene", "seeds"}, on the DEM itself; `seed` replaces the settings' seed (stability)."""
    args = [tools.program("demcal-invert")]
    for model in models:
        args += ["--model", model]
    if dem:
        args += ["--dem-scene", dem["scene"], "--dem-seeds", str(dem["seeds"]), "--jobs", tools.jobs,
                 "--cache", tools.cache]
    for name, value in targets.items():
        args += ["--target", f"{name}={value}"]
    args += ["--space", space, "--algo", inversion["algorithm"], "--objective", inversion["objective"],
             "--restarts", str(inversion["restarts"]), "--seed", str(inversion["seed"] if seed is None else seed)]
    if inversion["polish"]:
        args.append("--polish")
    args += inversion.get("extra", []) + ["--out", out]
    if history:
        args += ["--history", history]
    if quiet:
        args.append("--quiet")
    return args


def verify(tools, solution, scene, space, verification, work, out, md=None, csv=None, quiet=False):
    """demcal-verify: the DEM at a solution over the seeds of config/verification.json."""
    args = [tools.program("demcal-verify"), "--solution", solution, "--scene", scene, "--space", space,
            "--seeds", str(verification["seeds"]),
            "--max-seeds", str(verification.get("max_seeds", max(20, verification["seeds"]))),
            "--first-seed", str(verification.get("first_seed", 1)),
            "--tolerance", str(verification["tolerance"]), "--jobs", tools.jobs, "--cache", tools.cache,
            "--work", work]
    if md:
        args += ["--md", md]
    if csv:
        args += ["--csv", csv]
    args += ["--out", out]
    if quiet:
        args.append("--quiet")
    return args


def calibrate(tools, scene, targets, tolerance, budget, out_root, name, space=None, fixed=None, scale_parameter=None,
              check_resolution=None, check_tests=(), search=None, target_scatter=None, lab_specimens=None,
              curves=(), curve_window=None, model_discrepancy=None):
    """python -m demcal_study calibrate: the trust-region calibration (docs/explanation/calibration_method.md) of a
    "strategy": "trust_region" study, into out_root/name (resumable; exit 0 met, 3 unreachable, 4 budget).
    target_scatter: {output: {"sd", "n"}}, written as --target NAME=MEAN+-SD/n=N."""
    args = stage(tools, "calibrate", "--scene", scene)
    for key, value in targets.items():
        spread = (target_scatter or {}).get(key)
        if spread:
            n = spread.get("n", 1)
            args += ["--target", f"{key}={value!r}+-{spread['sd']!r}" + (f"/n={n}" if n != 1 else "")]
        else:
            args += ["--target", f"{key}={value!r}"]
    if lab_specimens:
        args += ["--lab-specimens", lab_specimens]
    for key, value in (fixed or {}).items():
        args += ["--fixed", f"{key}={value!r}"]
    args += ["--tolerance", repr(tolerance), "--budget", str(budget)]
    if space:
        args += ["--space", space]
    if scale_parameter:
        args += ["--scale-parameter", scale_parameter]
    if check_resolution:
        args += ["--check-resolution", repr(check_resolution)]
    for path in check_tests:
        args += ["--check-test", path]
    if search and search != "trust-region":  # the default stays off the line, so stored calibrations resume
        args += ["--strategy", search]
    for spec in curves:
        args += ["--curve", spec]
    if curve_window:
        args += ["--curve-window", curve_window]
    if model_discrepancy:
        args += ["--model-discrepancy", repr(model_discrepancy)]
    return args + ["--name", name, "--out-root", out_root]


def analyze(tools, kind, data, factors, responses, fmt, out, error=None):
    """demcal-analyze range or anova of a screening table; `error` names the term that is the error."""
    args = [tools.program("demcal-analyze"), kind, "--data", data, "--factors", ",".join(factors),
            "--responses", ",".join(responses), "--format", fmt, "--out", out]
    if error:
        args += ["--error", error]
    return args


def plot(tools, kind, data, out):
    """scripts/plot_analysis.py: main-effects, pareto or fit figure of a demcal-analyze/demcal-fit output."""
    return [tools.python, "scripts/plot_analysis.py", kind, data, "--out", out]


def stage(tools, name, *args):
    """One of the study layer's own stages (design, screen, refine, stability, report, plan)."""
    return [tools.python, "-m", "demcal_study", name] + list(args)


# A make variable reference, which make expands before the shell sees the line.
MAKE_REFERENCE = re.compile(r"(\$\([A-Za-z_][A-Za-z0-9_]*\)|\$[<@])")


def for_make(args):
    """A recipe line: each argument quoted for the shell where it needs it and `$` doubled for make, except
    make's own variable references, which stay for make to expand."""
    return " ".join(_make_word(arg) for arg in args)


def _make_word(arg):
    if arg == "":
        return "''"
    pieces = MAKE_REFERENCE.split(arg)  # odd indexes are the references
    return "".join(piece if k % 2 else shlex.quote(piece).replace("$", "$$") if piece else ""
                   for k, piece in enumerate(pieces))
