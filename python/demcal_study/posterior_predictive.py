"""The posterior predictive of the Bayesian search: what a mean of fresh specimens will show, for every output of
every test (targeted or not), at the exported point and over the whole posterior.

The emulators are of specimen 1 (common random numbers), so the prediction of a mean of n fresh specimens adds to
the emulator's own SD two terms of the specimens' scatter sigma, measured on the first verification's seeds:
specimen 1's own deviation from the population (sigma^2: the posterior does not know it) and the n-specimen mean's
(sigma^2 / n). A stress-like output scatters in proportion to the scale factor, so its sigma is carried as a
coefficient of variation. sigma is estimated from few seeds (5 at the least), so the interval is Student's, not the
normal one: with the emulator's variance a (known) and the specimens' term b (m - 1 degrees of freedom from m seeds),
Welch-Satterthwaite's (a + b)^2 (m - 1) / b^2 degrees of freedom; draws over the posterior take a Student-t
deviate for the specimens' term. The check a user reads: does the 95 % interval at the exported point hold the mean
of the first n verified specimens there?"""
import json
import math
import os

import numpy as np

from . import kriging
from .errors import load_json
from .files import write_target
from .outputs import is_output, output_info
from .searches.bayes_search import ScaleFreeEmulator
from .trust_region import t975

SEEDS_IN_MEAN = 5
DRAWS_SAMPLED = 400   # posterior draws the predictive over the posterior is sampled at (evenly thinned)


class _Emulator:
    """One output over the points run on specimen 1: the Bayesian search's emulator (a Gaussian process, of the
    logarithm for a positive stress-like output) of value / scale for an output that scales with the stress-like
    parameters, of the value otherwise. predict(u, scale) -> (mean, SD) in the output's own unit."""

    def __init__(self, u, values, scales, scaled, logged, seed):
        y = np.asarray(values, float) / (np.asarray(scales, float) if scaled else 1.0)
        self.scaled = scaled
        self.constant = float(y[0]) if np.ptp(y) == 0 else None  # a count that never moved: no process to fit
        self.emulator = None if self.constant is not None else ScaleFreeEmulator(
            kriging.fit(np.asarray(u, float), np.log(y) if logged else y, seed=seed), logged)

    def predict(self, u, scale):
        u = np.atleast_2d(u)
        if self.emulator is None:
            mean, sd = np.full(len(u), self.constant), np.zeros(len(u))
        else:
            mean, sd = self.emulator.predict(u)
        factor = np.asarray(scale, float) if self.scaled else 1.0
        return mean * factor, sd * np.abs(factor)


def half_width_95(emulator_sd, specimen_sd, freedom):
    """(half-width, degrees of freedom) of the 95 % interval of emulator error (SD known) plus the specimens' term
    (SD estimated with `freedom` degrees of freedom): Student's, by Welch-Satterthwaite."""
    a, b = emulator_sd ** 2, specimen_sd ** 2
    effective = (a + b) ** 2 * freedom / b ** 2 if b > 0 else math.inf
    return t975(effective) * math.sqrt(a + b), effective


def predicted_outputs(cal, seeds):
    """The outputs every usable specimen-1 point and at least two verified seeds have, as finite numbers: the
    scene's outputs and the targets' ratios."""
    described = cal.description["outputs"]
    names = set(described) | {o for o in cal.problem.targets if is_output(described, o, "predictive")}
    ok = [q for q in cal.runner.points if q["status"] == "ok"]
    out = []
    for o in sorted(names):
        if not ok or not all(_finite(q["outputs"].get(o)) for q in ok):
            continue
        if sum(_finite(s.get(o)) for s in seeds) >= 2:
            out.append(o)
    return out


