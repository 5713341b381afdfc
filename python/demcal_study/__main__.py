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
    for name, what in (("screen", "range analysis and ANOVA of the screening, main-effects and Pareto plots"),
                       ("stability", "other optimiser seeds, a target near the edge, too-small designs"),
                       ("refine", "while verification fails: add its DEM runs, refit, re-invert, re-verify"),
                       ("report", "OUT_DIR/report.md and a self-contained report.html")):
        sub.add_parser(name, help=what).add_argument("out", metavar="OUT_DIR")
    return p


def run(args):
    # Each stage imports only what it needs (the plan needs no matplotlib or markdown).
    if args.command == "plan":
        from .plan import plan
        plan(args.study, args.out)
    elif args.command == "design":
        from .design import design
        design(args.config, args.out_csv)
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


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        run(args)
    except StudyError as e:
        print(f"demcal_study: error: {str(e).replace(chr(10), ' ')}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
