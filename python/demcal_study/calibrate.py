"""calibrate: one command from a scene and targets to verified micro-parameters, no study file.

    python -m demcal_study calibrate --scene S.json --target sigma_u_MPa=48 --target E_GPa=6.5 --target nu=0.27
                                     [--space SP.json] [--fixed NAME=VALUE ...] [--tolerance 0.05] [--budget 80]
                                     [--name NAME] [--out-root build/calibrations]

The strategy (docs/explanation/calibration_method.md):
1. dimensionless form (calibration_problem.py): ratios of the stress-like parameters to a scale parameter against
   dimensionless targets; the scale factor that meets the scale target (E) is exact, so it costs no DEM run;
2. a trust region on common specimen 1 (trust_region.py): a small space-filling design around the reference, then
   each round one candidate (the Gauss-Newton step of a local linear model fitted with weights near the centre) and
   one point that keeps the model's slopes determined, until specimen 1 meets the targets within a third of the
   tolerance, or the box has shrunk;
3. verification on fresh seeds (demcal-verify: 5 to start, seeds added until the 95 % interval is narrower than the
   tolerance); when it fails, the offset between those specimens' mean and specimen 1 corrects the model and the
   corrected candidate is verified on other fresh seeds, until the targets are met or the budget is spent.

The parts: this file is the runner (the budget, the stored runs, the residual algebra, the design, the finish),
searches/ the searches of step 2 behind one protocol (trust region, kriging), calibrate_verify.py step 3.

Exit 0 met, 3 unreachable (the report says what the model reaches), 4 budget spent. Rerunning resumes: every
decision is a function of the stored DEM results, and the batches repeat no finished point."""
import csv
import difflib
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

from . import calibrate_runs, commands, curve_targets, executables, lab_targets, outputs, posterior_predictive, trust_region
from . import searches
from .calibrate_limits import (EXIT_BUDGET, EXIT_FAILED, EXIT_MET, EXIT_UNREACHABLE,  # noqa: F401 (the exit codes)
                               FIRST_VERIFICATION_SEEDS, INITIAL_RADIUS, MAX_VERIFICATION_SEEDS)
from .calibrate_runner import Runner
from .calibrate_verify import Verifier
from .calibrate_report import report
from .calibration_problem import Problem
from .errors import Problems, StudyError, fail, load_json
from .files import write_target

# The local fit weighs points within about this many coded units even when the step box is smaller: slopes from
# a few close points would be mostly specimen noise, and a correction step or a scale factor built on them misses.
SMALLEST_FIT_RADIUS = 0.125
CRN_FRACTION = 1.0 / 3.0  # specimen 1 must meet the targets within this fraction of the tolerance
# ... or within its measured noise, but never a noise allowance above this fraction: the first fits span the whole
# initial box, so their scatter is partly curvature, and an allowance near the tolerance stopped searches at the
# band's edge (wang2017_sandstone stopped at +5.5 % before this cap, docs/explanation/calibration_benchmark.md).
NOISE_CAP_FRACTION = 0.5
CHECK_SEEDS = 4  # specimens of each check test at the solution
# Sharpness (log units) of the soft scale bounds whose slope the bounded search follows: bounds within about 5 %
# of the tightest share its slope (Problem.scale_interval).
SCALE_BOUND_SHARPNESS = 20.0


def parse_assignments(items, what, problems=None):
    """{name: value} of NAME=NUMBER items (each item may hold several, separated by spaces). A bad item or a name given
    twice is a problem: noted in `problems` (and left out) when given, else raised."""
    out = {}
    for item in items or []:
        for part in item.split():
            name, sep, value = part.partition("=")
            try:
                number = float(value)
            except ValueError:
                sep = ""
            if not sep or not name:
                message = f"{what}: \"{part}\" is not NAME=NUMBER"
            elif name in out:
                message = f"{what}: {name} is given twice ({out[name]:g} and {number:g}): give it once"
            else:
                out[name] = number
                continue
            if problems is None:
                fail(message)
            problems.add(message)
    return out


def parse_lab_targets(items, problems):
    """({name: mean}, {name: {"sd", "n"}} of those given with their scatter) from --target items (each may hold
    several, separated by spaces): NAME=VALUE, NAME=MEAN+-SD or NAME=MEAN+-SD/n=N. Each bad item or repeated name is
    one problem."""
    targets, uncertainty = {}, {}
    for item in items or []:
        for part in item.split():
            t = lab_targets.parse_target(part)
            if isinstance(t, str):
                problems.add(t)
            elif t.name in targets:
                problems.add(f"--target: {t.name} is given twice ({targets[t.name]:g} and {t.mean:g}): give it once")
            else:
                targets[t.name] = t.mean
                if t.sd is not None:
                    uncertainty[t.name] = {"sd": t.sd, "n": t.n}
    return targets, uncertainty


