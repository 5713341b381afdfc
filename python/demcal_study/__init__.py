"""demcal's study layer: a study file (data/studies/) becomes a make plan whose every stage is a file target.

    python -m demcal_study plan STUDY.json OUT_DIR     validate and write OUT_DIR/plan.mk with its stage configs
    python -m demcal_study design CONFIG.json OUT.csv  a design in natural units, fixed values added
    python -m demcal_study screen OUT_DIR              range analysis and ANOVA of the screening, with plots
    python -m demcal_study stability OUT_DIR           other optimiser seeds, a target near the edge, too-small
                                                       designs (each verified)
    python -m demcal_study refine OUT_DIR              while verification fails: add its DEM runs to the data,
                                                       refit, re-invert, re-verify (up to refinement.rounds)
    python -m demcal_study report OUT_DIR              OUT_DIR/report.md and a self-contained report.html
    python -m demcal_study calibrate --scene S --target NAME=VALUE ...   make calibrate (docs/calibration.md)
    python -m demcal_study export --solution S.json --scene S --to pfc|yade|liggghts   a calibrated set as input
                                                       of the simulator a user runs (docs/external.md)

Run from the source tree with PYTHONPATH=python; `make study STUDY=data/studies/NAME.json` (scripts/run_study.sh)
plans, then runs make on the plan: design -> DEM responses -> models -> solution -> verification -> refinement ->
report, so an interrupted study resumes, `make -j2` runs independent stages together, and a change to the study
rewrites only the stage configs it touches (their contents are compared), so only what depends on them runs again.
"""
import os as _os

# One BLAS thread: the least-squares fits of a calibration then give the same bits however many cores the BLAS would
# have used, so a rerun makes the same decisions (a candidate differing in its last digit is another DEM point).
_os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
