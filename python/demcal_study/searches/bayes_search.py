"""The Bayesian search (`make calibrate STRATEGY=bayes`): a posterior over the micro-parameters from the lab's
targets with their scatter.

A Latin hypercube over the whole coded box comes first, so that the emulators know the prior and not only the
neighbourhood of the start. Then each round fits a Gaussian process of every modelled response over the points run
on specimen 1 (the kriging search's emulators: log(stress / scale) and the dimensionless outputs), samples the
posterior those emulators and the lab's means and standard errors give (bayes_posterior.Posterior, emcee), and runs
four DEM points where the posterior is: the three draws (apart from each other) where the emulators know least
against the lab's scatter, and the draw of highest posterior density. It stops when, over the posterior's draws, the emulators' SD is at most half the lab's standard error for
every target (more DEM runs would barely narrow the posterior), or when the budget leaves only the verification.
The exported point is the draw of highest posterior density (maximum a posteriori among the draws), verified on
fresh seeds as every search's point is. Each round's posterior is stored: rounds/LABELnn/posterior.csv and
posterior.json, the last also as posterior.csv and posterior.json in the calibration's folder."""
import csv
import json
import math
import os

import numpy as np

from .. import kriging
from ..bayes_posterior import Posterior
from ..calibrate_limits import INITIAL_RADIUS, MAX_ROUNDS
from ..files import write_target
from ..lab_targets import LabTarget

SETTLED = 0.5        # the emulators' SD over the lab's standard error below which the search stops
DRAWS_KEPT = 2000    # posterior draws stored and used to choose points (evenly thinned)
CREDIBLE = (5.0, 95.0)
MAX_STEPS = 16000    # the longest chain a round runs while it is shorter than 50 autocorrelation times


class ScaleFreeEmulator:
    """A Gaussian process of a modelled response as an emulator of the output at scale factor 1: exp of the process
    for a stress output modelled as log(stress / scale) (its SD by the first-order rule, exp(mean) times the
    process's SD), the process itself for a dimensionless output."""

    def __init__(self, gp, logged):
        self.gp, self.logged = gp, logged
        # The sampler asks for tens of thousands of predictions of one process: the inverse of its Cholesky factor
        # once (n <= budget points) instead of a general solve per call, which took three quarters of a search.
        self.chol_inverse = np.linalg.solve(gp.chol, np.eye(len(gp.chol)))

    def predict(self, u):
        gp = self.gp
        ks = gp.signal2 * kriging.matern52(np.atleast_2d(u), gp.x, gp.length)
        mean = gp.mean + ks @ gp.alpha
        v = self.chol_inverse @ ks.T
        sd = np.sqrt(np.maximum(gp.signal2 - (v ** 2).sum(axis=0), 1e-300))
        if self.logged:
            m = np.exp(mean)
            return m, m * sd
        return mean, sd


def lab_targets(cal):
    """The targets as LabTargets, in the order of the modelled outputs."""
    uncertainty = cal.config.get("target_uncertainty", {})
    out = []
    for o in cal.problem.modelled_outputs():
        u = uncertainty.get(o)
        out.append(LabTarget(o, cal.problem.targets[o], u["sd"], u.get("n", 1)) if u else LabTarget(o, cal.problem.targets[o]))
    return out


