"""The Bayesian search's part of a calibration report: each parameter's posterior (median, 90 % credible interval,
identified or not), the exported point and how it was chosen, and the sampler's diagnostics round by round, from
posterior.json beside the solution and the rounds the solution lists."""
import os

from .errors import load_json
from .report_text import md, num


def posterior_lines(out, solution):
    """Markdown lines of the posterior section, or none when the calibration has no posterior."""
    path = os.path.join(out, "posterior.json")
    if not os.path.exists(path):
        return []
    posterior = load_json(path, "posterior")
    lines = ["", "## Posterior (Bayesian search)", "",
             "Each parameter's posterior median and 90 % credible interval, given the targets with their scatter "
             "(below) and the emulators of the DEM runs on specimen 1; identified: "
             f"{md(posterior['identified_rule'])}. The draws are in [posterior.csv](posterior.csv).", "",
             "| parameter | median | 90 % credible interval | coded width (prior 2) | identified |", "|---|---|---|---|---|"]
    for name, p in sorted(posterior["parameters"].items()):
        lo, hi = p["credible_90"]
        lines.append(f"| {md(name)} | {num(p['median'])} | {num(lo)} to {num(hi)} | {num(p['coded_width'])} | "
                     f"{'yes' if p['identified'] else 'no'} |")
    lines += ["", "| target | lab mean | lab SD | specimens | standard error |", "|---|---|---|---|---|"]
    for name, t in sorted(posterior["targets"].items()):
        sd = "-" if t["sd"] is None else num(t["sd"])
        se = "-" if t["standard_error"] is None else num(t["standard_error"])
        lines.append(f"| {md(name)} | {num(t['mean'])} | {sd} | {t['n']} | {se} |")
    if posterior.get("model_discrepancy"):
        lines += ["", f"A model discrepancy of {num(100 * posterior['model_discrepancy'])} % of each target was added to "
                      "the DEM's SD in the likelihood: the model is not expected to meet the lab closer than that."]
    exported = posterior["exported"]
    lines += ["", f"Exported point: {md(exported['how'])}; it is the point the verifications above ran (then corrected "
                  "by specimen 1's measured offset where a verification missed)."]
    rows = [r for r in solution.get("rounds", []) if "bayes" in r]
    if rows:
        lines += ["", "| round | steps | draws kept | acceptance | longest autocorrelation, steps | chain >= 50 of them | "
                      "effective draws | emulators' SD / lab's standard error | runs after |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            d = r["bayes"]
            lines.append(f"| {r['round']} | {d['steps']} | {d['kept']} | {num(d['acceptance'])} | "
                         f"{num(max(d['autocorrelation_steps']))} | {'yes' if d.get('converged', True) else 'no'} | "
                         f"{num(d['effective_samples'])} | "
                         f"{num(d['emulator_sd_over_lab_se'])} | {r['runs']} |")
        lines += ["", "The search stops once the emulators' SD is at most half the lab's standard error for every "
                      "target (median over the draws): more DEM runs would barely narrow the posterior. An acceptance "
                      "of 0.2-0.5 and effective draws in the hundreds are what a sound MCMC run shows."]
    return lines + predictive_lines(out)


def predictive_lines(out):
    """Markdown lines of the posterior predictive (predictive.json), or none."""
    path = os.path.join(out, "predictive.json")
    if not os.path.exists(path):
        return []
    pred = load_json(path, "posterior predictive")
    n = pred["seeds_in_mean"]
    lines = ["", f"### What a mean of {n} fresh specimens will show", "",
             f"The posterior predictive of every output of every test, targeted or not: {md(pred['how'])}. At the "
             "exported point, and over the whole posterior (the parameters' uncertainty too). The last columns hold the "
             f"first verification's mean of {n} seeds ({md(pred['verification'])}) against the interval at the exported "
             "point.", "",
             "| output | target | at the exported point, 95 % | over the posterior, 95 % | specimens' SD | "
             f"verified {n}-seed mean | inside |", "|---|---|---|---|---|---|---|"]
    for name, r in sorted(pred["outputs"].items()):
        lo, hi = r["exported"]["interval_95"]
        plo, phi = r["posterior"]["interval_95"]
        target = "-" if r["target"] is None else num(r["target"])
        verified = "-" if r["verified_mean"] is None else num(r["verified_mean"])
        inside = "-" if r["inside"] is None else ("yes" if r["inside"] else "**no**")
        lines.append(f"| {md(name)} | {target} | {num(lo)} to {num(hi)} | {num(plo)} to {num(phi)} | "
                     f"{num(r['specimen_sd'])} | {verified} | {inside} |")
    return lines
