#!/usr/bin/python3
"""demcal's external-test driver for LIGGGHTS (Debian package liggghts 3.8): one of demcal's `drum_3d` scenes run
in LIGGGHTS with the same particles, contact laws, drum and measure, so that the two codes compare on equal terms.

    /usr/bin/python3 run_drum_liggghts.py PARAMS_JSON OUT_JSON DRUM_SCENE_JSON

data/external/liggghts/liggghts_drum.json runs it once per point and seed, in the point's own folder. It reads the
drum scene (its particles, drum and run sections and its two contact roles), binds the point's parameters into the
contacts, writes the drum's shell and ends as STL meshes and a LIGGGHTS input, runs `liggghts` on one process, and
measures the free surface's angle from LIGGGHTS' dumps exactly as demcal's drum_3d does (the highest sphere top in
bins across the drum, a line through the middle bins; the mean over the samples; steady when the two halves agree).

What carries over, and what LIGGGHTS does its own way (docs/explanation/liggghts_peer.md):
* spheres only (no clumps); the radii uniform by number between radius_min_m and radius_max_m, in LIGGGHTS as
  `SIZE_CLASSES` equal-number classes at their mid radii;
* `hertz_mindlin` (or `sjkr`) with LIGGGHTS' relative rolling friction (`rolling_friction_cdt_relative`) or none;
  Young's modulus 2 G (1 + nu); the wall's material as a second atom type;
* LIGGGHTS' own insertion (fix insert/pack at the same loose solids fraction), its velocity-Verlet integration and
  its own friction limit; the drum a faceted mesh of `SHELL_FACETS` facets around; the fixed step demcal's
  `run.rayleigh_fraction` sets (LIGGGHTS has no step of its own).
"""
import json
import math
import os
import re
import subprocess
import sys
import time

SIZE_CLASSES = 8
SHELL_FACETS = 120
SKIN_OF_MIN_RADIUS = 0.5  # the neighbour skin, in smallest radii (LIGGGHTS rebuilds when a sphere moved half of it)
GRAVITY_M_S2 = 9.81
DRUM_DEFAULTS = {"fill_fraction": 0.3, "bed_solids_fraction": 0.55}
RUN_DEFAULTS = {"settle_time_s": 0.5, "measure_from_s": 1.0, "measure_time_s": 2.0, "sample_every_s": 0.05,
                "surface_fraction": 0.6, "steady_tolerance_deg": 2.0, "bin_width_diameters": 1.5, "max_wall_s": 600,
                "local_damping": 0.0, "safety_factor": 0.8, "rayleigh_fraction": 0.0}
CONTACT_KEYS = {"shear_modulus_pa", "poisson", "shear_modulus_2_pa", "poisson_2", "restitution", "friction",
                "rolling_friction_cdt_relative", "cohesion_energy_density_j_m3"}


class Refused(Exception):
    """A scene or parameter this driver cannot run in LIGGGHTS: the point fails with this reason."""


def bind(expression, values, where):
    """A scene binding as demcal reads it: a number, a parameter's name, or a product of both ("a*b*2")."""
    if isinstance(expression, (int, float)) and not isinstance(expression, bool):
        return float(expression)
    product = 1.0
    for factor in str(expression).split("*"):
        try:
            product *= float(factor)
        except ValueError:
            if factor not in values:
                raise Refused(f"{where}: \"{factor}\" in \"{expression}\" is neither a number nor a parameter")
            product *= float(values[factor])
    return product


def section_numbers(scene, section, defaults, values):
    raw = scene.get(section, {})
    out = dict(defaults)
    for key, value in raw.items():
        if key == "note":
            continue
        out[key] = bind(value, values, f"{section}.{key}")
    return out


