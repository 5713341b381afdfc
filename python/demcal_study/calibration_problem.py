"""What a calibration varies and what it aims at, in the dimensionless form the exact scaling of bonded DEM allows.

Multiplying every stress-like parameter (by its unit: moduli, stiffnesses, strengths) by a factor s multiplies
every stress output by s and leaves strains, nu and crack counts unchanged (tests/dem/test_exact_scaling.cpp). So:

* one stress-like parameter is the *scale parameter* (default: the varied stress-like one with the largest value
  in SI units, a modulus in every shipped scene); the others are varied as ratios to it;
* one stress target is the *scale target* (E_GPa when it is a target, else the first stress target); the other
  stress targets become ratios to it (sigma_u / E) and dimensionless targets stay as they are (nu);
* the DEM runs at absolute values: ratios times the scale parameter's reference value, all stress-like values
  times the scale factor s that puts the scale target where it belongs.

Coordinates: every varied ratio or dimensionless parameter is coded to u in [-1, 1], on a log scale when its range
spans more than a decade (or the space says log_scale). Without a space, the scene's physical bounds are used, lows of
zero raised to 1e-3 of the high (angles keep theirs and are coded linearly); parameters that shape the specimen
(radii, size, density) and lengths stay at their defaults."""
import math

from .errors import fail
from .outputs import is_output, output_info

LOG_SPAN = 10.0  # a range wider than this (high / low) is coded on a log scale


class Coordinate:
    """One varied coordinate: a dimensionless parameter, or a stress-like one as a ratio to the scale parameter."""

    def __init__(self, name, low, high, reference, log_scale, ratio, unit="1"):
        if not (low < high):
            fail(f"{name}: low ({low:g}) must be below high ({high:g})")
        if log_scale and low <= 0:
            fail(f"{name}: a log-scale range needs a positive low (got {low:g})")
        self.name, self.low, self.high, self.log_scale, self.ratio = name, low, high, log_scale, ratio
        self.unit = "1" if ratio else (unit or "1")  # a ratio of two stresses is a pure number
        self.reference = min(max(reference, low), high)

    def code(self, value):
        if self.log_scale:
            return 2.0 * (math.log(value) - math.log(self.low)) / (math.log(self.high) - math.log(self.low)) - 1.0
        return 2.0 * (value - self.low) / (self.high - self.low) - 1.0

    def decode(self, u):
        u = min(max(u, -1.0), 1.0)
        if self.log_scale:
            return math.exp(math.log(self.low) + 0.5 * (u + 1.0) * (math.log(self.high) - math.log(self.low)))
        return self.low + 0.5 * (u + 1.0) * (self.high - self.low)

    def describe(self):
        kind = ("ratio to the scale parameter" if self.ratio else "dimensionless" if self.unit == "1"
                else f"value in {self.unit}")
        return {"name": self.name, "low": self.low, "high": self.high, "reference": self.reference,
                "log_scale": self.log_scale, "kind": kind, "unit": self.unit}


def _positive_low(low, high):
    return 1e-3 * high if low <= 0 else low


