"""The numerical core of the adaptive calibration: a local linear model of the responses around the current
candidate, fitted by weighted least squares to every DEM point so far (points near the candidate weigh most), the
Gauss-Newton step of its residuals inside the trust box, and the classical rule that sizes the box (Conn, Gould &
Toint, Trust-Region Methods, 2000, ch. 6: grow it when the model predicted the improvement and the step was held by
the box, shrink it when the model was wrong). Everything is in coded coordinates u in [-1, 1]^d.

No DEM, no files: pure functions of arrays, so a test drives them with a closed-form response."""
import numpy as np

# Weights: a point at coded distance (infinity norm) t from the centre weighs exp(-(t / (WEIGHT_RADII * radius))^2),
# so the points of the current box count fully and those of earlier, wider boxes still steady the fit.
WEIGHT_RADII = 2.0
RIDGE = 1e-8  # a tiny ridge on the slopes keeps the fit defined before there are d + 1 points near the centre


# Two-sided 95 % points of Student's t (tables), by degrees of freedom; between them linear in 1 / dof.
_T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228,
         12: 2.179, 15: 2.131, 20: 2.086, 25: 2.060, 30: 2.042, 40: 2.021, 60: 2.000, 120: 1.980}


def t975(dof):
    """t(0.975, dof) for a real dof >= 1 (an effective sample size gives fractional ones); 1.960 at infinity."""
    dof = max(float(dof), 1.0)
    keys = sorted(_T975)
    if dof >= keys[-1]:
        a, ta, tb = 1.0 / keys[-1], _T975[keys[-1]], 1.960
        return tb + (ta - tb) * (1.0 / dof) / a
    for lo, hi in zip(keys, keys[1:]):
        if lo <= dof <= hi:
            w = (1.0 / dof - 1.0 / hi) / (1.0 / lo - 1.0 / hi)
            return _T975[hi] + w * (_T975[lo] - _T975[hi])
    return _T975[1]


class LocalModel:
    """z(u) ~ intercept + slopes (u - centre), one column per modelled response; with the weighted residual
    variance and the coefficients' covariance (per unit variance) for slopes' t values and prediction intervals."""

    def __init__(self, centre, intercept, slopes, sigma2, cov_unscaled, dof):
        self.centre = np.asarray(centre, float)
        self.intercept = np.asarray(intercept, float)
        self.slopes = np.asarray(slopes, float)  # responses x d
        self.sigma2 = np.asarray(sigma2, float)  # per response
        self.cov_unscaled = cov_unscaled           # Cov(beta) / sigma^2 over (1, u - centre)
        self.dof = dof

    def predict(self, u):
        return self.intercept + self.slopes @ (np.asarray(u, float) - self.centre)

    def slope_t(self):
        """Each slope over its standard error (responses x d): which coordinates the data show an effect of."""
        se = np.sqrt(np.outer(self.sigma2, np.diag(self.cov_unscaled)[1:]))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(se > 0, np.abs(self.slopes) / se, np.inf)

    def significant(self, t_min=2.0):
        """The model with every slope the data cannot tell from zero (|t| < t_min) set to zero, as a screening
        would drop it: a step along a slope that is only noise moves the candidate for nothing. A response whose
        slopes are all insignificant keeps its largest one."""
        t = self.slope_t()
        slopes = self.slopes.copy()
        for k in range(slopes.shape[0]):
            keep = t[k] >= t_min
            if not keep.any() and slopes.shape[1]:
                keep[int(np.argmax(t[k]))] = True
            slopes[k, ~keep] = 0.0
        return LocalModel(self.centre, self.intercept, slopes, self.sigma2, self.cov_unscaled, self.dof)

    def prediction_sd(self, u):
        """SD of a new observation at u (one specimen): sqrt(sigma^2 (1 + x0' (X'WX)^-1 x0)) per response."""
        x0 = np.concatenate([[1.0], np.asarray(u, float) - self.centre])
        return np.sqrt(self.sigma2 * (1.0 + x0 @ self.cov_unscaled @ x0))

    def interval_half_width(self, u, extra_variance=0.0):
        """Half-width of the 95 % prediction interval of one new observation at u (t with the fit's effective
        degrees of freedom); extra_variance adds what the fit's points cannot see (specimen-to-specimen scatter)."""
        sd = np.sqrt(self.prediction_sd(u) ** 2 + extra_variance)
        return t975(self.dof) * sd


def weights(points, centre, radius):
    t = np.max(np.abs(np.asarray(points, float) - centre), axis=1)
    return np.exp(-(t / (WEIGHT_RADII * radius)) ** 2)


