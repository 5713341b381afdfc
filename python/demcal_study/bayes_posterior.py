"""The posterior over a calibration's coded parameters, and its scale factor, given emulators of the DEM's responses
and the lab's targets with their scatter; sampled by MCMC.

The parameters: u in [-1, 1]^d, the coded space (uniform there: a parameter the space codes on a log scale is so
log-uniform) and, when the calibration scales its stress-like outputs exactly (a stress parameter multiplies every
stress output), a scale factor s, log-uniform between its bounds. Target i's DEM mean is s m_i(u) for a stress-like
output and m_i(u) otherwise, m_i the emulator's mean of the response over seeds; its uncertainty the emulator's SD
of that mean (scaled likewise), which the spread of the DEM's single-seed runs sets. The likelihood
(lab_targets.gaussian_log_likelihood) adds the lab mean's standard error, with the lab's correlation of outputs
measured on one specimen.

Why an emulator with MCMC rather than sequential Monte Carlo on the DEM itself: the DEM runs are the whole cost,
and sampling the emulators costs none, so the sampler can take as many steps as its diagnostics ask; emcee's
affine-invariant ensemble (Debian's python3-emcee) needs no step size tuned per problem and measures its own
autocorrelation time, the check a user reads.
"""
from dataclasses import dataclass

import numpy as np

from .lab_targets import gaussian_log_likelihood


@dataclass
class Samples:
    """Posterior draws: `theta` rows of (u..., s) (s only with a scale), equal weights; and what a user checks."""

    theta: np.ndarray
    log_prob: np.ndarray         # the log posterior of each draw (up to a constant)
    acceptance: float            # mean acceptance fraction of the walkers
    autocorrelation_steps: list  # integrated autocorrelation time per coordinate, in steps
    effective_samples: float     # draws / the longest autocorrelation time
    steps: int
    walkers: int
    converged: bool = True       # the kept half of the chain is at least 50 autocorrelation times long


