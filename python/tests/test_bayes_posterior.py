"""The posterior sampler against problems whose posterior is known in closed form: linear emulators with no
uncertainty of their own and Gaussian lab targets give a Gaussian posterior (inside the prior's box), and an exactly
scaled stress with a pinned dimensionless output gives the scale factor its ratio."""
import numpy as np
import pytest

from demcal_study.bayes_posterior import Posterior
from demcal_study.lab_targets import LabTarget


class Linear:
    """An emulator that knows its response exactly: a + b . u, SD `sd`."""

    def __init__(self, a, b, sd=0.0):
        self.a, self.b, self.sd = a, np.asarray(b, dtype=float), sd

    def predict(self, u):
        u = np.atleast_2d(u)
        return self.a + u @ self.b, np.full(len(u), self.sd)


def test_linear_gaussian_posterior_mean_and_covariance():
    a = np.array([[2.0, 0.5], [0.3, 1.5]])
    b0 = np.array([10.0, 5.0])
    truth = np.array([0.2, -0.3])
    targets = [LabTarget("x", float(b0[0] + a[0] @ truth), 0.1, 1), LabTarget("y", float(b0[1] + a[1] @ truth), 0.2, 4)]
    posterior = Posterior([Linear(b0[0], a[0]), Linear(b0[1], a[1])], targets, [False, False], dimensions=2)
    samples = posterior.sample(seed=3, steps=6000)
    se = np.array([t.standard_error for t in targets])
    precision = a.T @ np.diag(1 / se ** 2) @ a
    covariance = np.linalg.inv(precision)  # the mean is the truth: the targets sit on the model
    assert samples.effective_samples > 1000
    assert 0.2 < samples.acceptance < 0.9
    # Monte Carlo error of the mean: sd / sqrt(effective samples), about 2e-3 here; 5 of them allowed.
    tolerance = 5 * np.sqrt(np.diag(covariance) / samples.effective_samples)
    assert np.all(np.abs(samples.theta.mean(axis=0) - truth) < tolerance)
    assert np.allclose(np.cov(samples.theta.T), covariance, rtol=0.15, atol=0.15 * np.sqrt(covariance[0, 0] * covariance[1, 1]))


def test_the_emulators_own_sd_widens_the_posterior_as_the_summed_variance_says():
    targets = [LabTarget("x", 3.0, 0.06, 1)]
    narrow = Posterior([Linear(3.0, [1.0])], targets, [False], dimensions=1).sample(seed=5, steps=4000)
    wide = Posterior([Linear(3.0, [1.0], sd=0.08)], targets, [False], dimensions=1).sample(seed=5, steps=4000)
    assert np.std(narrow.theta[:, 0]) == pytest.approx(0.06, rel=0.1)
    assert np.std(wide.theta[:, 0]) == pytest.approx(0.10, rel=0.1)  # sqrt(0.06^2 + 0.08^2)


def test_a_pinned_output_and_an_exactly_scaled_stress_give_the_scale_its_ratio():
    # nu = 0.3 + 0.1 u pins u at 0.4; sigma = s (1 + 0.5 u) = 90 MPa then asks s = 75.
    targets = [LabTarget("nu", 0.34, 0.0005, 1), LabTarget("sigma_u_MPa", 90.0, 0.9, 1)]
    posterior = Posterior([Linear(0.3, [0.1]), Linear(1.0, [0.5])], targets, [False, True], dimensions=1,
                          scale_bounds=(10.0, 500.0))
    samples = posterior.sample(seed=7, steps=5000)
    u, s = samples.theta[:, 0], samples.theta[:, 1]
    assert np.median(u) == pytest.approx(0.4, abs=0.01)
    assert np.median(s) == pytest.approx(75.0, rel=0.01)
    # sigma's 1 % SD over s: the scale's spread, with the small share u's spread adds.
    assert np.std(s) / np.median(s) == pytest.approx(0.01, rel=0.2)


def test_the_prior_bounds_hold():
    targets = [LabTarget("x", 10.0, 1.0, 1)]  # the model reaches at most 2: the posterior piles at u = 1
    samples = Posterior([Linear(1.0, [1.0])], targets, [False], dimensions=1).sample(seed=2, steps=2000)
    assert samples.theta.min() >= -1.0 and samples.theta.max() <= 1.0
    assert np.median(samples.theta[:, 0]) > 0.8
    assert Posterior([Linear(1.0, [1.0])], targets, [False], dimensions=1).log_prob(np.array([[1.5]]))[0] == -np.inf