def read_drum(scene, values):
    """The drum scene's geometry, run and contacts with the point's parameters bound."""
    if scene.get("test") != "drum_3d":
        raise Refused(f"test is \"{scene.get('test')}\": this driver runs drum_3d scenes")
    particles = section_numbers(scene, "particles", {"clump_aspect_ratio": 1.0, "clump_fraction": 0.0}, values)
    if particles.get("clump_fraction", 0) > 0 and particles.get("clump_aspect_ratio", 1) > 1:
        raise Refused("particles: clumps (clump_fraction > 0): Debian's LIGGGHTS-PUBLIC has no multisphere; use spheres")
    drum = section_numbers(scene, "drum", DRUM_DEFAULTS, values)
    run = section_numbers(scene, "run", RUN_DEFAULTS, values)
    if run["local_damping"] != 0:
        raise Refused("run.local_damping: LIGGGHTS has no local damping; set it to 0")
    if not run["rayleigh_fraction"] > 0:
        raise Refused("run.rayleigh_fraction: LIGGGHTS needs a fixed step; give it as a fraction of the Rayleigh step")
    contacts = {}
    for role in ("particle-particle", "particle-wall"):
        contact = scene.get("contacts", {}).get(role)
        if contact is None:
            raise Refused(f"contacts.{role}: missing")
        if contact.get("model") not in ("hertz_mindlin", "sjkr"):
            raise Refused(f"contacts.{role}.model \"{contact.get('model')}\": LIGGGHTS runs hertz_mindlin or sjkr here")
        bound = {}
        for key, value in contact.get("parameters", {}).items():
            if key not in CONTACT_KEYS:
                raise Refused(f"contacts.{role}.parameters.{key}: no LIGGGHTS counterpart in this driver "
                              "(rolling resistance: rolling_friction_cdt_relative only)")
            bound[key] = bind(value, values, f"contacts.{role}.parameters.{key}")
        bound["model"] = contact["model"]
        contacts[role] = bound
    pp, pw = contacts["particle-particle"], contacts["particle-wall"]
    for key in ("shear_modulus_pa", "poisson"):
        if pw.get(key, pp.get(key)) != pp.get(key):
            raise Refused(f"contacts.particle-wall.parameters.{key}: differs from particle-particle's; LIGGGHTS "
                          "gives the particles one material")
    if pp["model"] != pw["model"]:
        raise Refused("contacts: particle-particle and particle-wall must use the same model in LIGGGHTS")
    return particles, drum, run, contacts


def rayleigh_step_s(particles, pp):
    """As demcal's powder tests: pi R_min sqrt(rho / G) / (0.1631 nu + 0.8766)."""
    return (math.pi * particles["radius_min_m"] * math.sqrt(particles["density_kg_m3"] / pp["shear_modulus_pa"]) /
            (0.1631 * pp["poisson"] + 0.8766))


def youngs_modulus_pa(shear_modulus_pa, poisson):
    return 2 * shear_modulus_pa * (1 + poisson)


def write_drum_stl(path, radius_m, length_m, facets=SHELL_FACETS):
    """The drum's shell and both ends as one ASCII STL, the axis along y, centred on the origin."""
    half = 0.5 * length_m
    ring = [(radius_m * math.cos(2 * math.pi * k / facets), radius_m * math.sin(2 * math.pi * k / facets))
            for k in range(facets)]
    triangles = []
    for k in range(facets):
        (x0, z0), (x1, z1) = ring[k], ring[(k + 1) % facets]
        a, b, c, d = (x0, -half, z0), (x1, -half, z1), (x1, half, z1), (x0, half, z0)
        triangles += [(a, b, c), (a, c, d)]
        triangles += [((0, -half, 0), b, a), ((0, half, 0), d, c)]  # the ends as fans from the axis
    with open(path, "w") as f:
        f.write("solid drum\n")
        for t in triangles:
            f.write("facet normal 0 0 0\nouter loop\n")
            for v in t:
                f.write(f"vertex {v[0]:.9e} {v[1]:.9e} {v[2]:.9e}\n")
            f.write("endloop\nendfacet\n")
        f.write("endsolid drum\n")
    return len(triangles)


def liggghts_seeds(seed, count):
    """LIGGGHTS wants its random seeds prime and above 10,000: `count` distinct primes from the point's seed."""
    def is_prime(n):
        return n > 1 and all(n % d for d in range(2, int(math.isqrt(n)) + 1))
    out, n = [], 10007 + 1000 * (int(seed) % 100000)
    while len(out) < count:
        if is_prime(n):
            out.append(n)
        n += 1
    return out


def steps_for(time_s, dt_s):
    return max(1, int(math.ceil(time_s / dt_s - 1e-9)))