class BayesSearch:
    name = "bayes"

    @staticmethod
    def plan(d):
        """(the rounds in words, the most points they run) for the progress line."""
        n = global_size(d)
        return f"a Latin hypercube of {n} over the whole box + up to {MAX_ROUNDS} rounds of 4", n + 4 * MAX_ROUNDS

    def run(self, cal, centre, best, label="r"):
        p = cal.problem
        names = p.modelled_outputs()
        targets = lab_targets(cal)
        scaled = p.scale_parameter is not None
        stress = [scaled and p.output_stress_like[o] for o in names]
        d = len(centre)
        bounds = None
        support = None
        if scaled:
            lo, hi = p.absolute_bounds[p.scale_parameter]
            bounds = (max(lo, 1e-300) / p.scale_reference, hi / p.scale_reference)

            support = scale_support(p)
        lab_r = correlation_in_order(cal.config.get("lab_correlation"), names)
        discrepancy = cal.config.get("model_discrepancy", 0.0)
        reserve = cal.runner.verification_reserve()
        converged, samples, posterior, exported, draws = False, None, None, None, None
        # The emulators must know the whole prior, not only the first design's neighbourhood of the reference point,
        # or the posterior spreads to where nothing was run: a Latin hypercube over the whole coded box first.
        cal.runner.run_round(f"{label}01_global", [(u, 1.0) for u in global_design(d, global_size(d), seed=7)])
        for k in range(2, 2 + MAX_ROUNDS):
            rows = cal.runner.usable()
            x = np.array([r[0] for r in rows])
            z = np.array([r[1] for r in rows])
            # A stress spans decades over a log-coded box: its logarithm is what a Gaussian process follows (with
            # a scale factor the problem already models log(stress / scale)).
            if scaled:
                logged = list(stress)
            else:
                logged = [p.output_stress_like[o] and bool(np.all(z[:, j] > 0)) for j, o in enumerate(names)]
                for j in np.flatnonzero(logged):
                    z[:, j] = np.log(z[:, j])
            gps = [kriging.fit(x, z[:, j], seed=k) for j in range(len(names))]
            emulators = [ScaleFreeEmulator(gp, flag) for gp, flag in zip(gps, logged)]
            posterior = Posterior(emulators, targets, stress, d, scale_bounds=bounds,
                                  lab_correlation=lab_r,
                                  scale_support=support, discrepancy=discrepancy)
            start_u = np.clip(np.array(best["u"]) + 0.02 * np.random.default_rng(k).standard_normal((posterior.default_walkers(), d)), -1, 1)
            start = start_u if not scaled else np.column_stack(
                [start_u, best["scale"] * (1 + 0.005 * np.random.default_rng(k + 1000).standard_normal(len(start_u)))])
            samples = posterior.sample(seed=k, start=start, max_steps=MAX_STEPS)
            draws = thinned(samples, DRAWS_KEPT)
            _, sd = posterior.predicted(draws.theta)
            # What the DEM's mean is judged against: the lab's standard error, and the model's own misfit when one is
            # stated (more DEM runs cannot narrow what that leaves open).
            lab_se = np.hypot([t.standard_error for t in targets], posterior.discrepancy_sd)
            share = sd / lab_se
            settled = float(np.max(np.median(share, axis=0)))
            exported = draws.theta[int(np.argmax(draws.log_prob))]
            summary = store(cal, f"{label}{k:02d}", posterior, draws, samples, exported, settled)
            cal.rounds.append({"round": k, "bayes": summary["diagnostics"], "runs": cal.runner.runs,
                               "centre_residuals_pct": None, "accepted": True, "radius": INITIAL_RADIUS,
                               "held_at_bounds": []})
            cal.say(f"round {k}: posterior of {len(rows)} points: emulators' SD {settled:.2f} of the lab's standard "
                    f"error at most (median over the draws), {samples.effective_samples:.0f} effective draws"
                    + ("" if samples.converged else f" (the chain of {samples.steps} steps is shorter than 50 "
                       "autocorrelation times: the intervals are rough)") + ", "
                    f"{cal.runner.runs} runs")
            if settled <= SETTLED:
                converged = True
                break
            if not cal.runner.room_for(2, reserve):
                break
            # Where the emulators know least inside the posterior (three draws, apart from each other), and its
            # densest draw unless a point already ran there.
            order = np.argsort(-np.max(share, axis=1))
            picks = []
            for i in order:
                if all(np.linalg.norm(draws.theta[i][:d] - q[:d]) > 0.1 for q in picks):
                    picks.append(draws.theta[i])
                if len(picks) == 3:
                    break
            run_u = np.array([q["u"] for q in cal.runner.points]) if cal.runner.points else np.zeros((0, d))
            if not (run_u.size and np.min(np.linalg.norm(run_u - exported[:d], axis=1)) < 0.02):
                picks.append(exported)
            cal.runner.run_round(f"{label}{k:02d}", [(t[:d], float(t[d]) if scaled else 1.0) for t in picks])
        for name in ("posterior.csv", "posterior.json"):  # the last round's, where a user looks first
            src = os.path.join(cal.out, "rounds", f"{label}{k:02d}", name)
            if os.path.exists(src):
                with open(src) as f:
                    write_target(os.path.join(cal.out, name), f.read())
        # Kept for the posterior predictive, which needs the verification that follows (posterior_predictive.py).
        cal.posterior = {"round": k, "converged": converged, "exported": exported,
                         "draws": None if draws is None else draws.theta}
        centre = np.array(exported[:d]) if exported is not None else centre
        best = cal.best_point() or best
        return centre, INITIAL_RADIUS, best, converged, False


