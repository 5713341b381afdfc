# demcal's external-test driver for YADE: a uniaxial compression of YADE's CPM concrete model (Jirasek's
# concrete particle model) on a small prism, run as
#     yade -n -j1 -x run_point.py PARAMS_JSON OUT_JSON
# by data/external/yade/yade_cpm_uniaxial.json (one folder per point and seed, made by demcal).
#
# Specimen: a 25 x 25 x 50 mm prism of about 1,500 spheres on a hexagonal lattice, each sphere moved by a random
# offset of up to 5 % of its radius drawn from the point's seed (so seeds give different specimens, as our packings
# do). Loading: YADE's UniaxialStrainer along z at a constant strain rate until the stress falls below 80 % of its
# peak after the peak (or a strain limit). Outputs: sigma_u_MPa (peak axial stress), E_GPa (least-squares slope of
# stress on strain between 10 % and 40 % of the peak, before it), and the curve.
import json
import math
import random
import sys

from yade import pack
from yade.utils import uniaxialTestFeatures

params_path, out_path = sys.argv[1], sys.argv[2]
with open(params_path) as f:
    request = json.load(f)
p, seed = request["parameters"], int(request["seed"])


def finish(answer):
    with open(out_path, "w") as f:
        json.dump(answer, f)
    sys.exit(0)


width_m, spheres = 0.025, 1500
volume = width_m * width_m * 2 * width_m
radius_m = (math.pi / (3 * math.sqrt(2)) * volume / (spheres * 4.0 / 3.0 * math.pi)) ** (1.0 / 3.0)
concrete = O.materials.append(CpmMat(young=p["young_GPa"] * 1e9, poisson=p["poisson"], sigmaT=p["sigmaT_MPa"] * 1e6,
                                     frictionAngle=math.atan(0.8), epsCrackOnset=p["epsCrackOnset_1e4"] * 1e-4,
                                     relDuctility=p["relDuctility"], density=4800))
bodies = pack.regularHexa(pack.inAlignedBox((0, 0, 0), (width_m, width_m, 2 * width_m)), radius=radius_m, gap=0,
                          material=concrete)
rng = random.Random(seed)
for b in bodies:
    b.state.pos += Vector3(*(rng.uniform(-0.05, 0.05) * radius_m for _ in range(3)))
O.bodies.append(bodies)
features = uniaxialTestFeatures(axis=2)
strain_rate = -0.5  # 1/s: quasi-static for this prism (its P-wave crosses it in about 1e-5 s)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.5, label="aabb")], verletDist=0.05 * radius_m),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.5, label="geometry")],
                    [Ip2_CpmMat_CpmMat_CpmPhys()], [Law2_ScGeom_CpmPhys_Cpm()]),
    NewtonIntegrator(damping=0.4),
    UniaxialStrainer(strainRate=strain_rate, axis=2, asymmetry=0, posIds=features["posIds"],
                     negIds=features["negIds"], crossSectionArea=features["area"], blockDisplacements=False,
                     blockRotations=False, setSpeeds=True, label="strainer"),
]
O.dt = 0.8 * PWaveTimeStep()
O.step()  # bonds form within 1.5 radii; then contacts are searched at their plain reach
aabb.aabbEnlargeFactor = 1.0
geometry.interactionDetectionFactor = 1.0

strain, stress = [], []
max_steps, every = 200000, 20
peak = 0.0
while O.iter < max_steps:
    O.run(every, True)
    eps, sig = -strainer.strain, -strainer.avgStress
    if not (math.isfinite(eps) and math.isfinite(sig)):
        finish({"status": "failed", "reason": f"non-finite stress or strain at step {O.iter}"})
    strain.append(eps)
    stress.append(sig)
    peak = max(peak, sig)
    if peak > 0 and sig < 0.8 * peak and stress.index(peak) < len(stress) - 1:
        break
    if eps > 0.02:
        finish({"status": "failed", "reason": "no peak before 2 % axial strain"})
else:
    finish({"status": "failed", "reason": f"no peak within {max_steps} steps"})

k_peak = stress.index(peak)
window = [(e, s) for e, s in zip(strain[:k_peak + 1], stress[:k_peak + 1]) if 0.1 * peak <= s <= 0.4 * peak]
if len(window) < 3:
    finish({"status": "failed", "reason": f"only {len(window)} curve points between 10 and 40 % of the peak"})
me = sum(e for e, _ in window) / len(window)
ms = sum(s for _, s in window) / len(window)
slope = sum((e - me) * (s - ms) for e, s in window) / sum((e - me) ** 2 for e, _ in window)
finish({"status": "ok",
        "outputs": {"sigma_u_MPa": peak / 1e6, "E_GPa": slope / 1e9, "peak_strain": strain[k_peak],
                    "spheres": len(O.bodies), "steps": O.iter},
        "curve": {"axial_strain": strain, "stress_MPa": [s / 1e6 for s in stress]}})