def default_name(scene, targets):
    base = os.path.splitext(os.path.basename(scene))[0]
    return base + "_" + "_".join(f"{k}{v:g}" for k, v in sorted(targets.items()))


class Calibration:
    def __init__(self, config, out, tools, quiet=False):
        self.config, self.out, self.tools, self.quiet = config, out, tools, quiet
        self.scene = config["scene"]
        # A measured curve's points are outputs the scene does not describe: its runs' curves give them.
        self.curves = config.get("curves", [])
        description = curve_targets.extend_description(executables.describe(self.scene, config.get("space")),
                                                       self.curves)
        self.description = description
        space = load_json(config["space"], "parameter space") if config.get("space") else None
        self.problem = Problem(description, config["targets"], space=space, fixed=config.get("fixed"),
                               scale_parameter=config.get("scale_parameter"), where=config.get("where", "calibrate"))
        self.tolerance = config["tolerance"]
        # The budget counts lab-test runs: a point of a test list runs each of its tests.
        self.runner = Runner(self.problem, self.scene, out, tools, config["budget"],
                             outputs.tests_described(description), self.curves, quiet)
        self.rounds = []   # what each round decided
        self.verifications = []
        self.posterior = None  # the Bayesian search's last posterior: its draws and exported point
        self.specimen_variance = 0.0  # of the modelled responses over fresh specimens, once a verification ran
        # Set when the scale factor the scale target wants leaves the bounds: the search then goes on with the
        # scale held at its bound and the scale target as one more residual (bounded_scale_residual).
        self.bounded_scale = False
        self.started = time.time()
        # Other tests run at the solution once it is verified (predictions, not targets): each must take every
        # parameter the calibration sets, or it would not be the same material.
        self.defaults = {name: q["value"] for name, q in description["parameters"].items()}
        # What the report's final parameter set lists beside the solution: every parameter's unit and scene value.
        self.scene_parameters = {name: {"value": q["value"], "unit": q.get("unit", "")}
                                 for name, q in description["parameters"].items()}
        self.check_tests = list(config.get("check_tests", []))
        for path in self.check_tests:
            have = executables.describe(path)["parameters"]
            missing = sorted(set(self.defaults) - set(have))
            if missing:
                fail(f"--check-test {path}: it lacks the calibrated scene's parameter(s) {', '.join(missing)}: "
                     "it would not test the same material")

    def say(self, message):
        if not self.quiet:
            print(f"calibrate: {message}", file=sys.stderr, flush=True)

    # -- models and residuals --------------------------------------------------------------------------------------
    def fit(self, centre, radius):
        rows = self.runner.usable()
        if len(rows) < 2:
            fail(f"{self.out}: fewer than two DEM points ran; see the round folders for the reasons")
        return trust_region.fit_local([r[0] for r in rows], [r[1] for r in rows], np.asarray(centre),
                                      max(radius, SMALLEST_FIT_RADIUS))

    def z_of(self, model, u, offset):
        values = model.predict(u) + offset
        return dict(zip(self.problem.modelled_outputs(), values))

    def residuals_at(self, model, u, offset):
        return self.residuals_of(self.z_of(model, u, offset), u)

    def residuals_of(self, z, u):
        """The search's residuals for modelled responses z at coordinates u: the dimensionless targets', and the
        bounded scale term once it is on."""
        r = self.problem.residuals(z)
        if self.bounded_scale:
            r.append(self.bounded_scale_residual(z, u))
        return np.asarray(r)

    def bounded_scale_residual(self, z, u, sharpness=None):
        """The scale target's relative error (log) once the scale factor it wants is clipped to what the bounds
        allow at u: zero inside the bounds, and a residual like the others outside them (with soft bounds for
        its slope: Problem.scale_interval)."""
        wanted = self.problem.scale_for(z)
        low, high = self.problem.scale_interval(u, sharpness)
        return math.log(min(max(wanted, low), high) / wanted)

    def jacobian(self, model, u, offset):
        r0 = self.residuals_at(model, u, offset)

        def soft_scale_term(v):
            return self.bounded_scale_residual(self.z_of(model, v, offset), v, SCALE_BOUND_SHARPNESS)

        soft0 = soft_scale_term(u) if self.bounded_scale else None
        cols = []
        for i in range(len(u)):
            e = np.array(u, float)
            e[i] += 1.0
            col = self.residuals_at(model, e, offset) - r0  # exact for the model, which is linear in u
            if self.bounded_scale:
                # The clipped scale term is not linear in u (the bounds move with the ratios): its slope where it
                # stands, over soft bounds. With the hard min, two parameters at their bounds together (the
                # strengths' two standard deviations of ldb_granite) each show no slope, since lowering one alone
                # leaves the other holding the scale, and the search never frees it.
                h = 1e-4
                e = np.array(u, float)
                e[i] += h
                col[-1] = (soft_scale_term(e) - soft0) / h
            cols.append(col)
        return r0, np.array(cols).T if cols else np.zeros((len(r0), 0))

    def residual_noise(self, model):
        """SD of each residual on one specimen, from the local fit's scatter (responses taken as independent)."""
        names = self.problem.modelled_outputs()
        z0 = dict(zip(names, model.intercept))
        r0 = np.asarray(self.problem.residuals(z0))
        var = np.zeros(len(r0))
        for j, name in enumerate(names):
            z = dict(z0)
            z[name] += 1.0
            var += (np.asarray(self.problem.residuals(z)) - r0) ** 2 * model.sigma2[j]
        if self.bounded_scale:  # log(E / s) itself: its own scatter
            var = np.append(var, model.sigma2[self.problem.modelled_outputs().index(self.problem.scale_target)])
        return np.sqrt(var)

    def measured_residuals(self, point):
        if point["status"] != "ok":
            return None
        return self.residuals_of(self.runner.modelled(point["outputs"], point["scale"]), point["u"])

    def residual_labels(self):
        labels = self.problem.residual_labels()
        return labels + [f"{self.problem.scale_target} at the bounded scale"] if self.bounded_scale else labels

    def scale_at(self, model, u, offset):
        s = self.problem.scale_for(self.z_of(model, u, offset))
        low, high = self.problem.scale_interval(u)
        return min(max(s, low), high), (low, high), s

    def initial_design(self, centre):
        d = len(centre)
        n = 2 * d  # a linear model has d + 1 coefficients: the rest estimate the noise the slopes are judged by
        path = os.path.join(self.out, "rounds", "design_lhs.csv")
        if not os.path.exists(path) and d > 0:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            cmd = [self.tools.program("demcal-doe"), "lhs", "--factors", str(d), "--runs", str(n), "--criterion",
                   "maximin", "--seed", "1", "--out", path, "--quiet"]
            if subprocess.run(cmd).returncode != 0:
                fail(f"{path}: demcal-doe lhs failed")
        if d == 0:
            return []
        with open(path) as f:
            rows = list(csv.DictReader(f))
        out = []
        for row in rows:
            coded = np.array([float(row[f"x{i + 1}"]) for i in range(d)])
            out.append(np.clip(centre + INITIAL_RADIUS * coded, -1.0, 1.0))
        return out

    # -- the strategy --------------------------------------------------------------------------------------------
    def run(self):
        p = self.problem
        centre = np.array(p.reference_point())
        self.say(f"{len(p.coordinates)} coordinates ({', '.join(c.name for c in p.coordinates)}), scale parameter "
                 f"{p.scale_parameter or '-'} fitted to {p.scale_target or '-'}; dimensionless targets "
                 + ", ".join(f"{k} {v:.4g}" for k, v in p.dimensionless_targets().items()))
        first = self.runner.run_round("r00_reference", [(centre, 1.0)])
        wall = self.runner.point_wall_s("r00_reference")
        design = self.initial_design(centre)
        search = searches.by_name(self.config.get("strategy", "trust-region"))
        rounds_text, round_points = search.plan(len(centre))
        planned = (1 + len(design) + round_points) * self.runner.tests
        each = (f" (each point runs {self.runner.tests} tests, each counted)" if self.runner.tests > 1
                else "")
        tests, budget = self.runner.tests, self.runner.budget
        most = min(budget, planned + 2 * MAX_VERIFICATION_SEEDS * tests) / tests  # points, verifications included
        self.say(f"planned DEM points: 1 reference + {len(design)} design + {rounds_text} on specimen 1,"
                 f" then verification on {FIRST_VERIFICATION_SEEDS}-{MAX_VERIFICATION_SEEDS} fresh seeds per round{each};"
                 f" at most {budget} test runs in all. One point alone took {wall:.1f} s: about "
                 f"{self.estimate_min(most, wall):.1f}"
                 f" min at most if each of {self.tools.jobs} job(s) ran as fast (jobs share the cores: measured again"
                 " after the design)")
        if first and first[0]["status"] != "ok":
            self.say(f"the reference point failed: {first[0]['reason']}")
        self.runner.run_round("r01_design", [(u, 1.0) for u in design])
        shared_wall = self.runner.point_wall_s("r01_design")
        if shared_wall > 0:
            left = max(self.runner.left(), 0) / self.runner.tests
            self.say(f"the design's points took {shared_wall:.1f} s each with {self.tools.jobs} job(s) at once: at most"
                     f" about {self.estimate_min(left, shared_wall):.1f} min more for the {left:.0f} point(s) the"
                     " budget has left")
        radius = INITIAL_RADIUS
        best = self.best_point()
        if best is None:
            return self.finish("failed", "no DEM point of the first design ran", EXIT_FAILED)
        centre = np.array(best["u"])
        centre, radius, best, converged, blocked = search.run(self, centre, best)
        self.crn = {"converged": converged, "centre": centre.tolist(), "rounds": len(self.rounds), "residuals_pct":
                    (100 * self.measured_residuals(best)).tolist()}
        if not converged and blocked:
            reach = self.reachable()
            missed = ", ".join(f"{n} from {r['lowest_error_pct']:+.0f} % to {r['highest_error_pct']:+.0f} % of its target"
                               for n, r in reach.items() if r["lowest_error_pct"] > 100 * self.tolerance
                               or r["highest_error_pct"] < -100 * self.tolerance) or "no single target alone"
            return self.finish("unreachable", "the candidate sits on the bounds of the space and the model still "
                               f"misses the targets there; the points run reach {missed}", EXIT_UNREACHABLE,
                               centre=centre)
        return Verifier().run(self, centre, radius)

    def close_enough(self, residuals, noise):
        """Specimen 1 meets the dimensionless targets within a third of the tolerance, or within what the scatter of
        nearby points lets a model tell apart, capped at half the tolerance (the verification's offset does the
        rest)."""
        allowance = np.minimum(np.asarray(noise, float), NOISE_CAP_FRACTION * self.tolerance)
        return bool(np.all(np.abs(residuals) <= np.maximum(CRN_FRACTION * self.tolerance, allowance)))

    def residual_map(self):
        """The residuals are affine in the modelled responses: r = A z + c."""
        names = self.problem.modelled_outputs()
        z0 = dict.fromkeys(names, 0.0)
        c = np.asarray(self.problem.residuals(z0))
        cols = []
        for name in names:
            z = dict(z0)
            z[name] = 1.0
            cols.append(np.asarray(self.problem.residuals(z)) - c)
        return np.array(cols).T, c

    def point_at(self, model, centre, offset):
        """Everything the DEM runs and the report states at coordinates `centre`: the scale factor (the bounds'
        interval and the factor E wants), the scene parameters, the prediction (specimen 1's model plus the
        specimens' offset) and its 95 % prediction interval for one specimen."""
        p = self.problem
        scale, interval, wanted = self.scale_at(model, centre, offset)
        z = self.z_of(model, centre, offset)
        half = model.interval_half_width(centre, self.specimen_variance)
        return {"coordinates": [float(x) for x in centre], "scale_factor": scale, "scale_interval": list(interval),
                "wanted_scale_factor": wanted, "x": p.absolute(centre, scale), "ratios": p.ratios(centre),
                "predicted": {o: p.from_model(o, z[o], scale) for o in p.modelled_outputs()},
                "prediction_interval_95": {o: [p.from_model(o, z[o] - half[i], scale),
                                               p.from_model(o, z[o] + half[i], scale)]
                                           for i, o in enumerate(p.modelled_outputs())},
                "offset": dict(zip(p.modelled_outputs(), [float(x) for x in offset]))}

    def best_point(self):
        best, value = None, math.inf
        for q in self.runner.points:
            r = self.measured_residuals(q)
            if r is not None and np.all(np.isfinite(r)) and float(np.sum(r ** 2)) < value:
                best, value = q, float(np.sum(r ** 2))
        return best

    def estimate_min(self, runs, wall_s):
        return runs * wall_s / max(int(self.tools.jobs), 1) / 60.0

    def format_residuals(self, r):
        if r is None:
            return "failed"
        return ", ".join(f"{n} {100 * x:+.1f} %" for n, x in zip(self.residual_labels(), r))

    def finish(self, status, why, code, point=None, centre=None, verification=None):
        """solution.json (the point verified last, or `point`, or the local model's at `centre`), the final
        verification, and the closing line."""
        p = self.problem
        solution = {"status": status, "why": why, "exit_code": code, "dem_runs": self.runner.runs,
                    "budget": self.runner.budget, "wall_s": time.time() - self.started, "targets": p.targets,
                    "tolerance": self.tolerance, "problem": dict(p.describe(), residuals=self.residual_labels()),
                    "bounded_scale": self.bounded_scale,
                    "rounds": self.rounds, "verifications": self.verifications, "crn": getattr(self, "crn", None),
                    "scene_parameters": self.scene_parameters}
        if point is None and centre is not None:
            point = self.point_at(self.fit(centre, INITIAL_RADIUS), centre, np.zeros(len(p.modelled_outputs())))
        if point is not None:
            solution.update(point)
        solution["reachable"] = self.reachable()
        write_target(os.path.join(self.out, "solution.json"), json.dumps(solution, indent=1) + "\n")
        if verification is None and self.verifications:
            verification = load_json(os.path.join(self.out, self.verifications[-1]["folder"], "verification.json"),
                                     "verification")
        if verification is not None and "finer" in verification:
            solution["finer_check"] = {"factor": verification["finer"]["factor"],
                                       "runs": len(verification["finer"]["seeds"]),
                                       "shift_pct": verification["finer"]["shift_pct"],
                                       "note": "runs beyond the calibration's budget"}
            write_target(os.path.join(self.out, "solution.json"), json.dumps(solution, indent=1) + "\n")
        if verification is not None:
            write_target(os.path.join(self.out, "verification.json"), json.dumps(verification, indent=1) + "\n")
        if self.posterior and self.posterior.get("draws") is not None:
            posterior_predictive.predictive(self, self.posterior["draws"], self.posterior["exported"])
        if status in ("met", "noisy") and point is not None and self.check_tests:
            solution["checks"] = self.run_checks(point["x"])
            write_target(os.path.join(self.out, "solution.json"), json.dumps(solution, indent=1) + "\n")
        self.say(f"{status}: {why} ({self.runner.runs} DEM runs, {(time.time() - self.started) / 60:.1f} min)")
        return code

    def run_checks(self, x):
        """Each check test at the solution, on fresh seeds after the verifications' (runs listed apart from the
        budget, as the resolution check's)."""
        first = 1 + max((v["first_seed"] + v["seeds"] - 1 for v in self.verifications), default=1)
        values = dict(self.defaults, **x)
        out = []
        for k, path in enumerate(self.check_tests):
            name = os.path.splitext(os.path.basename(path))[0]
            folder = os.path.join("checks", f"c{k + 1}_{name}")
            described = executables.describe(path)
            have = described["parameters"]
            shown = {o for o, d in described["outputs"].items() if d.get("headline")}  # the test's headline values
            result = calibrate_runs.check(self.tools, path, os.path.join(self.out, folder),
                                          {n: v for n, v in values.items() if n in have}, first, CHECK_SEEDS,
                                          self.quiet)
            out.append(dict(result, scene=path, folder=folder, first_seed=first, seeds=CHECK_SEEDS,
                            note="runs beyond the calibration's budget"))
            self.say(f"check {name} on seeds {first}-{first + CHECK_SEEDS - 1}: " + ", ".join(
                f"{o} {s['mean']:.4g}" for o, s in sorted(result["outputs"].items()) if o in shown))
        return out

    def reachable(self):
        """The range of every dimensionless target seen on specimen 1: what the model reaches."""
        out = {}
        names = self.residual_labels()
        for q in self.runner.points:
            r = self.measured_residuals(q)
            if r is None:
                continue
            for n, x in zip(names, r):
                lo, hi = out.get(n, (math.inf, -math.inf))
                out[n] = (min(lo, 100 * x), max(hi, 100 * x))
        return {n: {"lowest_error_pct": lo, "highest_error_pct": hi} for n, (lo, hi) in out.items()}