def global_size(d):
    """The global design's points: 3 per coordinate, at least 6."""
    return max(6, 3 * d)


def global_design(d, n, seed):
    """n points of a Latin hypercube over the coded box [-1, 1]^d (numpy, seeded)."""
    rng = np.random.default_rng(seed)
    cells = np.array([rng.permutation(n) for _ in range(d)]).T
    return list(-1.0 + 2.0 * (cells + rng.uniform(size=(n, d))) / n)


def scale_support(p):
    """Rows of coded points -> (low, high) arrays of the scale factors that keep every varied stress-like parameter
    inside its bounds (Problem.scale_interval without its softening, for many rows at once)."""
    ratio = [(j, c) for j, c in enumerate(p.coordinates) if c.ratio]

    def decode(c, u):
        u = np.clip(u, -1.0, 1.0)
        if c.log_scale:
            return np.exp(np.log(c.low) + 0.5 * (u + 1.0) * (np.log(c.high) - np.log(c.low)))
        return c.low + 0.5 * (u + 1.0) * (c.high - c.low)

    def support(rows):
        rows = np.atleast_2d(rows)
        low = np.zeros(len(rows))
        high = np.full(len(rows), np.inf)
        bases = {p.scale_parameter: np.full(len(rows), p.scale_reference)}
        for j, c in ratio:
            bases[c.name] = decode(c, rows[:, j]) * p.scale_reference
        for name, base in bases.items():
            lo, hi = p.absolute_bounds[name]
            ok = base > 0
            low = np.where(ok, np.maximum(low, lo / np.where(ok, base, 1.0)), low)
            high = np.where(ok, np.minimum(high, hi / np.where(ok, base, 1.0)), high)
        return low, high

    return support


def correlation_in_order(stored, names):
    """The lab's correlation matrix (stored as {"names", "matrix"}) for the targets `names`, in their order; None
    when none is stored."""
    if not stored:
        return None
    where = {n: i for i, n in enumerate(stored["names"])}
    r = np.eye(len(names))
    for a, na in enumerate(names):
        for b, nb in enumerate(names):
            if a != b and na in where and nb in where:
                r[a, b] = stored["matrix"][where[na]][where[nb]]
    return r


class _Draws:
    def __init__(self, theta, log_prob):
        self.theta, self.log_prob = theta, log_prob


def thinned(samples, kept):
    """At most `kept` of the draws, evenly spaced (the chain order is the walkers' interleaving, so evenly spaced
    picks keep every walker)."""
    n = len(samples.theta)
    index = np.unique(np.linspace(0, n - 1, min(kept, n)).astype(int))
    return _Draws(samples.theta[index], samples.log_prob[index])


