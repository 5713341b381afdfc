"""export: a calibrated parameter set written as the input of the simulator a user runs.

    python -m demcal_study export --solution SOLUTION.json --scene S.json --to pfc|pfc3d|yade|liggghts [--out FILE]

The solution is any of demcal's (demcal-invert, make calibrate, a study), or the parameters.json a report writes
beside itself: its `x` (or parameters) over the scene's defaults. For our
DEM, each contact role's model parameters are evaluated from the scene's bindings (what demcal-dem describe lists)
and written under the other program's names, which each contact model declares (describe --registries,
contact_model_peer_names), SI units; for an external scene, its own parameters under their own
names (they are that program's already). What does not carry over is said in the file, never silently dropped:

* a 2D scene (disks of unit thickness) exports to PFC2D (`pfc`), which takes the moduli and strengths as they are;
  YADE and LIGGGHTS are 3D, where the same numbers give another material, so the calibration must be repeated there
  (or run through demcal's external test on that program). A 3D scene (spheres) exports to PFC3D (`pfc3d`), YADE
  and LIGGGHTS as it is, each law as close as that program's model (each model's reference page says how close);
* strength deviations (`*_std_pa`) have no property in the other programs: they are written as comments;
* a contact bond's strengths are stresses here (force = stress x 2 min(R) t per bond in 2D, pi min(R)^2 in 3D: PFC's
  contact area), which
  PFC's linearcbond takes through its cb_strength method after bonding, not as properties of the assignment table.
"""
import json
import math
import os

from . import executables
from .errors import fail, load_json

TARGETS = ("pfc", "pfc3d", "yade", "liggghts")


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


def dimension_key(dimension):
    """describe's dimension (2, 3) as the registries key it ("2d", "3d"); a description without one is 2D."""
    return f"{dimension or 2}d"


def contact_roles(description):
    """[(label, role, model, bindings, dimension)] of a scene or a test list, each distinct binding once."""
    contacts = description.get("contacts", {})
    flat = []
    if description.get("test") == "list":
        dims = {t["label"]: t.get("dimension") for t in description.get("tests", [])}
        for label, roles in contacts.items():  # {label: {role: ...}}; an external test's is empty
            flat += [(label, role, c["model"], c.get("parameters", {}), dimension_key(dims.get(label)))
                     for role, c in roles.items()]
    else:
        flat = [("", role, c["model"], c.get("parameters", {}), dimension_key(description.get("dimension")))
                for role, c in contacts.items()]
    seen, out = set(), []
    for label, role, model, bindings, dim in flat:
        key = (role, model, dim, json.dumps(bindings, sort_keys=True))
        if key not in seen:
            seen.add(key)
            out.append((label, role, model, bindings, dim))
    return out


# Each model's names in the other programs are its own (`demcal-dem describe --registries`, contact_model_peer_names):
# what follows only renders them in each program's syntax and applies that program's conventions.
PROGRAMS = {"pfc": "PFC", "pfc3d": "PFC3D", "yade": "YADE", "liggghts": "LIGGGHTS"}


def converted(keyword, p):
    """(value, None) of one keyword at the bound parameters `p`, (None, why) when it cannot be written, (None, None)
    when the scene does not give the key and the table has no default."""
    if "value" in keyword:
        return keyword["value"], None
    key = keyword["key"]
    if key not in p:
        return (float(keyword["default"]), None) if "default" in keyword else (None, None)
    v, kind = p[key], keyword.get("as", "same")
    if kind == "same":
        return v, None
    if kind == "integer":
        return int(round(v)), None
    if kind == "reciprocal":  # YADE's FrictMat: kn = 2 E R1 R2 / (R1 + R2), ks = poisson x kn
        return 1.0 / v, None
    if kind == "atan":  # a friction coefficient as YADE's friction angle (radians)
        return math.atan(v), None
    if kind == "hertz_mindlin_poisson":  # Hertz-Mindlin's ks / kn = 2 (1 - nu) / (2 - nu), r = ks / kn
        r = 1.0 / v
        nu = (2 - 2 * r) / (2 - r)
        if 0 <= nu < 0.5:
            return nu, None
        return None, f"{key} = {v:.10g} has no Hertz-Mindlin Poisson's ratio in [0, 0.5): choose one"
    if kind == "youngs_modulus":  # E = 2 G (1 + nu)
        other = keyword["with"]
        if other not in p:
            return None, f"{key} needs {other} to give a Young's modulus"
        return 2 * v * (1 + p[other]), None
    raise ValueError(f"unknown conversion {kind!r} in the peer names of {key}")