def fit_local(points, responses, centre, radius, w=None):
    """Weighted least squares of every response column on (1, u - centre); `w` overrides the weights."""
    u = np.asarray(points, float)
    z = np.asarray(responses, float)
    n, d = u.shape
    w = weights(u, centre, radius) if w is None else np.asarray(w, float)
    x = np.hstack([np.ones((n, 1)), u - centre])
    xtw = x.T * w
    xtwx = xtw @ x + RIDGE * np.diag([0.0] + [1.0] * d)
    xtwx_inv = np.linalg.pinv(xtwx)
    beta = xtwx_inv @ (xtw @ z)  # (d + 1) x responses
    # The weights say where the model should fit, not how precise a point is: the coefficients' covariance is
    # the sandwich A X'W^2X A (A = (X'WX)^-1) times the residual variance, unchanged when all weights scale.
    cov_unscaled = xtwx_inv @ ((x.T * w ** 2) @ x) @ xtwx_inv
    resid = z - x @ beta
    effective = w.sum() ** 2 / max((w ** 2).sum(), 1e-300)  # Kish's effective sample size
    dof = max(effective - (d + 1), 1.0)
    sigma2 = (w[:, None] * resid ** 2).sum(axis=0) / max(w.sum(), 1e-300) * effective / dof
    return LocalModel(centre, beta[0], beta[1:].T, sigma2, cov_unscaled, dof)


def step(r0, jacobian, centre, radius, damping=0.0):
    """The least-norm Gauss-Newton step of r0 + J delta inside |delta_i| <= radius and -1 <= centre + delta <= 1.

    Fewer residuals than coordinates (the usual case: two dimensionless targets, six ratios) leave many zero-
    residual steps; the least-norm one changes the candidate least. Coordinates that would leave the box are held
    at its face one at a time (the worst first) and the rest solved again: an active set.
    Returns (delta, predicted residuals, the coordinates held at a face)."""
    r0 = np.asarray(r0, float)
    jac = np.asarray(jacobian, float)
    d = jac.shape[1]
    lower = np.maximum(-radius, -1.0 - centre)
    upper = np.minimum(radius, 1.0 - centre)
    delta = np.zeros(d)
    held = []
    free = list(range(d))
    for _ in range(d + 1):
        if not free:
            break
        rhs = -(r0 + jac[:, held] @ delta[held]) if held else -r0
        a = jac[:, free]
        if damping > 0:
            a = np.vstack([a, np.sqrt(damping) * np.eye(len(free))])
            rhs = np.concatenate([rhs, np.zeros(len(free))])
        sol, *_ = np.linalg.lstsq(a, rhs, rcond=None)
        trial = delta.copy()
        trial[free] = sol
        over = np.maximum(trial - upper, lower - trial)
        over[held] = 0.0
        worst = int(np.argmax(over))
        if over[worst] <= 1e-12:
            delta = trial
            break
        delta[worst] = upper[worst] if trial[worst] > upper[worst] else lower[worst]
        held.append(worst)
        free.remove(worst)
    delta = np.clip(delta, lower, upper)
    return delta, r0 + jac @ delta, sorted(held)


def update_radius(radius, actual_reduction, predicted_reduction, step_length, *, smallest, largest):
    """The new trust radius and whether the candidate is accepted as the new centre."""
    if predicted_reduction <= 0:
        ratio = -1.0 if actual_reduction <= 0 else 1.0
    else:
        ratio = actual_reduction / predicted_reduction
    accepted = actual_reduction > 0
    if ratio < 0.25:
        # The model was wrong at this distance: halve the box (the new points near the centre improve the model).
        radius = max(smallest, 0.5 * radius)
    elif ratio > 0.75 and step_length >= 0.99 * radius:
        radius = min(largest, 2.0 * radius)
    elif accepted and step_length < 0.5 * radius:
        # Inside the box and right: the solution is near; the next design gathers close to it.
        radius = max(smallest, 0.5 * radius)
    return radius, accepted


def poising_direction(points, centre, radius):
    """The unit direction in which the points near the centre spread least (smallest eigenvector of their
    weighted scatter about the centre): one new point along it keeps the local slopes determined."""
    u = np.asarray(points, float) - centre
    w = weights(points, centre, radius)
    scatter = (u.T * w) @ u
    values, vectors = np.linalg.eigh(scatter)
    v = vectors[:, 0]
    return v / np.max(np.abs(v))
