"""make calibrate's verification: the candidate run on fresh specimens until every target is met within the
tolerance with a 95 % half-width inside it, corrected between verifications by specimen 1's local model with the
measured offset of the population (and a secant slope once two verifications of enough seeds exist); the
trust-region search is re-entered when the scale factor leaves its bounds (docs/explanation/calibration_method.md)."""
import math
import os

import numpy as np

from . import calibrate_runs, searches, trust_region
from .calibrate_limits import (EXIT_BUDGET, EXIT_MET, EXIT_UNREACHABLE, FIRST_VERIFICATION_SEEDS,
                               MAX_VERIFICATION_SEEDS)
from .calibrate_report import pct

OFFSET_TRIM = 0.2  # share of the verified specimens cut from each end of the offset's mean (one of 5, 4 of 20)
# Verifications of at least this many seeds measure the population's response well enough (a mean's SE of a few %
# at a CV of 12 %) for the step between two of them to correct the model's slope along it (secant_update).
SECANT_MIN_SEEDS = 10


def trimmed_mean(rows, cut_fraction):
    """Per column, the mean of the rows left after the int(cut_fraction * n) lowest and as many highest are cut."""
    rows = np.sort(np.asarray(rows, dtype=float), axis=0)
    cut = int(cut_fraction * len(rows))
    return rows[cut:len(rows) - cut].mean(axis=0)


def disk_factor_for(half_width_pct, tolerance, seeds, on_seeds):
    """How many times its disks a specimen would need for a 95 % half-width of half_width_pct, measured on `seeds`
    seeds, to come down to the tolerance on `on_seeds` seeds: a specimen's scatter falls about as one over the square
    root of its disks (docs/explanation/calibration_method.md, "Which disks measure nu": twice the disks took nu's CV from 11.6 to
    8.2 %), and a half-width is t(0.975, n - 1) times the scatter over sqrt(n)."""
    per_seed = half_width_pct * math.sqrt(seeds) / trust_region.t975(seeds - 1)
    on = per_seed * trust_region.t975(on_seeds - 1) / math.sqrt(on_seeds)
    return (on / (100 * tolerance)) ** 2


def trimmed_mean_variance(rows, cut_fraction):
    """Per column, the variance of trimmed_mean's value (Tukey & McLaughlin 1963): the winsorized variance over
    (1 - 2 g)^2 n, g the share cut from each end; the plain mean's s^2 / n when nothing is cut."""
    rows = np.sort(np.asarray(rows, dtype=float), axis=0)
    n = len(rows)
    cut = int(cut_fraction * n)
    if n < 2:
        return np.full(rows.shape[1:], np.inf)
    wins = rows.copy()
    if cut:
        wins[:cut] = rows[cut]
        wins[n - cut:] = rows[n - cut - 1]
    return wins.var(axis=0, ddof=1) / ((1.0 - 2.0 * cut / n) ** 2 * n)


def secant_update(jacobian, earlier, later):
    """Broyden's rank-one update of the residuals' Jacobian from two measured points (centre, residuals, and
    optionally the variance of each residual as measured): along the step between them it takes the measured change,
    across it the Jacobian stays as it was.

    Measured residuals are means over a few specimens, so their change over a short step can be mostly noise; with
    variances given, each residual's mismatch between the measured change and the Jacobian's is shrunk by
    max(0, 1 - noise variance / mismatch^2) (positive-part James-Stein), so only what the two means can tell apart
    from their noise changes the slope. On yineng_packsand the unshrunk update took a mismatch in sigma_u / E of
    -5.6 % with a noise SD of 2.8 % for the whole truth, and its correction moved sigma_u / E 2.7 times what it expected
    (docs/explanation/calibration_benchmark.md)."""
    (c1, r1, *v1), (c2, r2, *v2) = earlier, later
    d = np.asarray(c2, float) - np.asarray(c1, float)
    dd = float(d @ d)
    if dd < 1e-12 or len(r1) != len(r2) or len(r2) != jacobian.shape[0]:
        return jacobian
    mismatch = np.asarray(r2) - np.asarray(r1) - jacobian @ d
    if v1 and v2:
        noise = np.asarray(v1[0], float) + np.asarray(v2[0], float)
        with np.errstate(divide="ignore", invalid="ignore"):
            keep = np.where(mismatch != 0, np.maximum(0.0, 1.0 - noise / mismatch ** 2), 0.0)
        mismatch = mismatch * keep
    return jacobian + np.outer(mismatch, d) / dd