def test_the_same_seed_gives_the_same_draws():
    targets = [LabTarget("x", 3.0, 0.1, 1)]
    p = Posterior([Linear(3.0, [1.0])], targets, [False], dimensions=1)
    assert np.array_equal(p.sample(seed=4, steps=500).theta, p.sample(seed=4, steps=500).theta)


def test_inconsistent_arguments_are_refused():
    with pytest.raises(ValueError, match="one emulator"):
        Posterior([Linear(1.0, [1.0])], [], [False], dimensions=1)
    with pytest.raises(ValueError, match="scale factor's bounds"):
        Posterior([Linear(1.0, [1.0])], [LabTarget("s", 1.0, 0.1)], [True], dimensions=1)


def test_the_search_emulator_predicts_as_its_gaussian_process():
    # ScaleFreeEmulator keeps the inverse of the process's Cholesky factor for speed: the same mean and SD as
    # kriging.GP.predict to rounding, and exp of them (SD by the first-order rule) for a logged stress.
    from demcal_study import kriging
    from demcal_study.searches.bayes_search import ScaleFreeEmulator
    rng = np.random.default_rng(3)
    x = rng.uniform(-1, 1, size=(25, 3))
    y = np.sin(2 * x[:, 0]) + x[:, 1] ** 2 + 0.01 * rng.standard_normal(25)
    gp = kriging.fit(x, y, seed=2)
    u = rng.uniform(-1, 1, size=(40, 3))
    mean, sd = gp.predict(u)
    m, s = ScaleFreeEmulator(gp, logged=False).predict(u)
    np.testing.assert_allclose(m, mean, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(s, sd, rtol=1e-6, atol=1e-9)
    m, s = ScaleFreeEmulator(gp, logged=True).predict(u)
    np.testing.assert_allclose(m, np.exp(mean), rtol=1e-10)
    np.testing.assert_allclose(s, np.exp(mean) * sd, rtol=1e-6, atol=1e-9)


def test_a_chain_shorter_than_fifty_autocorrelation_times_runs_on_up_to_its_cap():
    # 100 kept steps cannot be 50 autocorrelation times of an ensemble (tau is several steps): the chain grows by
    # its first length, 200, up to the cap, and says it did not converge; a long enough one stops at once.
    p = Posterior([Linear(3.0, [1.0])], [LabTarget("y", 3.2, 0.1)], [False], dimensions=1)
    short = p.sample(seed=4, steps=200, max_steps=600)
    assert short.steps == 600 and not short.converged
    assert 50 * max(short.autocorrelation_steps) > 300
    long = p.sample(seed=4, steps=4000, max_steps=16000)
    assert long.steps == 4000 and long.converged


def test_a_stated_model_discrepancy_widens_the_posterior_by_its_share_of_the_target():
    # A 2 % discrepancy of a target of 3.0 is an SD of 0.06 beside the lab's 0.08: 0.10 in all.
    targets = [LabTarget("x", 3.0, 0.08, 1)]
    plain = Posterior([Linear(3.0, [1.0])], targets, [False], dimensions=1).sample(seed=5, steps=4000)
    with_misfit = Posterior([Linear(3.0, [1.0])], targets, [False], dimensions=1,
                            discrepancy=0.02).sample(seed=5, steps=4000)
    assert np.std(plain.theta[:, 0]) == pytest.approx(0.08, rel=0.1)
    assert np.std(with_misfit.theta[:, 0]) == pytest.approx(0.10, rel=0.1)
    with pytest.raises(ValueError):
        Posterior([Linear(3.0, [1.0])], targets, [False], dimensions=1, discrepancy=1.0)


def test_the_predictive_interval_is_students_when_the_specimens_sd_comes_from_few_seeds():
    from demcal_study.posterior_predictive import half_width_95
    # The specimens' term alone, SD from 5 seeds: t(0.975, 4) = 2.776.
    half, dof = half_width_95(0.0, 1.0, 4)
    assert dof == pytest.approx(4) and half == pytest.approx(2.776, abs=1e-3)
    # The emulator's term alone (no specimen scatter): the normal 1.96.
    half, dof = half_width_95(1.0, 0.0, 4)
    assert dof == float("inf") and half == pytest.approx(1.960, abs=1e-3)
    # Equal variances: Welch-Satterthwaite's (a + b)^2 (m - 1) / b^2 = 4 x 4 = 16 degrees of freedom, t = 2.120.
    half, dof = half_width_95(1.0, 1.0, 4)
    assert dof == pytest.approx(16) and half == pytest.approx(2.120 * 2 ** 0.5, abs=2e-3)