def store(cal, round_label, posterior, draws, samples, exported, settled):
    """rounds/ROUND/posterior.csv (every kept draw: the coded coordinates, the scale factor and the scene's
    parameter values, weight 1) and posterior.json (each parameter's median and 90 % credible interval, whether the
    data identify it, the exported point and the sampler's diagnostics); returns the JSON's content."""
    p = cal.problem
    d = len(p.coordinates)
    folder = os.path.join(cal.out, "rounds", round_label)
    os.makedirs(folder, exist_ok=True)
    scaled = p.scale_parameter is not None
    values = [p.absolute(list(t[:d]), float(t[d]) if scaled else 1.0) for t in draws.theta]
    names = sorted(values[0]) if values else []
    with open(os.path.join(folder, "posterior.csv.tmp"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([f"u_{c.name}" for c in p.coordinates] + (["scale_factor"] if scaled else []) + names
                   + ["log_posterior", "weight"])
        for t, v, lp in zip(draws.theta, values, draws.log_prob):
            w.writerow([repr(float(x)) for x in t] + [repr(float(v[n])) for n in names] + [repr(float(lp)), "1"])
    os.replace(os.path.join(folder, "posterior.csv.tmp"), os.path.join(folder, "posterior.csv"))
    parameters = {}
    for j, c in enumerate(p.coordinates):
        coded = draws.theta[:, j]
        lo, mid, hi = np.percentile(coded, [CREDIBLE[0], 50, CREDIBLE[1]])
        absolute = np.array([v[c.name] for v in values])
        a_lo, a_mid, a_hi = np.percentile(absolute, [CREDIBLE[0], 50, CREDIBLE[1]])
        parameters[c.name] = {"median": float(a_mid), "credible_90": [float(a_lo), float(a_hi)],
                              "coded_width": float(hi - lo), "identified": bool(hi - lo < 1.0)}
    if scaled:
        s = draws.theta[:, d]
        lo_b, hi_b = posterior.scale_bounds
        log_width = float(np.diff(np.log(np.percentile(s, CREDIBLE)))[0])
        absolute = s * p.scale_reference
        a_lo, a_mid, a_hi = np.percentile(absolute, [CREDIBLE[0], 50, CREDIBLE[1]])
        # In coded units: the log interval over the log of the bounds, times the coded box's width 2.
        coded_width = 2.0 * log_width / math.log(hi_b / lo_b)
        parameters[p.scale_parameter] = {"median": float(a_mid), "credible_90": [float(a_lo), float(a_hi)],
                                         "coded_width": coded_width, "identified": bool(coded_width < 1.0)}
    d_all = posterior.ndim
    summary = {
        "parameters": parameters,
        "identified": sorted(n for n, q in parameters.items() if q["identified"]),
        "not_identified": sorted(n for n, q in parameters.items() if not q["identified"]),
        "exported": {"how": "the draw of highest posterior density (maximum a posteriori among the draws)",
                     "coded": [float(x) for x in exported[:len(p.coordinates)]],
                     "scale_factor": float(exported[d]) if scaled else 1.0,
                     "parameters": p.absolute(list(exported[:d]), float(exported[d]) if scaled else 1.0)},
        "targets": {t.name: {"mean": t.mean, "sd": t.sd, "n": t.n, "standard_error": t.standard_error}
                    for t in posterior.targets},
        "diagnostics": {"draws": int(len(samples.theta)), "kept": int(len(draws.theta)),
                        "walkers": samples.walkers, "steps": samples.steps, "converged": samples.converged,
                        "acceptance": samples.acceptance,
                        "autocorrelation_steps": samples.autocorrelation_steps,
                        "effective_samples": samples.effective_samples,
                        "emulator_sd_over_lab_se": settled, "coordinates": d_all},
        "identified_rule": "a 90 % credible interval narrower than half the prior's width, in coded units",
        "model_discrepancy": cal.config.get("model_discrepancy", 0.0),
    }
    write_target(os.path.join(folder, "posterior.json"), json.dumps(summary, indent=1) + "\n")
    return summary