def translated(table, p):
    """[(keyword, value)] the table writes, the comment lines of what it cannot, and the keys it used."""
    written, comments, used = [], [], set()
    for keyword in table.get("keywords", []):
        used.add(keyword.get("key"))
        value, why = converted(keyword, p)
        if why:
            comments.append(f"# {why}")
        elif value is not None:
            written.append((keyword, value))
    return written, comments, used


def number(v):
    return repr(v) if isinstance(v, bool) else (str(v) if isinstance(v, int) else f"{v:.10g}")


def not_carried(p, used, program):
    return [f"# {key} = {p[key]:.10g}: no {program} counterpart; set it yourself if your version has one"
            for key in sorted(p) if key not in used]


def pfc_lines(role, model, p, table):
    # PFC 7's contact model assignment: method groups (deformability, pb_deformability) and properties in one
    # command; what PFC sets later (after bonding) or elsewhere is written as comments.
    written, lines, used = translated(table, p)
    later = table.get("later", {})
    groups = {}
    for keyword, value in written:
        groups.setdefault(keyword["group"], []).append(f"{keyword['name']} {number(value)}")
    cmd = f"contact cmat default model {table['model']}"
    methods = [g for g in groups if g != "property" and g not in later]
    if methods:
        cmd += " method " + " ".join(f"{g} {' '.join(groups[g])}" for g in methods)
    if "property" in groups:
        cmd += " property " + " ".join(groups["property"])
    for group, how in later.items():
        if group not in groups:
            continue
        if "command" in how:
            lines += [f"# {how['text']}:", f"# it.command(\"{how['command']} {' '.join(groups[group])}\")"]
        else:
            lines.append(f"# {how['text']}: " + ", ".join(groups[group]))
    return lines + not_carried(p, used, "PFC") + [f"it.command(\"{cmd}\")"]


def yade_lines(role, model, p, table):
    written, lines, used = translated(table, p)
    fields = ", ".join(f"{k['name']}={v!r}" for k, v in written)
    name = "".join(c if c.isalnum() else "_" for c in role)  # a Python name: "brazilian.particle-particle" -> brazilian_particle_particle
    return lines + not_carried(p, used, "YADE") + [f"{name} = dict(kind=\"{table['model']}\", {fields})"]


def liggghts_lines(role, model, p, table):
    written, lines, used = translated(table, p)
    # Fix ids named after the role: several roles (a test list) must not redefine one another's fixes.
    tag = "".join(c if c.isalnum() else "_" for c in role)
    for keyword, value in written:
        per = "peratomtypepair 1" if keyword.get("per") == "pair" else "peratomtype"
        lines.append(f"fix {keyword['name']}_{tag} all property/global {keyword['name']} {per} {number(value)}")
    return lines + not_carried(p, used, "LIGGGHTS")


