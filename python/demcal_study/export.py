"""export: a calibrated parameter set written as the input of the simulator a user runs.

    python -m demcal_study export --solution SOLUTION.json --scene S.json --to pfc|yade|liggghts [--out FILE]

The solution is any of demcal's (demcal-invert, make calibrate, a study), or the parameters.json a report writes
beside itself: its `x` (or parameters) over the scene's defaults. For our
DEM, each contact role's model parameters are evaluated from the scene's bindings (what demcal-dem describe lists)
and written under the other program's names, SI units; for an external scene, its own parameters under their own
names (they are that program's already). What does not carry over is said in the file, never silently dropped:

* our DEM is 2D (disks of unit thickness): PFC2D takes the moduli and strengths as they are; YADE and LIGGGHTS are 3D,
  where the same numbers give another material, so the calibration must be repeated there (or run through
  demcal's external test on that program);
* strength deviations (`*_std_pa`) have no property in the other programs: they are written as comments;
* a contact bond's strengths are stresses here (force = stress x 2 min(R) t per bond, PFC's contact area), which
  PFC's linearcbond takes through its cb_strength method after bonding, not as properties of the assignment table.
"""
import json
import math
import os

from . import executables
from .errors import fail, load_json

TARGETS = ("pfc", "yade", "liggghts")


def evaluate(expression, values, where):
    """A scene binding: a number, or a product of parameter names and numbers ("Ec_GPa*1e9")."""
    if isinstance(expression, (int, float)):
        return float(expression)
    product = 1.0
    for factor in str(expression).split("*"):
        try:
            product *= float(factor)
        except ValueError:
            if factor not in values:
                fail(f"{where}: \"{factor}\" in \"{expression}\" is not a scene parameter")
            product *= values[factor]
    return product


def parameter_values(description, solution, where):
    values = {name: p["value"] for name, p in description["parameters"].items()}
    for name, value in solution.get("x", {}).items():
        if name not in values:
            fail(f"{where}: x.{name} is not a parameter of {description['scene']}")
        values[name] = float(value)
    return values


def contact_roles(description):
    """[(label, role, model, bindings)] of a scene or a test list, each distinct binding once."""
    contacts = description.get("contacts", {})
    flat = []
    if description.get("test") == "list":
        for label, roles in contacts.items():  # {label: {role: ...}}; an external test's is empty
            flat += [(label, role, c["model"], c.get("parameters", {})) for role, c in roles.items()]
    else:
        flat = [("", role, c["model"], c.get("parameters", {})) for role, c in contacts.items()]
    seen, out = set(), []
    for label, role, model, bindings in flat:
        key = (role, model, json.dumps(bindings, sort_keys=True))
        if key not in seen:
            seen.add(key)
            out.append((label, role, model, bindings))
    return out