def write_input(path, particles, drum, run, contacts, dt_s, seed):
    """Writes the LIGGGHTS input; returns the step of the first surface sample, the last step, the steps between
    samples and the loose fill's solids fraction."""
    pp, pw = contacts["particle-particle"], contacts["particle-wall"]
    radius, length = 0.5 * drum["inner_diameter_m"], drum["length_m"]
    r_min, r_max = particles["radius_min_m"], particles["radius_max_m"]
    margin = 4 * r_max
    y_particle = youngs_modulus_pa(pp["shear_modulus_pa"], pp["poisson"])
    y_wall = youngs_modulus_pa(pw.get("shear_modulus_2_pa", pp["shear_modulus_pa"]), pw.get("poisson_2", pp["poisson"]))
    nu_wall = pw.get("poisson_2", pp["poisson"])

    def pair(key, default=None):
        a, b = pp.get(key, default), pw.get(key, default)
        return f"{a:.17g} {b:.17g} {b:.17g} {b:.17g}"

    rolling = "rolling_friction_cdt_relative" in pp or "rolling_friction_cdt_relative" in pw
    cohesion = pp["model"] == "sjkr"
    model = "model hertz tangential history" + (" cohesion sjkr" if cohesion else "") + \
        (" rolling_friction cdt" if rolling else "")
    s_distribution, s_insert, *s_sizes = liggghts_seeds(seed, 2 + SIZE_CLASSES)
    spin_period_s = 60.0 / drum["speed_rpm"]
    settle = steps_for(run["settle_time_s"], dt_s)
    to_first = steps_for(run["measure_from_s"], dt_s)
    every = max(1, int(round(run["sample_every_s"] / dt_s)))
    measure = steps_for(run["measure_time_s"], dt_s)
    fill = drum["fill_fraction"] * drum["bed_solids_fraction"]
    lines = [
        "# written by run_drum_liggghts.py from a demcal drum_3d scene",
        "atom_style granular", "atom_modify map array", "boundary f f f", "newton off",
        "communicate single vel yes", "units si", "processors 1 1 1",
        "hard_particles yes",  # LIGGGHTS refuses Young's moduli above 1e9 Pa (a steel wall) without it
        f"region domain block {-radius - margin:.9e} {radius + margin:.9e} {-0.5 * length - margin:.9e} "
        f"{0.5 * length + margin:.9e} {-radius - margin:.9e} {radius + margin:.9e} units box",
        "create_box 2 domain",
        f"neighbor {SKIN_OF_MIN_RADIUS * r_min:.9e} bin", "neigh_modify delay 0",
        f"fix m1 all property/global youngsModulus peratomtype {y_particle:.17g} {y_wall:.17g}",
        f"fix m2 all property/global poissonsRatio peratomtype {pp['poisson']:.17g} {nu_wall:.17g}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 2 {pair('restitution')}",
        f"fix m4 all property/global coefficientFriction peratomtypepair 2 {pair('friction')}",
    ]
    if rolling:
        lines.append(f"fix m5 all property/global coefficientRollingFriction peratomtypepair 2 "
                     f"{pair('rolling_friction_cdt_relative', 0.0)}")
    if cohesion:
        lines.append(f"fix m6 all property/global cohesionEnergyDensity peratomtypepair 2 "
                     f"{pair('cohesion_energy_density_j_m3', 0.0)}")
    lines += [
        f"pair_style gran {model}", "pair_coeff * *", f"timestep {dt_s:.17g}",
        f"fix gravity all gravity {GRAVITY_M_S2} vector 0 0 -1",
        "fix drum all mesh/surface file drum.stl type 2",
        f"fix walls all wall/gran {model} mesh n_meshes 1 meshes drum",
    ]
    classes = []
    for k in range(SIZE_CLASSES):
        r = r_min + (k + 0.5) * (r_max - r_min) / SIZE_CLASSES
        lines.append(f"fix size{k} all particletemplate/sphere {s_sizes[k]} atom_type 1 "
                     f"density constant {particles['density_kg_m3']:.17g} radius constant {r:.9e}")
        classes.append(f"size{k} {1.0 / SIZE_CLASSES:.17g}")
    lines += [
        f"fix sizes all particledistribution/discrete/numberbased {s_distribution} {SIZE_CLASSES} {' '.join(classes)}",
        f"region fill cylinder y 0 0 {radius:.9e} {-0.5 * length:.9e} {0.5 * length:.9e} units box",
        f"fix fill all insert/pack seed {s_insert} distributiontemplate sizes insert_every once overlapcheck yes "
        f"all_in yes volumefraction_region {fill:.17g} region fill",
        "fix integrate all nve/sphere",
        "thermo_style custom step atoms ke", f"thermo {max(1, settle // 4)}", "thermo_modify lost error norm no",
        "run 1", "unfix fill",
        f"run {settle}",
        f"fix turn all move/mesh mesh drum rotate origin 0 0 0 axis 0 1 0 period {spin_period_s:.17g}",
        f"run {to_first}",
        f"dump surface all custom {every} dump.surface id x y z radius",
        "dump_modify surface first yes",
        f"run {measure}",
    ]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    first_sample_step = 1 + settle + to_first
    return {"first_sample_step": first_sample_step, "last_step": first_sample_step + measure, "every": every,
            "fill_solids_fraction": fill}


