"""The trust-region search (docs/explanation/calibration_method.md, section 3): each round one Gauss-Newton
candidate of the local linear model of the residuals and one poising point, both on specimen 1; the radius grows
or shrinks with the agreement of the measured and the predicted misfit."""
import math

import numpy as np

from .. import trust_region
from ..calibrate_limits import INITIAL_RADIUS, MAX_ROUNDS, SMALLEST_RADIUS


class TrustRegionSearch:
    name = "trust-region"

    @staticmethod
    def plan(d):
        """(the rounds in words, the most points they run) for the progress line."""
        return f"up to {MAX_ROUNDS} rounds of 2", 2 * MAX_ROUNDS

    def run(self, cal, centre, best, label="r"):
        """Rounds of one Gauss-Newton candidate and one poising point on specimen 1 (section 3 of the docs), stored
        as rounds/LABEL02, LABEL03, ... Returns (centre, radius, best point, converged, blocked at the bounds)."""
        p = cal.problem
        converged, blocked = False, False
        radius = INITIAL_RADIUS
        reserve = cal.runner.verification_reserve()
        rejected = 0
        for k in range(2, 2 + MAX_ROUNDS):
            current = cal.measured_residuals(best)
            model = cal.fit(centre, radius)
            if cal.close_enough(current, cal.residual_noise(model)) or (
                    rejected >= 2 and np.max(np.abs(current)) <= cal.tolerance):
                converged = True
                break
            if not cal.runner.room_for(2, reserve):
                blocked = False  # stopped by the budget, not by the bounds
                break
            offset = np.zeros(len(p.modelled_outputs()))
            r0, jac = cal.jacobian(model.significant(), centre, offset)
            delta, predicted, held = trust_region.step(r0, jac, centre, radius)
            candidate = np.clip(centre + delta, -1, 1)
            at_bounds = [p.coordinates[i].name for i in held if abs(candidate[i]) >= 1 - 1e-9]
            step_length = float(np.max(np.abs(delta))) if len(delta) else 0.0
            if at_bounds and step_length < SMALLEST_RADIUS and np.max(np.abs(predicted)) > cal.tolerance:
                blocked = True  # the model would leave the space to go on: nothing left to try inside it
                break
            s, _, _ = cal.scale_at(model, candidate, offset)
            poise = np.clip(candidate + radius * trust_region.poising_direction(
                [q["u"] for q in cal.runner.points], candidate, radius), -1, 1)
            sp, _, _ = cal.scale_at(model, poise, offset)
            added = cal.runner.run_round(f"{label}{k:02d}", [(candidate, s), (poise, sp)])
            measured = cal.measured_residuals(added[0])
            phi_now = float(np.sum(current ** 2))
            phi_new = float(np.sum(measured ** 2)) if measured is not None else math.inf
            phi_pred = float(np.sum(np.asarray(predicted) ** 2))
            radius, accepted = trust_region.update_radius(radius, phi_now - phi_new, phi_now - phi_pred, step_length,
                                                          smallest=SMALLEST_RADIUS, largest=1.0)
            if accepted:
                centre, best = candidate, added[0]
            rejected = 0 if accepted else rejected + 1
            cal.rounds.append({"round": k if label == "r" else f"{label}{k}",
                                "centre_residuals_pct": (100 * current).tolist(),
                                "candidate_residuals_pct": None if measured is None else (100 * measured).tolist(),
                                "predicted_residuals_pct": (100 * np.asarray(predicted)).tolist(),
                                "accepted": accepted, "radius": radius, "held_at_bounds": at_bounds,
                                "scale": s, "runs": cal.runner.runs, "bounded_scale": cal.bounded_scale})
            cal.say(f"round {k}: candidate " + cal.format_residuals(measured) +
                     f" ({'accepted' if accepted else 'rejected'}), radius {radius:.3g}, {cal.runner.runs} runs")
            blocked = bool(at_bounds) and np.max(np.abs(predicted)) > cal.tolerance
            if radius <= SMALLEST_RADIUS and not accepted:
                break
        return centre, radius, best, converged, blocked