# -- PFC2D 7 (contact model assignment table) ------------------------------------------------------------------
def pfc_lines(role, model, p):
    if model not in ("linear", "parallel_bond", "flat_joint", "contact_bond"):
        return [f"# {role}: model {model} has no PFC counterpart in this exporter"]
    if "modulus_pa" in p:
        cmat = (f"contact cmat default model {{model}} method deformability emod {p['modulus_pa']:.10g} "
                f"kratio {p['kn_ks']:.10g}")
    else:  # linear springs given as stiffnesses
        cmat = f"contact cmat default model {{model}} property kn {p['kn_n_m']:.10g} ks {p['ks_n_m']:.10g}"
    notes = [f"# {k} = {v:.10g} Pa: PFC has no property for a strength's spread; draw per contact yourself"
             for k, v in sorted(p.items()) if k.endswith("_std_pa") and v > 0]
    rmul = p.get("radius_multiplier", 1.0)
    if model == "linear":
        cmd = cmat.format(model="linear") + f" property fric {p['friction']:.10g}"
    elif model == "parallel_bond":
        cmd = (cmat.format(model="linearpbond") +
               f" pb_deformability emod {p['bond_modulus_pa']:.10g} kratio {p['bond_kn_ks']:.10g}"
               f" property fric {p['friction']:.10g} pb_ten {p['tensile_strength_pa']:.10g}"
               f" pb_coh {p['shear_strength_pa']:.10g} pb_fa 0 pb_rmul {rmul:.10g}")
    elif model == "flat_joint":
        cmd = (f"contact cmat default model flatjoint method deformability emod {p['joint_modulus_pa']:.10g}"
               f" kratio {p['joint_kn_ks']:.10g} property fj_ten {p['tensile_strength_pa']:.10g}"
               f" fj_coh {p['cohesion_pa']:.10g} fj_fa {p['friction_angle_deg']:.10g}"
               f" fj_fric {p['joint_friction']:.10g} fj_nr {int(p.get('elements', 2))} fj_rmul {rmul:.10g}")
        notes.append(f"# contacts that form later (unjoined) take the linear part: emod {p['modulus_pa']:.10g}, "
                     f"kratio {p['kn_ks']:.10g}, fric {p['friction']:.10g}")
    elif model == "contact_bond":
        cmd = cmat.format(model="linearcbond") + f" property fric {p['friction']:.10g}"
        # PFC multiplies cb_strength's stresses by the contact area 2 min(R) t, as our contact bond does.
        notes.append("# after bonding (contact method bond gap ...), the strengths as stresses; PFC turns them into the "
                     "forces cb_tenf and cb_shearf with the contact area 2 min(R) t, as demcal does:")
        notes.append(f"# it.command(\"contact method cb_strength tensile {p['tensile_strength_pa']:.10g} "
                     f"shear {p['shear_strength_pa']:.10g}\")")
    return [f"# {role}: {model}"] + notes + [f"it.command(\"{cmd}\")"]


# -- YADE (3D) ----------------------------------------------------------------------------------------------------
def yade_lines(role, model, p):
    # YADE's FrictMat gives kn = 2 E R1 R2 / (R1 + R2) and ks = poisson x kn: its "poisson" is ks / kn.
    lines = [f"# {role}: {model}"]
    base = {"young": p.get("modulus_pa"), "poisson": 1.0 / p["kn_ks"] if p.get("kn_ks") else None,
            "frictionAngle": math.atan(p["friction"]) if "friction" in p else None}
    if model in ("parallel_bond", "contact_bond"):
        base.update({"normalCohesion": p["tensile_strength_pa"], "shearCohesion": p["shear_strength_pa"],
                     "isCohesive": True})
        kind = "CohFrictMat"
    elif model == "flat_joint":
        base.update({"young": p["joint_modulus_pa"], "poisson": 1.0 / p["joint_kn_ks"],
                     "frictionAngle": math.atan(p["joint_friction"]), "normalCohesion": p["tensile_strength_pa"],
                     "shearCohesion": p["cohesion_pa"], "isCohesive": True})
        kind = "CohFrictMat"
        lines.append("# no flat joint in YADE: its elements, partial damage and friction angle phi_b "
                     f"({p['friction_angle_deg']:.10g} deg) do not carry over; a cohesive-frictional bond is the nearest")
    elif model == "linear":
        kind = "FrictMat"
    else:
        return [f"# {role}: model {model} has no YADE counterpart in this exporter"]
    fields = {k: v for k, v in base.items() if v is not None}
    name = "".join(c if c.isalnum() else "_" for c in role)  # a Python name: "brazilian.disk-disk" -> brazilian_disk_disk
    lines.append(f"{name} = dict(kind=\"{kind}\", " +
                 ", ".join(f"{k}={v!r}" for k, v in fields.items()) + ")")
    return lines


# -- LIGGGHTS (3D, Hertz-Mindlin) ----------------------------------------------------------------------------------
def liggghts_lines(role, model, p):
    lines = [f"# {role}: {model}"]
    if model not in ("linear", "parallel_bond", "contact_bond", "flat_joint"):
        return lines + [f"# model {model} has no LIGGGHTS counterpart in this exporter"]
    if model != "linear":
        lines.append("# LIGGGHTS-PUBLIC has no bonds: only the contact's stiffness and friction carry over")
    # Hertz-Mindlin's ks / kn = 2 (1 - nu) / (2 - nu), so nu = (2 - 2 r) / (2 - r) with r = ks / kn.
    if "modulus_pa" not in p:
        return lines + ["# springs given as stiffnesses (kn_n_m, ks_n_m): no Young's modulus to carry over"]
    r = 1.0 / p["kn_ks"]
    nu = (2 - 2 * r) / (2 - r)
    # Fix ids named after the role: several roles (a test list) must not redefine one another's fixes.
    tag = "".join(c if c.isalnum() else "_" for c in role)
    lines.append(f"fix m1_{tag} all property/global youngsModulus peratomtype {p['modulus_pa']:.10g}")
    if 0 <= nu < 0.5:
        lines.append(f"fix m2_{tag} all property/global poissonsRatio peratomtype {nu:.10g}")
    else:
        lines.append(f"# kn/ks = {p['kn_ks']:.10g} has no Hertz-Mindlin Poisson's ratio in [0, 0.5): choose one")
    lines.append(f"fix m4_{tag} all property/global coefficientFriction peratomtypepair 1 {p['friction']:.10g}")
    return lines


