"""python -m demcal_study COMMAND ...: the study layer's command line (see the package's docstring). `calibrate` and
`export` are a user's commands; plan, design, split, score, candidates, screen, stability, refine and report are the
stages plan.mk runs, parsed as before but left out of the help."""
import argparse
import os
import re
import subprocess
import sys

from .errors import StudyError, messages_of

PACKAGE = os.path.dirname(os.path.abspath(__file__))
SOURCE_TREE = os.path.dirname(os.path.dirname(PACKAGE))
USER_COMMANDS = ("calibrate", "export")

DESCRIPTION = ("demcal's study layer: calibrate a scene's micro-parameters against measured targets, and export\n"
               "a calibrated parameter set to the simulator you run.")
EPILOG = """environment:
  BIN    folder of the executables demcal-dem, demcal-doe, ... (default build/bin)
  CACHE  folder of the cached specimens, packed once and reused (default: cache beside BIN's folder)
  JOBS   DEM runs at once (default 2)

exit codes:
  0  met, or done
  1  internal failure (a bug: please report it)
  2  bad input: one line per problem on stderr, and nothing written
  3  a target outside what the scene can reach (calibrate)
  4  the budget is spent and the targets are not met, or the DEM runs failed (calibrate)

Studies (data/studies/*.json) run through make: make study STUDY=data/studies/NAME.json."""


CALIBRATE_EPILOG = """example:
  python -m demcal_study calibrate --scene data/scenes/ucs_rock_cb.json \\
      --target sigma_u_MPa=48 --target E_GPa=6.5 --target nu=0.27

environment:
  BIN    folder of the executables (default build/bin)
  CACHE  folder of the cached specimens (default: cache beside BIN's folder)
  JOBS   DEM runs at once (default 2)

exit codes:
  0  met: every target within the tolerance on fresh seeds
  1  internal failure (a bug: please report it)
  2  bad input: one line per problem on stderr, and nothing written
  3  a target outside what the scene can reach (the report says what it reaches)
  4  the budget is spent and the targets are not met, or the DEM runs failed"""


class OneLineParser(argparse.ArgumentParser):
    """A usage error as one line, "demcal_study calibrate: error: ... (see --help)", exit 2, as the executables."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def version_line():
    """"demcal_study 0.1.0 (commit 1a2b3c4d5e6f)": the top-level CMakeLists.txt's project version and the git commit
    of the source tree ("+local-changes" when it differs from it; "unknown" outside git), as the executables say."""
    version = "unknown"
    try:
        with open(os.path.join(SOURCE_TREE, "CMakeLists.txt")) as f:
            m = re.search(r"project\s*\(\s*demcal\s+VERSION\s+([0-9][0-9A-Za-z.+-]*)", f.read())
        if m:
            version = m.group(1)
    except OSError:
        pass
    commit = "unknown"
    try:
        done = subprocess.run(["git", "-C", SOURCE_TREE, "rev-parse", "--short=12", "HEAD"], capture_output=True,
                              text=True)
        if done.returncode == 0 and done.stdout.strip():
            commit = done.stdout.strip()
            dirty = subprocess.run(["git", "-C", SOURCE_TREE, "diff", "--quiet", "HEAD", "--"], capture_output=True)
            if dirty.returncode != 0:
                commit += "+local-changes"
    except OSError:
        pass
    return f"demcal_study {version} (commit {commit})"


class VersionAction(argparse.Action):
    """--version: asks git only when given."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings=option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        print(version_line())
        parser.exit()