STRATEGIES = searches.NAMES


def number_option(value, what, problems, whole=False):
    """An option's number (given as text on the command line, or as a number), or None with the problem noted."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        x = value
    else:
        try:
            x = int(value) if whole else float(value)
        except (TypeError, ValueError):
            problems.add(f"{what}: \"{value}\" is not {'a whole number' if whole else 'a number'}")
            return None
    if not math.isfinite(x) or (whole and x != int(x)):
        problems.add(f"{what}: {value} is not {'a whole number' if whole else 'a finite number'}")
        return None
    return int(x) if whole else float(x)


def did_you_mean(name, names):
    close = difflib.get_close_matches(name, list(names), n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""


def range_text(low, high, unit):
    """[low, high] of describe, either end null for none: "0 to 90 deg", "at least 0 MPa"."""
    unit = "" if unit in (None, "", "1") else f" {unit}"
    if low is not None and high is not None:
        return f"{low:g} to {high:g}{unit}"
    return f"at least {low:g}{unit}" if low is not None else f"at most {high:g}{unit}"


def check_targets(targets, description, problems):
    """The targets the scene's outputs can be held to: an output or a ratio A/B of two, a finite non-zero value, inside
    the output's physical range where describe declares one ("range": [low, high], null for an open end; a ratio has
    none). Returns those that pass; each other one is a problem."""
    outs = description["outputs"]
    good = {}
    for name, value in targets.items():
        known = problems.check(outputs.is_output, outs, name, "--target")
        if known is None:
            continue
        if not known:
            problems.add(f"--target: {name} is not an output of the scene, nor a ratio A/B of two"
                         f"{did_you_mean(name, outs)} (outputs: {', '.join(sorted(outs))})")
            continue
        if problems.check(outputs.output_info, outs, name, "--target") is None:
            continue
        if not math.isfinite(value):
            problems.add(f"--target: {name}: {value} is not a finite number")
            continue
        if value == 0:
            problems.add(f"--target: {name}: 0 cannot be a target (its errors are relative to it)")
            continue
        declared = outs[name].get("range") if name in outs else None
        if isinstance(declared, (list, tuple)) and len(declared) == 2 and outside(value, *declared):
            problems.add(f"--target: {name}={value:g} lies outside its physical range, "
                         f"{range_text(*declared, outs[name].get('unit'))}")
            continue
        good[name] = value
    return good


def outside(value, low, high):
    """Whether `value` lies outside [low, high] (None: an open end)."""
    return (low is not None and value < low) or (high is not None and value > high)


def check_fixed(fixed, description, problems):
    """Fixed values: each a parameter of the scene, inside its physical bounds. Returns those that pass."""
    params = description["parameters"]
    good = {}
    for name, value in fixed.items():
        if name not in params:
            problems.add(f"--fixed: {name} is not a parameter of the scene{did_you_mean(name, params)}")
            continue
        if not math.isfinite(value):
            problems.add(f"--fixed: {name}: {value} is not a finite number")
            continue
        low, high = params[name].get("low"), params[name].get("high")
        if outside(value, low, high):
            problems.add(f"--fixed: {name}={value:g} lies outside the scene's physical bounds, "
                         f"{range_text(low, high, params[name].get('unit'))}")
            continue
        good[name] = value
    return good


def holds_no_work(out):
    """Whether a calibration folder holds no DEM result: only its settings (a command refused before this version
    checked everything first, or stopped before its first run), which other settings may then replace."""
    return not any(os.path.exists(os.path.join(out, name)) for name in ("rounds", "verify", "checks", "solution.json"))


def checked_command(args):
    """Every option of `calibrate` checked before anything is written: the scene (through demcal-dem describe), the
    space, the targets, the fixed values, the budget, the tolerance, the checks and the strategy, and the folder it
    would write. Returns (config, out folder, whether stored settings without any work are replaced); raises
    StudyErrors with every problem found, one line each."""
    problems = Problems()
    if getattr(args, "unrecognized", None):
        problems.add(f"calibrate: unrecognized arguments: {' '.join(args.unrecognized)}")
    targets, uncertainty = parse_lab_targets(args.target, problems)
    lab_correlation = None
    measured = None
    if getattr(args, "lab_specimens", None):
        measured = problems.check(lab_targets.read_specimens, args.lab_specimens)
    if not args.target and not getattr(args, "lab_specimens", None):
        problems.add("--target: give at least one NAME=VALUE (e.g. --target E_GPa=6.5)")
    fixed = parse_assignments(args.fixed, "--fixed", problems)
    tolerance = number_option(args.tolerance, "--tolerance", problems)
    if tolerance is not None and not (0 < tolerance < 1):
        problems.add(f"--tolerance: {tolerance} must lie in (0, 1)")
        tolerance = None
    budget = number_option(args.budget, "--budget", problems, whole=True)
    if budget is not None and budget < 1:
        problems.add(f"--budget: {budget} must be a positive number of DEM runs")
        budget = None
    strategy = args.strategy or "trust-region"
    if strategy not in STRATEGIES:
        problems.add(f"--strategy: {strategy} is not one of {', '.join(STRATEGIES)}")
    if strategy == "bayes":
        for name in targets:
            if name not in uncertainty:
                problems.add(f"--target: {name}: the Bayesian search weighs each target by the lab's scatter: write "
                             f"{name}=MEAN+-SD (or +-SD/n=N for a mean of N specimens), or give --lab-specimens")
    discrepancy = None
    if getattr(args, "model_discrepancy", None) is not None:
        discrepancy = number_option(args.model_discrepancy, "--model-discrepancy", problems)
        if discrepancy is not None and not 0 < discrepancy < 1:
            problems.add(f"--model-discrepancy: {discrepancy:g} must lie in (0, 1) (a fraction of each target)")
            discrepancy = None
        if strategy != "bayes":
            problems.add("--model-discrepancy: only the Bayesian search weighs the targets by their uncertainty: "
                         "add --strategy bayes")
    check_resolution = None
    if args.check_resolution is not None:
        check_resolution = number_option(args.check_resolution, "--check-resolution", problems)
        if check_resolution is not None and not check_resolution > 1:
            problems.add(f"--check-resolution: {check_resolution:g} must be above 1 (the radii are divided by it)")
    scene_ok = False
    if not args.scene:
        problems.add("--scene: give the scene to calibrate (--scene SCENE.json)")
    elif not os.path.exists(args.scene):
        problems.add(f"--scene: {args.scene} does not exist")
    else:
        scene_ok = True
    space_ok = True
    if args.space and not os.path.exists(args.space):
        problems.add(f"--space: {args.space} does not exist")
        space_ok = False
    check_tests = list(args.check_test or [])
    for path in check_tests:
        if not os.path.exists(path):
            problems.add(f"--check-test: {path} does not exist")

    description = problems.check(executables.describe, args.scene) if scene_ok else None
    lab_names = {}  # a lab specimen file's names as the targets name them
    if measured is not None:  # the lab's specimens join the targets, named as the scene's outputs
        file_names = measured[1]
        if description:
            measured = lab_targets.named_as_outputs(measured, description["outputs"])
        by_name, names, r = measured
        lab_names = dict(zip(file_names, names))
        for name, t in by_name.items():
            if name in targets:
                problems.add(f"--lab-specimens {args.lab_specimens}: {name} is also a --target: give it once")
                continue
            targets[name], uncertainty[name] = t.mean, {"sd": t.sd, "n": t.n}
        if len(names) > 1 and not np.array_equal(r, np.eye(len(names))):
            lab_correlation = {"names": names, "matrix": r.tolist()}
    curves = measured_curves(args, targets, uncertainty, description, strategy, problems)
    if any(c.get("by_specimen") for c in curves):
        lab_correlation = specimens_correlation(curves, lab_names, args, targets) or lab_correlation
    if description and curves:
        description = curve_targets.extend_description(description, curves)
    tests = outputs.tests_described(description) if description else 1
    coordinates = 0
    if description:
        good_targets = check_targets(targets, description, problems)
        good_fixed = check_fixed(fixed, description, problems)
        space = None
        if args.space and space_ok:
            space = problems.check(load_json, args.space, "parameter space")
            # demcal-dem checks that the space narrows the scene, and names the field when it does not.
            if space is not None and problems.check(executables.describe, args.scene, args.space) is None:
                space = None
                space_ok = False
        if good_targets and space_ok:
            problem = problems.check(Problem, description, good_targets, space=space, fixed=good_fixed,
                                     scale_parameter=args.scale_parameter, where="calibrate")
            coordinates = len(problem.coordinates) if problem is not None else 0
        for path in check_tests:
            if os.path.exists(path):
                have = problems.check(executables.describe, path)
                missing = sorted(set(description["parameters"]) - set(have["parameters"])) if have else []
                if missing:
                    problems.add(f"--check-test {path}: it lacks the calibrated scene's parameter(s) "
                                 f"{', '.join(missing)}: it would not test the same material")
    if budget is not None:
        # A reference point, the first design (two points per coordinate) and a first verification on fresh seeds.
        points = max(10, 1 + 2 * coordinates + FIRST_VERIFICATION_SEEDS)
        if budget < points * tests:
            problems.add(f"--budget: {budget} DEM runs cannot hold a design and a verification (at least {points}"
                         + (f" points of {tests} tests: {points * tests} test runs" if tests > 1 else "") + ")")

    config = {"scene": args.scene, "space": args.space, "targets": targets, "fixed": fixed,
              "tolerance": tolerance, "budget": budget, "scale_parameter": args.scale_parameter}
    if check_resolution is not None:
        config["check_resolution"] = check_resolution
    if check_tests:
        config["check_tests"] = check_tests
    if curves:  # absent without any, so calibrations stored before curves resume
        config["curves"] = curves
    if strategy != "trust-region":  # absent for the default, so calibrations stored before the option resume
        config["strategy"] = strategy
    if uncertainty:  # likewise absent without any
        config["target_uncertainty"] = uncertainty
    if lab_correlation:
        config["lab_correlation"] = lab_correlation
    if discrepancy is not None:
        config["model_discrepancy"] = discrepancy
    out, replace = None, False
    if targets and args.scene:
        on_curve = set(curve_targets.names(curves))
        name = args.name or (default_name(args.scene, {k: v for k, v in targets.items() if k not in on_curve})
                             + (f"_curves{len(curves)}" if curves else "")
                             + ("" if strategy == "trust-region" else f"_{strategy}"))
        out = os.path.join(args.out_root, name)
        stored = os.path.join(out, "calibration.json")
        existing = os.path.abspath(out)
        while not os.path.exists(existing) and os.path.dirname(existing) != existing:
            existing = os.path.dirname(existing)  # the nearest folder that exists: the calibration is made in it
        if os.path.exists(out) and not os.path.isdir(out):
            problems.add(f"--out-root/--name: {out} exists and is not a folder")
        elif not os.path.isdir(existing) or not os.access(existing, os.W_OK | os.X_OK):
            problems.add(f"--out-root: cannot write {out} ({existing} is not a folder this user may write in)")
        elif os.path.exists(stored) and not problems:
            before = problems.check(load_json, stored, "calibration")
            # A check after the calibration changes none of its decisions: it may be added to a finished one. A
            # larger budget continues it: the runs already made are found again (each DEM point is stored by its
            # parameters and seed), so nothing is repeated.
            checks = ("check_resolution", "check_tests", "budget")
            if before is not None and {k: v for k, v in before.items() if k not in checks} != {
                    k: v for k, v in config.items() if k not in checks}:
                if holds_no_work(out):
                    replace = True
                else:
                    problems.add(f"{stored}: another calibration is stored here (different scene, targets or "
                                 f"settings); remove {out} or give --name")
    problems.raise_if_any()
    return config, out, replace


def specimens_correlation(curves, lab_names, args, targets):
    """{"names", "matrix"}: the correlation over the lab's specimens of every target measured specimen by specimen,
    its curves' points and, where the specimen file names the same specimens, its scalar outputs (a specimen's
    peak and its curve's last point move together); None when it is the identity."""
    specimen_of = {}
    if lab_names:
        for (name, specimen), value in lab_targets.specimen_values(args.lab_specimens).items():
            specimen_of[(lab_names.get(name, name), specimen)] = value
    for c in curves:
        for specimen, values in (c.get("by_specimen") or {}).items():
            for name, value in values.items():
                specimen_of[(name, specimen)] = value
    measured = {name for name, _ in specimen_of}
    names = [n for n in targets if n in measured]
    r = lab_targets.specimen_correlation(names, specimen_of)
    return {"names": names, "matrix": r.tolist()} if len(names) > 1 and not np.array_equal(r, np.eye(len(names))) else None


