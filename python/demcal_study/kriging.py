"""Gaussian-process (kriging) regression and the expected improvement of a calibration's misfit, for the
alternative search strategy of `calibrate --strategy kriging`.

Each modelled response gets its own GP: constant mean, anisotropic Matern 5/2 kernel, a nugget for the specimen
noise; the hyperparameters maximise the log marginal likelihood (Rasmussen & Williams 2006, eq. 2.30) over log
length-scales, log signal variance and log nugget, by a seeded random search refined coordinate by coordinate
(numpy only, d <= 15 and n <= 100 here). The misfit of a point is the sum of squared dimensionless residuals, a
function of the responses; its expected improvement over the best point is estimated by sampling the GP posteriors
with common random numbers, so the candidates are compared on the same draws."""
import numpy as np

SQRT5 = np.sqrt(5.0)


def matern52(a, b, length):
    d = np.sqrt(np.maximum(((a[:, None, :] - b[None, :, :]) / length) ** 2, 0.0).sum(axis=2))
    return (1.0 + SQRT5 * d + 5.0 / 3.0 * d ** 2) * np.exp(-SQRT5 * d)


class GP:
    def __init__(self, x, y, length, signal2, nugget2):
        self.x, self.length, self.signal2, self.nugget2 = np.asarray(x, float), length, signal2, nugget2
        y = np.asarray(y, float)
        k = signal2 * matern52(self.x, self.x, length) + nugget2 * np.eye(len(y))
        self.chol = np.linalg.cholesky(k + 1e-12 * signal2 * np.eye(len(y)))
        ones = np.ones(len(y))
        kinv_1 = self._solve(ones)
        self.mean = float(ones @ self._solve(y) / (ones @ kinv_1))  # generalised least squares constant mean
        self.alpha = self._solve(y - self.mean)

    def _solve(self, v):
        return np.linalg.solve(self.chol.T, np.linalg.solve(self.chol, v))

    def predict(self, u):
        """Posterior mean and SD of the latent response (noise-free) at the rows of u."""
        ks = self.signal2 * matern52(np.atleast_2d(u), self.x, self.length)
        mean = self.mean + ks @ self.alpha
        v = np.linalg.solve(self.chol, ks.T)
        var = np.maximum(self.signal2 - (v ** 2).sum(axis=0), 1e-300)
        return mean, np.sqrt(var)


def log_likelihood(x, y, theta):
    d = x.shape[1]
    length, signal2, nugget2 = np.exp(theta[:d]), np.exp(theta[d]), np.exp(theta[d + 1])
    try:
        gp = GP(x, y, length, signal2, nugget2)
    except np.linalg.LinAlgError:
        return -np.inf, None
    r = np.asarray(y, float) - gp.mean
    value = -0.5 * r @ gp.alpha - np.log(np.diag(gp.chol)).sum() - 0.5 * len(y) * np.log(2 * np.pi)
    return value, gp


def fit(x, y, seed=1, tries=60):
    """The GP of y over the rows of x (coded coordinates) with maximum-likelihood hyperparameters."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    d = x.shape[1]
    spread = max(float(np.var(y)), 1e-12)
    rng = np.random.default_rng(seed)
    lows = np.concatenate([np.full(d, np.log(0.05)), [np.log(spread * 0.05), np.log(spread * 1e-6)]])
    highs = np.concatenate([np.full(d, np.log(20.0)), [np.log(spread * 20.0), np.log(spread * 0.5)]])
    best_theta, best_value, best_gp = None, -np.inf, None
    for _ in range(tries):
        theta = rng.uniform(lows, highs)
        value, gp = log_likelihood(x, y, theta)
        if value > best_value:
            best_theta, best_value, best_gp = theta, value, gp
    step = 0.5
    for _ in range(6):  # coordinate refinement
        for i in range(d + 2):
            for sign in (-1.0, 1.0):
                theta = best_theta.copy()
                theta[i] = np.clip(theta[i] + sign * step, lows[i], highs[i])
                value, gp = log_likelihood(x, y, theta)
                if value > best_value:
                    best_theta, best_value, best_gp = theta, value, gp
        step *= 0.5
    return best_gp


def expected_improvement(gps, misfit, candidates, best, draws=256, seed=2):
    """E[max(best - misfit(responses), 0)] at each candidate row, responses drawn from the GPs' posteriors (the same
    standard-normal draws for every candidate). misfit maps an array (draws x candidates x responses) to (draws x
    candidates)."""
    rng = np.random.default_rng(seed)
    means, sds = zip(*(gp.predict(candidates) for gp in gps))
    mean, sd = np.stack(means, axis=1), np.stack(sds, axis=1)  # candidates x responses
    z = rng.standard_normal((draws, 1, len(gps)))
    samples = mean[None, :, :] + sd[None, :, :] * z
    return np.maximum(best - misfit(samples), 0.0).mean(axis=0), mean