def read_dump_frames(path):
    """[(timestep, {"x": [...], "y": [...], "z": [...], "radius": [...]})] from a LAMMPS custom dump."""
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        if not lines[k].startswith("ITEM: TIMESTEP"):
            k += 1
            continue
        step = int(lines[k + 1])
        count = int(lines[k + 3])
        header = lines[k + 8].split()[2:]
        columns = {name: [] for name in header}
        for row in lines[k + 9:k + 9 + count]:
            for name, value in zip(header, row.split()):
                columns[name].append(float(value))
        frames.append((step, columns))
        k += 9 + count
    return frames


def fit_slope(x, z):
    n = len(x)
    mx, mz = sum(x) / n, sum(z) / n
    sxx = sum((a - mx) ** 2 for a in x)
    if sxx <= 0:
        raise Refused("the drum's free surface has no horizontal spread")
    return sum((a - mx) * (b - mz) for a, b in zip(x, z)) / sxx


def surface_angle_deg(x_m, z_m, radius_m, drum_radius_m, bin_m, surface_fraction):
    """demcal's drum_3d measure: the highest sphere top in bins across the drum, a line through the middle
    surface_fraction of the bins that hold spheres, atan of its slope's magnitude."""
    bins = int(math.ceil(2 * drum_radius_m / bin_m))
    top = [-math.inf] * bins
    for x, z, r in zip(x_m, z_m, radius_m):
        b = int(min(max((x + drum_radius_m) / bin_m, 0.0), bins - 1))
        top[b] = max(top[b], z + r)
    held = [b for b in range(bins) if math.isfinite(top[b])]
    if not held:
        raise Refused("no particle in the drum's cross-section")
    first, last = held[0], held[-1]
    span = last - first + 1
    skip = 0.5 * (1 - surface_fraction) * span
    xs, zs = [], []
    for b in range(first, last + 1):
        k = b - first
        if k < skip or k > span - 1 - skip or not math.isfinite(top[b]):
            continue
        xs.append(-drum_radius_m + (b + 0.5) * bin_m)
        zs.append(top[b])
    if len(xs) < 2:
        raise Refused("too few surface bins to fit the drum's free surface (widen the drum or narrow the bins)")
    return math.degrees(math.atan(abs(fit_slope(xs, zs))))


def steady_angle(angles, tolerance_deg):
    """The mean, SD and halves' means; a Refused reason when not steady or too few samples."""
    n = len(angles)
    if n < 4:
        raise Refused(f"only {n} surface samples (at least 4): lengthen run.measure_time_s")
    half = n // 2
    first, second = sum(angles[:half]) / half, sum(angles[half:]) / (n - half)
    mean = sum(angles) / n
    sd = math.sqrt(sum((a - mean) ** 2 for a in angles) / (n - 1))
    if abs(first - second) > tolerance_deg:
        chance = sd * math.sqrt(1 / half + 1 / (n - half))
        raise Refused(f"no steady state: the surface's angle moved from {first:.4g} to {second:.4g} deg between the "
                      f"halves of the measuring window (run.steady_tolerance_deg {tolerance_deg:g}); the samples "
                      f"scatter by {sd:.3g} deg (SD), so the halves of a steady flow differ by about {chance:.2g} deg "
                      "or more")
    return mean, sd, first, second


def loop_times(log_text):
    """[(seconds, steps, atoms)] of every `run` in a LIGGGHTS log."""
    return [(float(m.group(1)), int(m.group(2)), int(m.group(3))) for m in
            re.finditer(r"Loop time of ([0-9.eE+-]+) on \d+ procs? for (\d+) steps with (\d+) atoms", log_text)]