class Posterior:
    """log p(u, s | lab) up to a constant, for emulators with `predict(u) -> (mean, sd)` over rows of coded points.

    targets: lab_targets.LabTarget per emulator, in the same order; stress_like: which of them scale with s;
    scale_bounds: (low, high) of s, or None when nothing scales; lab_correlation: the lab's correlation matrix of
    the targets (None: independent); discrepancy: the model's own misfit, a relative SD of each target's mean added
    to the DEM's SD in quadrature (a 2D model of 3D lab data cannot meet it better than that; 0: none)."""

    def __init__(self, emulators, targets, stress_like, dimensions, scale_bounds=None, lab_correlation=None,
                 scale_support=None, discrepancy=0.0):
        if len(emulators) != len(targets) or len(stress_like) != len(targets):
            raise ValueError("one emulator and one stress-like flag per target")
        if scale_bounds is None and any(stress_like):
            raise ValueError("stress-like targets need the scale factor's bounds")
        if scale_bounds is not None and not 0 < scale_bounds[0] < scale_bounds[1]:
            raise ValueError("the scale factor's bounds must be 0 < low < high")
        self.emulators, self.targets = list(emulators), list(targets)
        self.stress_like = np.array(stress_like, dtype=bool)
        self.d = int(dimensions)
        self.scale_bounds = scale_bounds
        # Rows of u -> (low, high) arrays of the scale factors that keep every stress-like parameter inside its
        # bounds there (None: the fixed bounds alone); the prior is then 1/s over that region of (u, s).
        self.scale_support = scale_support
        self.lab_r = None if lab_correlation is None else np.asarray(lab_correlation, dtype=float)
        if not 0.0 <= discrepancy < 1.0:
            raise ValueError("the model discrepancy is a relative SD in [0, 1)")
        self.discrepancy_sd = discrepancy * np.abs(np.array([t.mean for t in self.targets], dtype=float))

    @property
    def ndim(self):
        return self.d + (0 if self.scale_bounds is None else 1)

    def split(self, theta):
        """(u rows, s per row) of rows of theta."""
        theta = np.atleast_2d(theta)
        u = theta[:, :self.d]
        s = np.ones(len(theta)) if self.scale_bounds is None else theta[:, self.d]
        return u, s

    def predicted(self, theta):
        """The DEM means and their SDs the emulators give at rows of theta: two (rows, targets) arrays."""
        u, s = self.split(theta)
        means, sds = [], []
        for emulator, scaled in zip(self.emulators, self.stress_like):
            m, sd = emulator.predict(u)
            factor = s if scaled else 1.0
            means.append(factor * np.asarray(m, dtype=float))
            sds.append(factor * np.asarray(sd, dtype=float))
        return np.stack(means, axis=1), np.stack(sds, axis=1)

    def log_prob(self, theta):
        """log posterior of each row of theta (-inf outside the prior's support); a row per walker."""
        theta = np.atleast_2d(theta)
        u, s = self.split(theta)
        inside = np.all(np.abs(u) <= 1.0, axis=1)
        if self.scale_bounds is not None:
            inside &= (s >= self.scale_bounds[0]) & (s <= self.scale_bounds[1])
        if self.scale_support is not None and np.any(inside):
            low, high = self.scale_support(u[inside])
            inside[inside] = (s[inside] >= low) & (s[inside] <= high)
        out = np.full(len(theta), -np.inf)
        if not np.any(inside):
            return out
        mean, sd = self.predicted(theta[inside])
        sd = np.hypot(sd, self.discrepancy_sd)
        value = gaussian_log_likelihood(self.targets, mean, sd, lab_correlation=self.lab_r)
        if self.scale_bounds is not None:
            value -= np.log(s[inside])  # log-uniform prior on s
        out[inside] = value
        return out

    def default_walkers(self):
        """8 walkers per coordinate, at least 32: enough draws for 90 % intervals from a 4000-step chain."""
        return max(32, 8 * self.ndim)

    def sample(self, seed=1, walkers=None, steps=4000, start=None, max_steps=16000):
        """Draws from the posterior: an ensemble of `walkers` (default 8 per coordinate, at least 32) from `start`
        (rows inside the support; default: uniform over the fixed bounds), `steps` steps, the first half discarded,
        thinned by half the longest autocorrelation time. While the kept half is shorter than 50 autocorrelation
        times (emcee's rule for a trustworthy estimate), the chain runs on by `steps` more, up to `max_steps`;
        `converged` says whether it got there."""
        import emcee  # Debian's python3-emcee (scripts/install-deps.sh)

        ndim = self.ndim
        walkers = walkers or self.default_walkers()
        rng = np.random.default_rng(seed)
        if start is None:
            start = rng.uniform(-1.0, 1.0, size=(walkers, ndim))
            if self.scale_bounds is not None:
                lo, hi = np.log(self.scale_bounds[0]), np.log(self.scale_bounds[1])
                start[:, self.d] = np.exp(rng.uniform(lo, hi, size=walkers))
        sampler = emcee.EnsembleSampler(walkers, ndim, self.log_prob, vectorize=True)
        sampler.random_state = np.random.RandomState(seed).get_state()  # the same draws for the same seed
        chunk = steps
        state = sampler.run_mcmc(np.asarray(start, dtype=float), chunk, progress=False)
        while True:
            try:
                tau, converged = sampler.get_autocorr_time(discard=steps // 2), True
            except emcee.autocorr.AutocorrError as e:  # its estimate comes with it
                tau, converged = e.tau, False
            if converged or steps + chunk > max(max_steps, chunk):
                break
            state = sampler.run_mcmc(state, chunk, progress=False)
            steps += chunk
        thin = max(1, int(0.5 * float(np.max(tau))))
        chain = sampler.get_chain(discard=steps // 2, thin=thin, flat=True)
        log_prob = sampler.get_log_prob(discard=steps // 2, thin=thin, flat=True)
        return Samples(theta=chain, log_prob=log_prob, acceptance=float(np.mean(sampler.acceptance_fraction)),
                       autocorrelation_steps=[float(t) for t in tau],
                       effective_samples=float(walkers * (steps - steps // 2) / np.max(tau)), steps=steps,
                       walkers=walkers, converged=converged)