WRITERS = {"pfc": pfc_lines, "pfc3d": pfc_lines, "yade": yade_lines, "liggghts": liggghts_lines}
HEADERS_3D = {
    "pfc3d": ["# PFC3D 7 contact model assignment (Python, run inside PFC3D: import itasca as it). SI units.",
              "# Written from PFC's documented keywords without a PFC to run it on: check them against your version.",
              "# Our 3D DEM has spheres, as PFC3D: moduli and strengths carry over as they are.",
              "import itasca as it"],
    "yade": ["# YADE material properties (Python dicts: O.materials.append(CohFrictMat(**{k: v for k, v in d.items()",
             "# if k != 'kind'})) ). SI units. Our 3D DEM has spheres, as YADE; its cohesive-frictional law is related",
             "# to, not the same as, PFC3D's bonds: check a run in YADE against demcal's (docs/howto/own_simulator.md)."],
    "liggghts": ["# LIGGGHTS fix property/global lines (one atom type). SI units. Our 3D DEM has spheres, as LIGGGHTS:",
                 "# the numbers carry over as they are; the laws are each model's (see its reference page)."],
}
HEADERS = {
    "pfc": ["# PFC2D 7 contact model assignment (Python, run inside PFC: import itasca as it). SI units.",
            "# Written from PFC's documented keywords without a PFC to run it on: check them against your version.",
            "# Our DEM is 2D with disks of unit thickness, as PFC2D: moduli and strengths carry over as they are.",
            "import itasca as it"],
    "yade": ["# YADE material properties (Python dicts: O.materials.append(CohFrictMat(**{k: v for k, v in d.items()",
             "# if k != 'kind'})) ). SI units. CAUTION: our DEM is 2D (disks, unit thickness), YADE 3D (spheres): the",
             "# same numbers make another material; repeat the calibration in YADE (docs/howto/own_simulator.md)."],
    "liggghts": ["# LIGGGHTS fix property/global lines (one atom type). SI units. CAUTION: our DEM is 2D, LIGGGHTS 3D",
                 "# Hertz-Mindlin: the same numbers make another material; repeat the calibration there."],
}


def role_lines(to, role, model, bound, peer_names):
    """`peer_names`: one engine's tables ({model: {program: table}})."""
    table = peer_names.get(model, {}).get("pfc" if to == "pfc3d" else to)
    if table is None:
        return [f"# {role}: model {model} has no {PROGRAMS[to]} counterpart in this exporter"]
    return ([f"# {role}: {model} as {PROGRAMS[to]}'s {table['model']}"] + [f"# {n}" for n in table.get("notes", [])] +
            WRITERS[to](role, model, bound, table))


def external_lines(to, values):
    if to in ("pfc", "pfc3d"):
        return [f"{name} = {value!r}" for name, value in sorted(values.items())]
    if to == "yade":
        return ["parameters = " + repr(dict(sorted(values.items())))]
    return [f"variable {name} equal {value!r}" for name, value in sorted(values.items())]


def export_text(description, solution, to, peer_names, where="export"):
    """The file for program `to`; `peer_names` is describe --registries' contact_model_peer_names (per engine: "2d",
    "3d")."""
    if to not in TARGETS:
        fail(f"{where}: --to must be one of {', '.join(TARGETS)} (got {to})")
    values = parameter_values(description, solution, where)
    lines = [f"# demcal export of {description['scene']} at the solution's parameters ({to})"]
    roles = contact_roles(description)
    if not roles:  # an external scene (or a list of them): no contacts of ours to translate
        lines.append("# an external scene: its own parameters, under their own names")
        return "\n".join(lines + external_lines(to, values)) + "\n"
    dims = {dim for _, _, _, _, dim in roles}
    if to == "pfc" and "3d" in dims:
        fail(f"{where}: --to pfc writes PFC2D's commands, and {description['scene']} is a 3D scene: use --to pfc3d")
    if to == "pfc3d" and "3d" not in dims:
        fail(f"{where}: --to pfc3d writes PFC3D's commands, and {description['scene']} is a 2D scene: use --to pfc")
    lines += HEADERS_3D[to] if dims == {"3d"} else HEADERS[to]
    lines.append("# scene parameters: " + ", ".join(f"{k} = {v:.10g}" for k, v in sorted(values.items())))
    for label, role, model, bindings, dim in roles:
        bound = {k: evaluate(v, values, f"{where}: contacts.{role}.{k}") for k, v in bindings.items()}
        lines += [""] + role_lines(to, f"{label + '.' if label else ''}{role}", model, bound, peer_names.get(dim, {}))
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
    description = executables.describe(args.scene)
    # Only a scene with contacts of ours needs the models' names (an external scene exports its own parameters).
    peer_names = executables.registries()["contact_model_peer_names"] if contact_roles(description) else {}
    text = export_text(description, solution, args.to, peer_names, where=args.solution)
    if args.out:
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        with open(args.out, "w") as f:
            f.write(text)
        print(args.out)
    else:
        print(text, end="")
    return 0