def run_point(request, scene):
    values = dict(request["parameters"])
    particles, drum, run, contacts = read_drum(scene, values)
    pp = contacts["particle-particle"]
    dt_s = run["rayleigh_fraction"] * rayleigh_step_s(particles, pp)
    facets = write_drum_stl("drum.stl", 0.5 * drum["inner_diameter_m"], drum["length_m"])
    plan = write_input("in.drum", particles, drum, run, contacts, dt_s, int(request["seed"]))
    if os.path.exists("dump.surface"):
        os.remove("dump.surface")
    start = time.monotonic()
    try:
        done = subprocess.run(["liggghts", "-in", "in.drum", "-log", "log.liggghts", "-echo", "none"],
                              capture_output=True, text=True, timeout=run["max_wall_s"])
    except FileNotFoundError:
        raise Refused("liggghts is not installed (Debian package liggghts: apt-get install liggghts)")
    except subprocess.TimeoutExpired:
        raise Refused(f"timeout: LIGGGHTS ran longer than run.max_wall_s {run['max_wall_s']:g} s")
    wall_s = time.monotonic() - start
    log = open("log.liggghts").read() if os.path.exists("log.liggghts") else ""
    if done.returncode != 0:
        errors = [line for line in log.splitlines() + done.stderr.splitlines() if "ERROR" in line]
        raise Refused(f"LIGGGHTS exit {done.returncode}: {(errors[-1] if errors else done.stderr.strip()[-300:])}")
    runs = loop_times(log)
    particle_steps = sum(steps * atoms for _, steps, atoms in runs)
    loop_s = sum(seconds for seconds, _, _ in runs)
    frames = [(step, f) for step, f in read_dump_frames("dump.surface")
              if plan["first_sample_step"] <= step <= plan["last_step"]]
    if not frames:
        raise Refused("LIGGGHTS wrote no surface sample in the measuring window")
    atoms = len(frames[-1][1]["x"])
    expected = plan["fill_solids_fraction"] * math.pi * (0.5 * drum["inner_diameter_m"]) ** 2 * drum["length_m"]
    placed = sum(4.0 / 3.0 * math.pi * r ** 3 for r in frames[-1][1]["radius"])
    if placed < 0.95 * expected:
        raise Refused(f"LIGGGHTS inserted {atoms} spheres filling {placed / expected:.3f} of the fill's volume "
                      "(fewer than 95 %): the fill does not fit its vessel")
    bin_m = run["bin_width_diameters"] * (particles["radius_min_m"] + particles["radius_max_m"])
    angles = [surface_angle_deg(f["x"], f["z"], f["radius"], 0.5 * drum["inner_diameter_m"], bin_m,
                                run["surface_fraction"]) for _, f in frames]
    mean, sd, first, second = steady_angle(angles, run["steady_tolerance_deg"])
    with open("angles.csv", "w") as f:  # the samples, for a look at how steady the flow was
        f.write("time_s,angle_deg\n")
        f.writelines(f"{(step - 1) * dt_s:.6g},{a:.6g}\n" for (step, _), a in zip(frames, angles))
    return {"status": "ok",
            "outputs": {"aor_deg": mean, "aor_sd_deg": sd, "aor_first_half_deg": first, "aor_second_half_deg": second,
                        "particles": atoms, "samples": len(angles), "dt_s": dt_s, "steps": sum(s for _, s, _ in runs),
                        "particle_steps": particle_steps, "loop_time_s": loop_s, "wall_s": wall_s,
                        "particle_steps_per_s": particle_steps / loop_s if loop_s > 0 else 0.0,
                        "mesh_triangles": facets}}


def main(argv):
    if len(argv) != 4:
        sys.exit("usage: run_drum_liggghts.py PARAMS_JSON OUT_JSON DRUM_SCENE_JSON")
    params_path, out_path, scene_path = argv[1:]
    with open(params_path) as f:
        request = json.load(f)
    with open(scene_path) as f:
        scene = json.load(f)
    try:
        answer = run_point(request, scene)
    except Refused as e:
        answer = {"status": "failed", "reason": f"{os.path.basename(scene_path)}: {e}"}
    with open(out_path, "w") as f:
        json.dump(answer, f)


if __name__ == "__main__":
    main(sys.argv)
