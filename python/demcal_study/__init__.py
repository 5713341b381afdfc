"""demcal's study layer. What a user runs:

    python -m demcal_study calibrate --scene S --target NAME=VALUE ...   make calibrate (docs/tutorial.md)
    python -m demcal_study export --solution S.json --scene S --to pfc|pfc3d|yade|liggghts   a calibrated set as input
                                                       of the simulator a user runs (docs/howto/own_simulator.md)

A study file (data/studies/) becomes a make plan whose every stage is a file target; the stages are subcommands
too (plan, design, split, score, candidates, screen, stability, refine, report), called by that plan, not by hand.

Run from the source tree with PYTHONPATH=python; `make study STUDY=data/studies/NAME.json` (scripts/run_study.sh)
plans, then runs make on the plan: design -> DEM responses -> models -> solution -> verification -> refinement ->
report, so an interrupted study resumes, `make -j2` runs independent stages together, and a change to the study
rewrites only the stage configs it touches (their contents are compared), so only what depends on them runs again.
"""
import os as _os

# One BLAS thread: the least-squares fits of a calibration then give the same bits however many cores the BLAS would
# have used, so a rerun makes the same decisions (a candidate differing in its last digit is another DEM point).
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