def measured_curves(args, targets, uncertainty, description, strategy, problems):
    """The --curve targets (curve_targets.curve_target each), their points added to `targets` (and, with an sd_MPa
    column, to `uncertainty`, one specimen's SD); problems added for every defect."""
    specs = list(getattr(args, "curve", None) or [])
    window_text = getattr(args, "curve_window", None)
    if window_text is not None and not specs:
        problems.add("--curve-window: give the curve it applies to (--curve CURVE.csv)")
    if not specs:
        return []
    curves = curve_targets.read_curves(specs, window_text, problems, "--curve", "--curve-window",
                                       description=description)
    if len(curves) == len(specs) and not targets:
        problems.add("--curve: give at least one NAME=VALUE target beside the curve (the verification decides how "
                     "many fresh seeds to run by those)")
    for c in curves:
        for q in c["points"]:
            if q["name"] in targets:
                problems.add(f"--curve {c['spec']}: a second curve of the same test gives {q['name']} again")
                continue
            targets[q["name"]] = q["value"]
            if q["sd"] is not None:
                uncertainty[q["name"]] = {"sd": q["sd"], "n": q.get("n", 1)}
        if strategy == "bayes" and curve_targets.without_scatter(c):
            problems.add(f"--curve {c['spec']}: the Bayesian search weighs each point by the lab's scatter: give the "
                         "curve a specimen column (several specimens' curves) or an sd_MPa column" +
                         (" and no lateral_strain column (sd_MPa is the stress's)"
                          if any(q["kind"] == "lateral" for q in c["points"]) else ""))
    return curves


