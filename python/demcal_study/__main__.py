"""python -m demcal_study SUBCOMMAND ...: the study layer's command line (see the package's docstring)."""
import argparse
import sys

from . import __doc__ as overview
from .errors import StudyError


def parser():
    p = argparse.ArgumentParser(prog="demcal_study", description=overview.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True, metavar="SUBCOMMAND")
    plan = sub.add_parser("plan", help="validate STUDY.json and write OUT_DIR/plan.mk with its stage configs")
    plan.add_argument("study", metavar="STUDY.json")
    plan.add_argument("out", metavar="OUT_DIR")
    design = sub.add_parser("design", help="a design in natural units, fixed values added")
    design.add_argument("config", metavar="CONFIG.json")
    design.add_argument("out_csv", metavar="OUT.csv")
    split = sub.add_parser("split", help="a surface's DEM responses into the points it trains on and those held out")
    split.add_argument("config", metavar="HOLDOUT.json")
    split.add_argument("responses", metavar="RESPONSES.csv")
    split.add_argument("out", metavar="SPLIT.json", help="written with train.csv and holdout.csv beside it")
    score = sub.add_parser("score", help="a fitted model's R^2 and RMSE on the held-out points")
    score.add_argument("model", metavar="MODEL.json")
    score.add_argument("holdout", metavar="HOLDOUT.csv")
    score.add_argument("output", metavar="OUTPUT")
    score.add_argument("out", metavar="SCORE.json")
    cands = sub.add_parser("candidates", help="a search's candidates verified in DEM, the best one chosen")
    cands.add_argument("out", metavar="OUT_DIR")
    for name, what in (("screen", "range analysis and ANOVA of the screening, main-effects and Pareto plots"),
                       ("stability", "other optimiser seeds, a target near the edge, too-small designs"),
                       ("refine", "while verification fails: add its DEM runs, refit, re-invert, re-verify"),
                       ("report", "OUT_DIR/report.md and a self-contained report.html")):
        sub.add_parser(name, help=what).add_argument("out", metavar="OUT_DIR")
    exp = sub.add_parser("export", help="a calibrated parameter set as PFC, YADE or LIGGGHTS input")
    exp.add_argument("--solution", required=True, metavar="SOLUTION.json")
    exp.add_argument("--scene", required=True, metavar="SCENE.json", help="the scene the solution belongs to")
    exp.add_argument("--to", required=True, choices=("pfc", "yade", "liggghts"))
    exp.add_argument("--out", metavar="FILE", help="default: print it")
    cal = sub.add_parser("calibrate", help="a scene and its targets to verified micro-parameters (no study file)")
    cal.add_argument("--scene", required=True, metavar="SCENE.json")
    cal.add_argument("--target", action="append", metavar="NAME=VALUE", help="a target (repeatable)")
    cal.add_argument("--space", metavar="SPACE.json", help="ranges to search (default: the scene's physical bounds)")
    cal.add_argument("--fixed", action="append", metavar="NAME=VALUE", help="a parameter held at a value")
    cal.add_argument("--tolerance", type=float, default=0.05, help="largest relative error that passes (0.05)")
    cal.add_argument("--budget", type=int, default=80, help="most DEM runs in all, failed ones counted (80)")
    cal.add_argument("--scale-parameter", metavar="NAME", help="the stress-like parameter the others are ratios to")
    cal.add_argument("--strategy", choices=("trust-region", "kriging"), default="trust-region",
                     help="the search on specimen 1: local linear models in a trust region (default), or Gaussian "
                          "processes with expected improvement")
    cal.add_argument("--check-resolution", type=float, metavar="F",
                     help="once met, verify again with the disk radii divided by F (> 1) and report the shift")
    cal.add_argument("--check-test", action="append", metavar="SCENE.json",
                     help="once verified, run this test too at the solution on 4 fresh seeds (a prediction, not a "
                          "target; e.g. a biaxial series for c and phi); repeatable")
    cal.add_argument("--name", help="folder name under --out-root (default: the scene's name and the targets)")
    cal.add_argument("--out-root", default="build/calibrations")
    cal.add_argument("--quiet", action="store_true")
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
    args = parser().parse_args(argv)
    try:
        code = run(args)
    except StudyError as e:
        print(f"demcal_study: error: {str(e).replace(chr(10), ' ')}", file=sys.stderr)
        sys.exit(2)
    sys.exit(code or 0)


if __name__ == "__main__":
    main()