def _finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def predictive(cal, draws, exported):
    """predictive.json beside the solution: for every output, the 95 % interval of a mean of SEEDS_IN_MEAN fresh
    specimens at the verified exported point and over the posterior's draws, and whether the first verification's
    mean of that many seeds falls inside. draws: rows of (coded coordinates[, scale factor]); exported: one such
    row. Returns the content, or None when no verification ran."""
    if not cal.verifications:
        return None
    p = cal.problem
    d = len(p.coordinates)
    first = cal.verifications[0]
    verification = load_json(os.path.join(cal.out, first["folder"], "verification.json"), "verification")
    seeds = [s["macro"] for s in verification["seeds"] if s["status"] == "ok"]
    scaled_problem = p.scale_parameter is not None
    at_scale = float(first["scale"])
    draws = np.atleast_2d(np.asarray(draws, float))
    keep = np.unique(np.linspace(0, len(draws) - 1, min(DRAWS_SAMPLED, len(draws))).astype(int))
    draws = draws[keep]
    draw_scales = draws[:, d] if scaled_problem else np.ones(len(draws))
    ok = [q for q in cal.runner.points if q["status"] == "ok"]
    u = np.array([q["u"] for q in ok])
    scales = np.array([q["scale"] for q in ok])
    rng = np.random.default_rng(1)
    rows = {}
    for k, o in enumerate(predicted_outputs(cal, seeds)):
        stress = bool(output_info(cal.description["outputs"], o, "predictive")["stress_like"])
        values = np.array([q["outputs"][o] for q in ok], float)
        positive = bool(np.all(values > 0))
        scaled = stress and scaled_problem
        emulator = _Emulator(u, values, scales, scaled, stress and positive, seed=k + 1)
        measured = np.array([s[o] for s in seeds if _finite(s.get(o))], float)
        sd_seed = float(measured.std(ddof=1))
        # The specimens' scatter in the output's unit at scale `s`: a stress-like output's scales with it.
        def seed_sd(s):
            return sd_seed * (np.asarray(s, float) / at_scale if scaled else 1.0)
        spread = math.sqrt(1.0 + 1.0 / SEEDS_IN_MEAN)
        freedom = len(measured) - 1  # of the specimens' SD
        mean_e, sd_e = emulator.predict(exported[:d], at_scale)
        half, effective = half_width_95(float(sd_e[0]), spread * float(seed_sd(at_scale)), freedom)
        mean_d, sd_d = emulator.predict(draws[:, :d], draw_scales)
        sampled = (mean_d + sd_d * rng.standard_normal(len(draws))
                   + spread * seed_sd(draw_scales) * rng.standard_t(freedom, len(draws)))
        verified = measured[:SEEDS_IN_MEAN]
        verified_mean = float(verified.mean()) if len(verified) == SEEDS_IN_MEAN else None
        interval = [float(mean_e[0]) - half, float(mean_e[0]) + half]
        rows[o] = {"target": p.targets.get(o), "stress_like": stress,
                   "exported": {"mean": float(mean_e[0]), "interval_95": interval},
                   "posterior": {"median": float(np.median(sampled)),
                                 "interval_95": [float(x) for x in np.percentile(sampled, [2.5, 97.5])]},
                   "specimen_sd": float(seed_sd(at_scale)), "specimen_sd_seeds": len(measured),
                   "emulator_sd": float(sd_e[0]),
                   "degrees_of_freedom": effective if math.isfinite(effective) else None,
                   "verified_mean": verified_mean,
                   "inside": None if verified_mean is None else bool(interval[0] <= verified_mean <= interval[1])}
    content = {"seeds_in_mean": SEEDS_IN_MEAN,
               "verification": first["folder"], "verified_seeds": len(seeds),
               "how": f"a mean of {SEEDS_IN_MEAN} fresh specimens: specimen 1's emulator, its SD, specimen 1's own "
                      f"deviation from the population (the specimens' SD) and the mean's (that SD over "
                      f"sqrt({SEEDS_IN_MEAN})), in quadrature; the specimens' SD from the first verification's seeds, "
                      "so Student's interval (Welch-Satterthwaite's degrees of freedom)",
               "outputs": rows}
    write_target(os.path.join(cal.out, "predictive.json"), json.dumps(content, indent=1) + "\n")
    return content