def calibrate(args):
    config, out, replace = checked_command(args)
    # Built before anything is written: the Problem and the descriptions it needs are those just checked.
    calibration = Calibration(config, out, commands.from_environment(), quiet=args.quiet)
    stored = os.path.join(out, "calibration.json")
    if os.path.exists(stored):
        before = load_json(stored, "calibration")
        if replace:
            calibration.say(f"{stored}: replacing settings under which no DEM point ran")
            if os.path.exists(os.path.join(out, "wall_s.json")):  # the time of those settings, not of these
                os.remove(os.path.join(out, "wall_s.json"))
        if before != config:
            write_target(stored, json.dumps(config, indent=1) + "\n")
    else:
        os.makedirs(out, exist_ok=True)
        write_target(stored, json.dumps(config, indent=1) + "\n")
    started = time.time()
    try:
        code = calibration.run()
    finally:
        # An invocation stopped by an error or an interrupt spent its time too: the resumed calibration counts it.
        # A failure to record it must not hide the error that stopped the calibration.
        try:
            record_wall_time(out, time.time() - started)
        except (OSError, StudyError) as e:
            print(f"calibrate: warning: the wall time of this invocation was not recorded: {e}", file=sys.stderr)
    report(out)
    return code


def record_wall_time(out, seconds):
    """A calibration run in parts: every invocation's wall time is kept, and solution.json states their sum."""
    path = os.path.join(out, "wall_s.json")
    parts = load_json(path, "wall times") if os.path.exists(path) else []
    parts.append(round(seconds, 1))
    write_target(path, json.dumps(parts) + "\n")
    solution_path = os.path.join(out, "solution.json")
    if not os.path.exists(solution_path):  # stopped before its first result: the next invocation states the sum
        return
    solution = load_json(solution_path, "calibration solution")
    solution["wall_s_parts"] = parts
    solution["wall_s_total"] = sum(parts)
    write_target(solution_path, json.dumps(solution, indent=1) + "\n")
