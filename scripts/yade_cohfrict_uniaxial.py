# YADE's cohesive-frictional model (CohFrictMat: normal, shear, rolling and
# twisting bonds) on our exported 3D cylinder, in uniaxial compression between
# two frictionless platens, timed: the 3D bonded peer of `make bench`
# (scripts/bench_yade.py runs it as
# `yade -n -j1 -x scripts/yade_cohfrict_uniaxial.py SPHERES MATERIAL STEPS DT SPEED`).
# SPHERES is `demcal-dem export --yade`'s x y z r file, MATERIAL the
# `python -m demcal_study export --to yade` file of the same scene (its
# particle_particle and particle_platen dicts). Bonds are made at the first
# step between spheres closer than 1 % of their radii sum; each platen then
# moves in at SPEED. Prints one JSON line: spheres, steps, wall time of the
# loading steps only, interactions and bonds, the platens' mean stress at the end.
import json
import math
import re
import sys
import time

from yade import ymport

spheres_path, material_path = sys.argv[1], sys.argv[2]
steps, dt_s, speed_m_s = int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])

with open(spheres_path) as f:
    header = f.readline()
density = float(re.search(r"density ([0-9.eE+-]+) kg/m3", header).group(1))
exported = {}
with open(material_path) as f:
    exec(f.read(), {}, exported)


def material(entry, **extra):
    kind = {"CohFrictMat": CohFrictMat, "FrictMat": FrictMat}[entry["kind"]]
    return kind(density=density, **{k: v for k, v in entry.items() if k != "kind"}, **extra)


rock = O.materials.append(material(exported["particle_particle"], momentRotationLaw=True))
platen = O.materials.append(material(exported["particle_platen"]))
spheres = O.bodies.append(ymport.text(spheres_path, material=rock))
low = min(O.bodies[i].state.pos[2] - O.bodies[i].shape.radius for i in spheres)
high = max(O.bodies[i].state.pos[2] + O.bodies[i].shape.radius for i in spheres)
radius = max(math.hypot(O.bodies[i].state.pos[0], O.bodies[i].state.pos[1]) + O.bodies[i].shape.radius for i in spheres)
bottom = O.bodies.append(utils.wall((0, 0, low), axis=2, sense=1, material=platen))
top = O.bodies.append(utils.wall((0, 0, high), axis=2, sense=-1, material=platen))
O.bodies[bottom].state.vel = Vector3(0, 0, speed_m_s)
O.bodies[top].state.vel = Vector3(0, 0, -speed_m_s)

mean_radius = sum(O.bodies[i].shape.radius for i in spheres) / len(spheres)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.01, label="aabb"), Bo1_Wall_Aabb()],
                          verletDist=0.25 * mean_radius),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=1.01, label="geometry"),
                     Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True), Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True),
                     Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.7),
]
O.dt = dt_s
# The bonds form within 1 % of the radii sum in a first step too short to move anything; each then starts
# force-free as it lies (its plastic normal displacement set to its overlap), as our bonds do, and nothing moves.
# The contacts are searched at their plain reach from then on.
O.dt = 1e-30 * dt_s
O.step()
O.dt = dt_s
for i in O.interactions:
    if i.isReal and isinstance(i.phys, CohFrictPhys):
        i.phys.unp = i.geom.penetrationDepth
for j in spheres:
    O.bodies[j].state.vel = O.bodies[j].state.angVel = Vector3(0, 0, 0)
aabb.aabbEnlargeFactor = -1
geometry.interactionDetectionFactor = 1
bonds = sum(1 for i in O.interactions if i.isReal and isinstance(i.phys, CohFrictPhys) and i.phys.cohesionBroken is False)
start = time.time()
O.run(steps, True)
wall_s = time.time() - start
area = math.pi * radius * radius
stress = 0.5 * (abs(O.forces.f(bottom)[2]) + abs(O.forces.f(top)[2])) / area
print("YADE_RESULT " + json.dumps({"spheres": len(spheres), "steps": steps, "wall_s": wall_s, "dt_s": O.dt,
                                   "interactions": sum(1 for i in O.interactions if i.isReal), "bonds": bonds,
                                   "platen_stress_MPa": stress / 1e6}))