def parser():
    p = OneLineParser(prog="demcal_study", description=DESCRIPTION, epilog=EPILOG,
                      formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action=VersionAction, help="print the version and the git commit, then exit")
    sub = p.add_subparsers(dest="command", required=True, metavar="{" + ",".join(USER_COMMANDS) + "}",
                           title="commands")

    def stage(name, description):
        # A make-internal stage: parsed as before, but not listed in the help (argparse lists a subcommand only when
        # it is given a help string; help=argparse.SUPPRESS would still list it, as "==SUPPRESS==", on Python 3.11).
        return sub.add_parser(name, description=description + " (a stage plan.mk runs)")

    plan = stage("plan", "validate STUDY.json and write OUT_DIR/plan.mk with its stage configs")
    plan.add_argument("study", metavar="STUDY.json")
    plan.add_argument("out", metavar="OUT_DIR")
    design = stage("design", "a design in natural units, fixed values added")
    design.add_argument("config", metavar="CONFIG.json")
    design.add_argument("out_csv", metavar="OUT.csv")
    split = stage("split", "a surface's DEM responses into the points it trains on and those held out")
    split.add_argument("config", metavar="HOLDOUT.json")
    split.add_argument("responses", metavar="RESPONSES.csv")
    split.add_argument("out", metavar="SPLIT.json", help="written with train.csv and holdout.csv beside it")
    score = stage("score", "a fitted model's R^2 and RMSE on the held-out points")
    score.add_argument("model", metavar="MODEL.json")
    score.add_argument("holdout", metavar="HOLDOUT.csv")
    score.add_argument("output", metavar="OUTPUT")
    score.add_argument("out", metavar="SCORE.json")
    cands = stage("candidates", "a search's candidates verified in DEM, the best one chosen")
    cands.add_argument("out", metavar="OUT_DIR")
    for name, what in (("screen", "range analysis and ANOVA of the screening, main-effects and Pareto plots"),
                       ("stability", "other optimiser seeds, a target near the edge, too-small designs"),
                       ("refine", "while verification fails: add its DEM runs, refit, re-invert, re-verify"),
                       ("report", "OUT_DIR/report.md and a self-contained report.html")):
        stage(name, what).add_argument("out", metavar="OUT_DIR")
    cal = sub.add_parser("calibrate", help="a scene and its targets to verified micro-parameters (no study file)",
                         description="A scene and its targets to verified micro-parameters: a trust region on one "
                                     "specimen, then verification on fresh seeds (docs/explanation/"
                                     "calibration_method.md). Every option is checked before anything is written; "
                                     "rerunning the same command resumes.",
                         epilog=CALIBRATE_EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    # Numbers are read as text and checked with everything else, so that one bad value does not hide the others.
    cal.add_argument("--scene", metavar="SCENE.json", help="the scene (or test list) to calibrate (required)")
    cal.add_argument("--target", action="append", metavar="NAME=VALUE",
                     help="a target: an output of the scene, or a ratio A/B of two, in its unit (repeatable); "
                          "NAME=MEAN+-SD or NAME=MEAN+-SD/n=N gives the lab's scatter over N specimens (the point "
                          "searches aim at the mean; bayes weighs it)")
    cal.add_argument("--lab-specimens", metavar="SPECIMENS.csv",
                     help="targets from the lab's specimens: a CSV test,output,value[,specimen], one row per "
                          "measurement (each output's mean, SD and count, and the correlation of outputs measured on "
                          "one specimen)")
    cal.add_argument("--curve", action="append", metavar="[LABEL:]CURVE.csv",
                     help="a measured stress-strain curve as a target (repeatable): CSV axial_strain,axial_stress_MPa"
                          "[,lateral_strain][,sd_MPa][,confining_stress_MPa][,specimen] (a confined series: sigma_1 at that sigma_3; "
                          "specimen: several specimens' curves), "
                          "compression positive, strains as fractions; compared at 8 "
                          "strains over --curve-window; LABEL names the test of a test list")
    cal.add_argument("--curve-window", metavar="A:B",
                     help="the strains a curve is compared over, as fractions of its measured peak strain (0.1:1.0)")
    cal.add_argument("--space", metavar="SPACE.json", help="ranges to search (default: the scene's physical bounds)")
    cal.add_argument("--fixed", action="append", metavar="NAME=VALUE",
                     help="a scene parameter held at a value inside its physical bounds (repeatable)")
    cal.add_argument("--tolerance", default=0.05, metavar="T",
                     help="largest relative error that passes, 0 < T < 1 (0.05)")
    cal.add_argument("--budget", default=80, metavar="RUNS",
                     help="most DEM runs in all, failed ones counted; each test of a test list counts (80)")
    cal.add_argument("--scale-parameter", metavar="NAME", help="the stress-like parameter the others are ratios to")
    cal.add_argument("--strategy", default="trust-region", metavar="{trust-region,kriging,bayes}",
                     help="the search on specimen 1: local linear models in a trust region (default), Gaussian "
                          "processes with expected improvement, or a posterior over the parameters from targets "
                          "with their scatter (bayes: posterior.csv and posterior.json beside the solution)")
    cal.add_argument("--model-discrepancy", metavar="F",
                     help="bayes only: the model's own misfit as a fraction F of each target, added to the DEM's SD "
                          "in quadrature (a 2D model of 3D lab data, e.g. 0.1); none by default")
    cal.add_argument("--check-resolution", metavar="F",
                     help="once met, verify again with the disk radii divided by F (> 1) and report the shift")
    cal.add_argument("--check-test", action="append", metavar="SCENE.json",
                     help="once verified, run this test too at the solution on 4 fresh seeds (a prediction, not a "
                          "target; e.g. a biaxial series for c and phi); repeatable")
    cal.add_argument("--name", help="folder name under --out-root (default: the scene's name and the targets)")
    cal.add_argument("--out-root", default="build/calibrations", metavar="DIR",
                     help="the folder the calibration's own folder (--name) is made in; the report, solution.json "
                          "and parameters.json land there (default build/calibrations)")
    cal.add_argument("--quiet", action="store_true",
                     help="no progress lines on stderr (errors and the exit code still tell the outcome)")
    exp = sub.add_parser("export", help="a calibrated parameter set as PFC2D, PFC3D, YADE or LIGGGHTS input",
                         description="A calibrated parameter set written as the input of the simulator you run.",
                         epilog="exit codes: 0 written; 1 internal failure; 2 bad input (one line naming the file)")
    exp.add_argument("--solution", required=True, metavar="SOLUTION.json",
                     help="a solution.json (make calibrate, a study, demcal-invert) or a report's parameters.json")
    exp.add_argument("--scene", required=True, metavar="SCENE.json", help="the scene the solution belongs to")
    exp.add_argument("--to", required=True, choices=("pfc", "pfc3d", "yade", "liggghts"),
                     help="pfc: PFC2D (a 2D scene); pfc3d: PFC3D (a 3D scene); yade; liggghts")
    exp.add_argument("--out", metavar="FILE", help="default: print it")
    return p


def run(args):
    # Each stage imports only what it needs (the plan needs no matplotlib or markdown).
    if args.command == "plan":
        from .plan import plan
        plan(args.study, args.out)
    elif args.command == "design":
        from .design import design
        design(args.config, args.out_csv)
    elif args.command == "split":
        from .holdout import split
        split(args.config, args.responses, args.out)
    elif args.command == "score":
        from .holdout import score
        score(args.model, args.holdout, args.output, args.out)
    elif args.command == "candidates":
        from .candidates import verify_candidates
        verify_candidates(args.out)
    elif args.command == "screen":
        from .screening import screen
        screen(args.out)
    elif args.command == "stability":
        from .stability import stability
        stability(args.out)
    elif args.command == "refine":
        from .refine import refine
        refine(args.out)
    elif args.command == "report":
        from .report import report
        report(args.out)
    elif args.command == "export":
        from .export import export
        return export(args)
    elif args.command == "calibrate":
        from .calibrate import calibrate
        return calibrate(args)
    return 0


def main(argv=None):
    p = parser()
    args, unknown = p.parse_known_args(argv)
    if unknown and args.command != "calibrate":
        p.error(f"unrecognized arguments: {' '.join(unknown)}")
    args.unrecognized = unknown  # calibrate reports them with every other problem of the command
    try:
        code = run(args)
    except StudyError as e:
        for message in messages_of(e):
            print(f"demcal_study: error: {message}", file=sys.stderr)
        sys.exit(2)
    sys.exit(code or 0)


if __name__ == "__main__":
    main()