class Verifier:
    def run(self, cal, centre, radius):
        p = cal.problem
        offset = np.zeros(len(p.modelled_outputs()))
        next_seed = 2  # specimen 1 made the design; verify on others
        pooled = []    # (n, variance per modelled output over those specimens)
        deviations = []  # per verified specimen: its modelled outputs less specimen 1's model at that centre
        population = []  # per verification of enough seeds: (centre, the trimmed mean's residuals, their variance)
        verified = None  # the last point a verification ran at
        k = 0
        while True:
            k += 1
            left = cal.runner.left()
            model = cal.fit(centre, radius)
            point = cal.point_at(model, centre, offset)
            if left < 2 * cal.runner.tests:
                return cal.finish("budget", f"the budget of {cal.runner.budget} DEM runs is spent", EXIT_BUDGET,
                                   point=verified or point)
            interval, wanted = point["scale_interval"], point["wanted_scale_factor"]
            outside = not (interval[0] * (1 - 1e-9) <= wanted <= interval[1] * (1 + 1e-9))
            if outside and not cal.bounded_scale and pooled:
                # A verification's offset moved the wanted factor out: the correction steps carry the scale term
                # from here on (a search on specimen 1 alone would drop that offset).
                cal.bounded_scale = True
            if outside and not cal.bounded_scale:
                # The dimensionless solution found is one of many; others may want a scale the bounds allow. Search
                # on from here with the scale held at its bound and the scale target as one more residual.
                cal.bounded_scale = True
                cal.say(f"{p.scale_target} wants a scale factor {wanted:.4g} here, outside what the bounds allow "
                         f"({interval[0]:.4g} to {interval[1]:.4g}): searching on with the scale at its bound and "
                         f"{p.scale_target} as a residual")
                best = cal.best_point()  # by the residuals with the scale term now
                centre, radius, best, converged, blocked = searches.by_name("trust-region").run(
                    cal, np.array(best["u"]), best, label="b")
                cal.crn = dict(cal.crn or {}, bounded={
                    "converged": converged, "centre": centre.tolist(), "residuals_pct":
                    None if cal.measured_residuals(best) is None else (100 * cal.measured_residuals(best)).tolist()})
                if not converged and blocked:
                    reach = cal.reachable()
                    lo, hi = p.absolute_bounds[p.scale_parameter]
                    return cal.finish("unreachable", f"{p.scale_target} needs a scale factor outside the bounds at "
                                       f"the first solution, and searching on with the scale at its bound "
                                       f"({p.scale_parameter} bounds {lo:.4g} to {hi:.4g}, or a ratio's) ends on the "
                                       "bounds of the space still missing the targets; the points run reach " +
                                       ", ".join(f"{n} {r['lowest_error_pct']:+.0f} % to {r['highest_error_pct']:+.0f} %"
                                                 for n, r in reach.items()), EXIT_UNREACHABLE, centre=centre)
                k -= 1
                continue
            if outside and abs(math.log(point["scale_factor"] / wanted)) > cal.tolerance:
                at = p.absolute(centre, wanted)
                beyond = ", ".join(f"{n} {at[n]:.4g} (bounds {lo:.4g} to {hi:.4g})"
                                   for n, (lo, hi) in sorted(p.absolute_bounds.items()) if not lo <= at[n] <= hi)
                return cal.finish("unreachable", f"{p.scale_target} needs a scale factor {wanted:.4g}, outside what "
                                   f"the bounds allow ({interval[0]:.4g} to {interval[1]:.4g}): at that factor "
                                   f"{beyond}", EXIT_UNREACHABLE, point=point)
            each = left // cal.runner.tests  # seeds of every test the budget holds
            seeds, most = min(FIRST_VERIFICATION_SEEDS, each), min(MAX_VERIFICATION_SEEDS, each)
            folder = os.path.join(cal.out, "verify", f"v{k:02d}")
            v = calibrate_runs.verify(cal.tools, cal.scene, folder, point["x"], p.targets, point["predicted"],
                                      next_seed, seeds, most, cal.tolerance, cal.quiet,
                                      intervals=point["prediction_interval_95"], curves=cal.curves)
            verified = point
            used = len(v["seeds"])
            cal.runner.spend(used)
            next_seed += used
            rows = v["outputs"]
            met = v["passed"] and all(r["half_width_pct"] is not None and r["half_width_pct"] <= 100 * cal.tolerance
                                      for r in rows.values())
            cal.verifications.append({"round": k, "folder": os.path.join("verify", f"v{k:02d}"), "seeds": used,
                                       "first_seed": next_seed - used, "passed": v["passed"], "verdict": v["verdict"],
                                       "met": met, "scale": point["scale_factor"], "runs": cal.runner.runs,
                                       "errors_pct": {o: r["relative_error_pct"] for o, r in rows.items()},
                                       "half_width_pct": {o: r["half_width_pct"] for o, r in rows.items()}})
            cal.say(f"verification {k} on seeds {next_seed - used}-{next_seed - 1}: " +
                     ", ".join(f"{o} {pct(r['relative_error_pct'], '+.1f')} % (+-{pct(r['half_width_pct'], '.1f')})"
                               for o, r in rows.items()) + (" - met" if met else "") + f"; {cal.runner.runs} runs")
            if met and cal.config.get("check_resolution"):
                # The met point again on finer specimens (the coarse runs are reused): the shift a user will see.
                v = calibrate_runs.verify(cal.tools, cal.scene, folder, point["x"], p.targets, point["predicted"],
                                          next_seed - used, seeds, most, cal.tolerance, cal.quiet,
                                          intervals=point["prediction_interval_95"],
                                          scale_resolution=cal.config["check_resolution"], curves=cal.curves)
                cal.say("at disk radii / {:g}: ".format(cal.config["check_resolution"]) + ", ".join(
                    f"{o} shift {s:+.1f} %" for o, s in v["finer"]["shift_pct"].items() if s is not None))
            if met:
                return cal.finish("met", "every target within the tolerance, every 95 % half-width too", EXIT_MET,
                                   point=point, verification=v)
            if v["passed"] and used >= most:
                wide = [o for o, r in rows.items() if r["half_width_pct"] is None
                        or r["half_width_pct"] > 100 * cal.tolerance]
                widths = [rows[o]["half_width_pct"] for o in wide if rows[o]["half_width_pct"] is not None]
                larger = "a larger specimen scatters less"
                if widths and len(widths) == len(wide) and used >= 2:
                    factor = disk_factor_for(max(widths), cal.tolerance, used, MAX_VERIFICATION_SEEDS)
                    larger = (f"{MAX_VERIFICATION_SEEDS} seeds, more than the budget left, would do" if factor <= 1
                              else f"on {MAX_VERIFICATION_SEEDS} seeds a specimen with about {factor:.1f}x the disks "
                              "would scatter little enough")
                return cal.finish("noisy", f"the means are within the tolerance but {', '.join(wide)} scatter too "
                                   f"much for a {100 * cal.tolerance:g} % half-width in {used} seeds: {larger}",
                                   EXIT_BUDGET, point=point, verification=v)
            # The specimens against specimen 1's model: an offset per response over every verified specimen, and
            # their scatter, which the prediction interval of one specimen must include. The offset is a trimmed
            # mean: one far seed (nu 2.5x the median at a dilatant point) would otherwise move the next point by
            # its whole share of a plain mean and the verification after it would overshoot the other way.
            zs = [[p.to_model(o, s["macro"][o], point["scale_factor"]) for o in p.modelled_outputs()]
                  for s in v["seeds"] if s["status"] == "ok"
                  and all(isinstance(s["macro"].get(o), (int, float)) for o in p.modelled_outputs())]
            zs = np.array([row for row in zs if all(math.isfinite(x) for x in row)])
            if len(zs) >= 2:
                deviations.extend(zs - model.predict(centre))
                pooled.append((len(zs), zs.var(axis=0, ddof=1)))
                total = sum(n for n, _ in pooled)
                offset = trimmed_mean(np.array(deviations), OFFSET_TRIM)
                cal.specimen_variance = sum((n - 1) * var for n, var in pooled) / max(total - len(pooled), 1)
                if len(zs) >= SECANT_MIN_SEEDS:
                    zbar = dict(zip(p.modelled_outputs(), trimmed_mean(zs, OFFSET_TRIM)))
                    each = [cal.residuals_of(dict(zip(p.modelled_outputs(), row)), centre) for row in zs]
                    population.append((np.array(centre, float), cal.residuals_of(zbar, centre),
                                       trimmed_mean_variance(each, OFFSET_TRIM)))
            r0, jac = cal.jacobian(model.significant(), centre, offset)
            model_jac = jac
            if len(population) >= 2:
                # Specimen 1's local model can misjudge how far a step moves the population (nu at dilatant
                # points moved 1.6 times what it predicted on yineng_siltstone); two verified points measure it.
                jac = secant_update(jac, population[-2], population[-1])
                cal.verifications[-1]["secant_step"] = jac is not model_jac
            delta, _, _ = trust_region.step(r0, jac, centre, max(radius, 0.05))
            record_correction(cal, r0, model_jac, jac, delta)
            centre = np.clip(centre + delta, -1, 1)


def record_correction(cal, r0, model_jac, jac, delta):
    """What the correction after a verification expects: the residuals (%) it starts from and the change its
    step should make, by specimen 1's model and, once two verifications measured it, by the secant; so a report
    can tell an overshoot of the model from the noise of the means it corrected."""
    labels = cal.residual_labels()
    entry = {"from_pct": dict(zip(labels, (100 * np.asarray(r0)).tolist())),
             "model_change_pct": dict(zip(labels, (100 * (model_jac @ delta)).tolist()))}
    text = "model " + cal.format_residuals(model_jac @ delta)
    if jac is not model_jac:
        entry["secant_change_pct"] = dict(zip(labels, (100 * (jac @ delta)).tolist()))
        text += ", secant " + cal.format_residuals(jac @ delta)
    cal.verifications[-1]["correction"] = entry
    cal.say(f"correcting from {cal.format_residuals(r0)}: the step should change them by {text}")

# -- bookkeeping -------------------------------------------------------------------------------------------
