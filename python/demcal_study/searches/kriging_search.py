"""The kriging search (`make calibrate STRATEGY=kriging`): Gaussian processes of the responses over every point
on specimen 1, and each round the two points of largest expected improvement of the misfit."""
import numpy as np

from .. import kriging
from ..calibrate_limits import INITIAL_RADIUS, MAX_ROUNDS


class KrigingSearch:
    name = "kriging"

    @staticmethod
    def plan(d):
        """(the rounds in words, the most points they run) for the progress line."""
        return f"up to {MAX_ROUNDS} rounds of 2", 2 * MAX_ROUNDS

    def run(self, cal, centre, best, label="r"):
        """The alternative: Gaussian processes of the responses over every point on specimen 1, and each round the
        two points of largest expected improvement of the misfit (the second by the kriging believer: the first
        added at its predicted mean), inside a box of +-2 initial radii around the best point. Returns as
        TrustRegionSearch.run (the radius is the initial one: the verification's local model uses it)."""
        p = cal.problem
        names = p.modelled_outputs()
        a, c = cal.residual_map()
        misfit = lambda z: ((z @ a.T + c) ** 2).sum(axis=-1)  # noqa: E731
        converged, blocked = False, False
        reserve = cal.runner.verification_reserve()
        half = 2 * INITIAL_RADIUS
        d = len(centre)
        stale = 0
        for k in range(2, 2 + MAX_ROUNDS):
            rows = cal.runner.usable()
            x = np.array([r[0] for r in rows])
            z = np.array([r[1] for r in rows])
            current = cal.measured_residuals(best)
            gps = [kriging.fit(x, z[:, j], seed=k) for j in range(len(names))]
            noise = np.sqrt(((a ** 2) * np.array([gp.nugget2 for gp in gps])).sum(axis=1))
            if cal.close_enough(current, noise):
                converged = True
                break
            if not cal.runner.room_for(2, reserve):
                break
            if stale >= 2 and nowhere_within_tolerance(cal, gps, d) and np.any(np.abs(centre) >= 0.98):
                blocked = True  # two rounds without a better point, and the GPs see nothing better anywhere
                break
            rng = np.random.default_rng(k)
            low, high = np.maximum(centre - half, -1.0), np.minimum(centre + half, 1.0)
            candidates = np.vstack([rng.uniform(low, high, size=(3000, d)),
                                    np.clip(centre + 0.05 * rng.standard_normal((1000, d)), low, high)])
            best_misfit = float(np.sum(current ** 2))
            ei, mean = kriging.expected_improvement(gps, misfit, candidates, best_misfit, seed=k)
            # No draw improves anywhere: take the lowest predicted misfit rather than an arbitrary candidate.
            first = int(np.argmax(ei)) if np.max(ei) > 0 else int(np.argmin(misfit(mean)))
            believed = [kriging.GP(np.vstack([x, candidates[first]]), np.append(z[:, j], mean[first, j]), gp.length,
                                   gp.signal2, gp.nugget2) for j, gp in enumerate(gps)]
            ei2, mean2 = kriging.expected_improvement(believed, misfit, candidates, best_misfit, seed=k)
            ei2[first] = -1.0
            if np.max(ei2) > 0:
                second = int(np.argmax(ei2))
            else:
                order = np.argsort(misfit(mean2))
                second = int(order[1] if order[0] == first else order[0])
            picks = [candidates[first], candidates[second]]
            entries = []
            for u in picks:
                zu = dict(zip(names, [gp.predict(u[None, :])[0][0] for gp in gps]))
                s = p.scale_for(zu)
                lo, hi = p.scale_interval(u)
                entries.append((u, min(max(s, lo), hi)))
            added = cal.runner.run_round(f"r{k:02d}", entries)
            improved = False
            for q in added:
                r = cal.measured_residuals(q)
                if r is not None and float(np.sum(r ** 2)) < float(np.sum(cal.measured_residuals(best) ** 2)):
                    best, centre, improved = q, np.array(q["u"]), True
            stale = 0 if improved else stale + 1
            measured = cal.measured_residuals(added[0]) if added else None
            cal.rounds.append({"round": k, "centre_residuals_pct": (100 * current).tolist(),
                                "candidate_residuals_pct": None if measured is None else (100 * measured).tolist(),
                                "predicted_residuals_pct": (100 * (mean[first] @ a.T + c)).tolist(),
                                "accepted": improved, "radius": half, "held_at_bounds": [],
                                "expected_improvement": float(ei[first]), "scale": entries[0][1], "runs": cal.runner.runs})
            cal.say(f"round {k}: EI points " + cal.format_residuals(measured) +
                     f" ({'improved' if improved else 'no better'}), best " +
                     cal.format_residuals(cal.measured_residuals(best)) + f", {cal.runner.runs} runs")
        return centre, INITIAL_RADIUS, best, converged, blocked


def nowhere_within_tolerance(cal, gps, d):
    """Whether the GPs' means miss the tolerance on some target everywhere in the space (20,000 points,
    seeded): the tolerance applies to each residual."""
    a, c = cal.residual_map()
    anywhere = np.random.default_rng(0).uniform(-1, 1, size=(20000, d))
    means = np.stack([gp.predict(anywhere)[0] for gp in gps], axis=1)
    return float(np.min(np.max(np.abs(means @ a.T + c), axis=1))) > cal.tolerance