WRITERS = {"pfc": pfc_lines, "yade": yade_lines, "liggghts": liggghts_lines}
HEADERS = {
    "pfc": ["# PFC2D 7 contact model assignment (Python, run inside PFC: import itasca as it). SI units.",
            "# Written from PFC's documented keywords without a PFC to run it on: check them against your version.",
            "# Our DEM is 2D with disks of unit thickness, as PFC2D: moduli and strengths carry over as they are.",
            "import itasca as it"],
    "yade": ["# YADE material properties (Python dicts: O.materials.append(CohFrictMat(**{k: v for k, v in d.items()",
             "# if k != 'kind'})) ). SI units. CAUTION: our DEM is 2D (disks, unit thickness), YADE 3D (spheres): the",
             "# same numbers make another material; repeat the calibration in YADE (docs/howto/own_simulator.md)."],
    "liggghts": ["# LIGGGHTS fix property/global lines (one atom type). SI units. CAUTION: our DEM is 2D with linear",
                 "# springs, LIGGGHTS 3D Hertz-Mindlin: the same numbers make another material; repeat the calibration."],
}


def external_lines(to, values):
    if to == "pfc":
        return [f"{name} = {value!r}" for name, value in sorted(values.items())]
    if to == "yade":
        return ["parameters = " + repr(dict(sorted(values.items())))]
    return [f"variable {name} equal {value!r}" for name, value in sorted(values.items())]


def export_text(description, solution, to, where="export"):
    if to not in TARGETS:
        fail(f"{where}: --to must be one of {', '.join(TARGETS)} (got {to})")
    values = parameter_values(description, solution, where)
    lines = [f"# demcal export of {description['scene']} at the solution's parameters ({to})"]
    roles = contact_roles(description)
    if not roles:  # an external scene (or a list of them): no contacts of ours to translate
        lines.append("# an external scene: its own parameters, under their own names")
        return "\n".join(lines + external_lines(to, values)) + "\n"
    lines += HEADERS[to]
    lines.append("# scene parameters: " + ", ".join(f"{k} = {v:.10g}" for k, v in sorted(values.items())))
    for label, role, model, bindings in roles:
        bound = {k: evaluate(v, values, f"{where}: contacts.{role}.{k}") for k, v in bindings.items()}
        lines += [""] + WRITERS[to](f"{label + '.' if label else ''}{role}", model, bound)
    return "\n".join(lines) + "\n"


def as_solution(solution, where):
    """A solution's `x`, from any of demcal's solutions or from a report's parameters.json ({"parameters": {name:
    {"value", "unit", ...}}})."""
    if isinstance(solution, dict) and "x" not in solution and isinstance(solution.get("parameters"), dict):
        x = {}
        for name, entry in solution["parameters"].items():
            value = entry.get("value") if isinstance(entry, dict) else entry
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
                fail(f"{where}: parameters.{name}: value must be a finite number")
            x[name] = float(value)
        return {"x": x}
    if not isinstance(solution, dict) or not isinstance(solution.get("x"), dict):
        fail(f"{where}: x: missing (the calibrated parameters, as demcal-invert and make calibrate write them, or a "
             "report's parameters.json)")
    return solution


def export(args):
    solution = as_solution(load_json(args.solution, "solution"), args.solution)
    text = export_text(executables.describe(args.scene), solution, args.to, where=args.solution)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out, "w") as f:
            f.write(text)
        print(args.out)
    else:
        print(text, end="")
    return 0