class Problem:
    """Built from demcal-dem describe's JSON of the scene, an optional space, fixed values and the targets."""

    def __init__(self, scene_description, targets, space=None, fixed=None, scale_parameter=None, where="calibrate"):
        self.where = where
        params = scene_description["parameters"]
        outputs = scene_description["outputs"]
        self.targets = dict(targets)
        if not self.targets:
            fail(f"{where}: no targets")
        for name, value in self.targets.items():
            if not is_output(outputs, name, f"{where}: target"):
                fail(f"{where}: target {name} is not an output of the scene, nor a ratio A/B of two "
                     f"(outputs: {', '.join(sorted(outputs))})")
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value != 0):
                fail(f"{where}: target {name} must be a non-zero number")
        info = {o: output_info(outputs, o, f"{where}: target") for o in self.targets}
        self.output_stress_like = {o: bool(info[o]["stress_like"]) for o in self.targets}
        fixed = dict(fixed or {})
        for name in fixed:
            if name not in params:
                fail(f"{where}: fixed {name} is not a parameter of the scene")
        self.tied = list((space or {}).get("tied", []))
        tied_names = {t["name"] for t in self.tied}

        # What varies, with its absolute bounds.
        varied = {}  # name -> (low, high, reference, log_scale or None)
        if space is not None:
            for p in space.get("parameters", []):
                if p["name"] in fixed:
                    continue
                varied[p["name"]] = (p["low"], p["high"], p.get("reference", params[p["name"]]["value"]),
                                     p.get("log_scale"))
            for name, value in space.get("fixed", {}).items():
                fixed.setdefault(name, value)
        else:
            for name, p in sorted(params.items()):
                if name in fixed or name in tied_names:
                    continue
                if p.get("shapes_specimen") or p["quantity"] == "length":
                    continue
                if p["quantity"] not in ("stress", "stiffness", "dimensionless", "angle"):
                    continue  # densities, velocities, times: not micro-parameters of the contacts
                high = p["high"]
                if not (math.isfinite(high) and high < 1e299):
                    fail(f"{where}: {name} has no finite high bound in the scene; give a space (SPACE=...)")
                if p["quantity"] == "angle":
                    # A friction angle (the flat joint's phi_b) acts through tan and sin: coded linearly from its
                    # own low, zero included; a log scale would crowd the search near zero degrees.
                    varied[name] = (p["low"], high, p["value"], False)
                else:
                    varied[name] = (_positive_low(p["low"], high), high, p["value"], None)
        if not varied:
            fail(f"{where}: nothing to vary (every parameter is fixed, a length or shapes the specimen)")
        self.fixed = fixed
        self.stress_like = {n: bool(params[n]["stress_like"]) for n in params}
        self.absolute_bounds = {n: (v[0], v[1]) for n, v in varied.items()}

        stress_varied = sorted(n for n in varied if self.stress_like[n])
        # A stress-like value held fixed would not follow the scale factor: the scaling is then not exact, and the
        # scale parameter is searched like any other.
        self.held_stress = sorted(n for n in fixed if self.stress_like[n])
        if scale_parameter is not None and self.held_stress:
            fail(f"{where}: scale parameter {scale_parameter} given, but {', '.join(self.held_stress)} is held fixed "
                 "and stress-like: the exact scaling needs every stress-like value to follow the scale factor")
        # An external program need not scale with its stress-like parameters: only when its scene says so.
        self.exact_scaling = scene_description.get("exact_scaling", True)
        if scale_parameter is not None and not self.exact_scaling:
            fail(f"{where}: scale parameter {scale_parameter} given, but the scene does not declare \"exact_scaling\": "
                 "true (an external program's outputs need not scale with its stress-like parameters)")
        if scale_parameter is None and stress_varied and not self.held_stress and self.exact_scaling:
            scale_parameter = max(stress_varied, key=lambda n: (varied[n][2] * params[n]["si_factor"], n))
        if scale_parameter is not None and scale_parameter not in stress_varied:
            fail(f"{where}: scale parameter {scale_parameter} is not a varied stress-like parameter"
                 f" (those: {', '.join(stress_varied) or 'none'})")
        self.scale_parameter = scale_parameter
        stress_targets = sorted(o for o, s in self.output_stress_like.items() if s)
        self.scale_target = None
        if scale_parameter is not None and stress_targets:
            # A modulus (set by the stiffnesses alone) when one is a target, the test's first by its rank; else the
            # first stress target.
            moduli = sorted((outputs[o]["modulus"], o) for o in stress_targets if o in outputs and outputs[o].get("modulus"))
            self.scale_target = moduli[0][1] if moduli else stress_targets[0]
        self.output_si = {o: info[o]["si_factor"] for o in self.targets}
        # The scale parameter's reference value at scale 1; every ratio multiplies it.
        self.scale_reference = varied[scale_parameter][2] if scale_parameter else 1.0

        self.coordinates = []
        for name in sorted(varied):
            if name == scale_parameter:
                continue
            low, high, reference, log_flag = varied[name]
            ratio = scale_parameter is not None and self.stress_like[name]
            if ratio:
                # The ratios the absolute bounds allow at scale 1; other scales narrow them (scale_interval).
                low, high, reference = low / self.scale_reference, high / self.scale_reference, \
                    reference / self.scale_reference
            else:
                low = _positive_low(low, high) if log_flag is None and high / max(low, 1e-300) > LOG_SPAN else low
            log_scale = log_flag if log_flag is not None else (low > 0 and high / low > LOG_SPAN)
            self.coordinates.append(Coordinate(name, low, high, reference, log_scale, ratio,
                                               unit=params[name].get("unit", "1") if name in params else "1"))
        if not self.coordinates and self.scale_target is None:
            fail(f"{where}: nothing to vary")

    # -- the residuals, after the scale factor is chosen exactly -------------------------------------------------
    def modelled_outputs(self):
        """The responses the local model fits: log(stress output / scale factor) for stress outputs (scale-free),
        the output itself for dimensionless ones."""
        return sorted(self.targets)

    def to_model(self, output, value, scale):
        if self.output_stress_like[output] and self.scale_parameter is not None:
            return math.log(value / scale) if value > 0 else float("nan")
        return value

    def from_model(self, output, z, scale):
        if self.output_stress_like[output] and self.scale_parameter is not None:
            return scale * math.exp(z)
        return z

    def scale_for(self, z):
        """The scale factor that puts the scale target where it belongs, given modelled responses z (dict)."""
        if self.scale_target is None:
            return 1.0
        return self.targets[self.scale_target] / math.exp(z[self.scale_target])

    def residual_names(self):
        return [o for o in sorted(self.targets) if o != self.scale_target]

    def residual_labels(self):
        """The residuals as the dimensionless problem names them (sigma_u_MPa/E_GPa, nu)."""
        return [f"{o}/{self.scale_target}" if self.output_stress_like[o] and self.scale_target is not None else o
                for o in self.residual_names()]

    def residuals(self, z):
        """Relative errors of the targets once the scale factor is exact (the scale target's own is then zero):
        stress ratios as log(predicted / target), dimensionless outputs as (value - target) / |target|."""
        out = []
        for o in self.residual_names():
            t = self.targets[o]
            if self.output_stress_like[o] and self.scale_parameter is not None:
                if self.scale_target is not None:
                    out.append(z[o] - z[self.scale_target] - math.log(t / self.targets[self.scale_target]))
                else:
                    out.append(z[o] - math.log(t))
            else:
                out.append((z[o] - t) / abs(t))
        return out

    def dimensionless_targets(self):
        """The targets as the dimensionless calibration sees them: stress targets over the scale target."""
        out = {}
        for o in self.residual_names():
            if self.output_stress_like[o] and self.scale_target is not None:  # in SI over SI: a pure number
                out[f"{o}/{self.scale_target}"] = (self.targets[o] * self.output_si[o]) / (
                    self.targets[self.scale_target] * self.output_si[self.scale_target])
            else:
                out[o] = self.targets[o]
        return out

    # -- from coordinates to a DEM point ---------------------------------------------------------------------------
    def reference_point(self):
        return [c.code(c.reference) for c in self.coordinates]

    def ratios(self, u):
        """The stress-like coordinates as ratios to the scale parameter (the dimensionless solution)."""
        return {c.name: c.decode(x) for c, x in zip(self.coordinates, u) if c.ratio}

    def absolute(self, u, scale):
        """Scene parameter values at coordinates u and scale factor s (varied and fixed; tied ones follow)."""
        values = dict(self.fixed)
        for c, x in zip(self.coordinates, u):
            v = c.decode(x)
            values[c.name] = v * self.scale_reference * scale if c.ratio else v
        if self.scale_parameter is not None:
            values[self.scale_parameter] = self.scale_reference * scale
        # A scale factor taken from a bound (scale_interval: the bound over the value at factor 1) puts that value
        # back on its bound only up to rounding, and the DEM refuses a value one ulp outside (ldb_granite's
        # corrected point had cb_tau_c_std_Pa = 1.0000000000000001e8 against a bound of 1e8): snap those.
        for name, (lo, hi) in self.absolute_bounds.items():
            v = values.get(name)
            if v is not None and not lo <= v <= hi:
                edge = hi if v > hi else lo
                if abs(v - edge) <= 1e-12 * max(abs(v), abs(edge)):
                    values[name] = edge
        for t in self.tied:
            if t["source"] in values:
                values[t["name"]] = t.get("factor", 1.0) * values[t["source"]] + t.get("offset", 0.0)
        return values

    def scale_interval(self, u, sharpness=None):
        """The scale factors for which every varied stress-like value stays inside its absolute bounds. With a
        `sharpness` (in log units), the max and min over the parameters are softened (log-sum-exp), so that bounds
        within a few 1/sharpness of the tightest one share its slope: a search then sees that two parameters
        pinning the scale together must both move to free it."""
        if self.scale_parameter is None:
            return 1.0, 1.0
        lows, highs = [], []
        base = self.absolute(u, 1.0)
        for name, (lo, hi) in self.absolute_bounds.items():
            if self.stress_like[name] and base[name] > 0:
                lows.append(lo / base[name])
                highs.append(hi / base[name])
        if sharpness is None:
            return max(lows + [0.0]), min(highs + [math.inf])
        logs_low = [math.log(x) for x in lows if x > 0]
        logs_high = [math.log(x) for x in highs if math.isfinite(x)]
        return (math.exp(soft_max(logs_low, sharpness)) if logs_low else 0.0,
                math.exp(-soft_max([-h for h in logs_high], sharpness)) if logs_high else math.inf)

    def describe(self):
        return {"targets": self.targets, "dimensionless_targets": self.dimensionless_targets(),
                "scale_parameter": self.scale_parameter, "scale_reference": self.scale_reference,
                "scale_target": self.scale_target, "coordinates": [c.describe() for c in self.coordinates],
                "fixed": self.fixed, "tied": self.tied, "held_stress_like": self.held_stress,
                "exact_scaling": self.exact_scaling}


def soft_max(values, sharpness):
    """log-sum-exp over `sharpness`: the largest value, smoothed; never below it, at most log(n) / sharpness above."""
    top = max(values)
    return top + math.log(sum(math.exp(sharpness * (v - top)) for v in values)) / sharpness
