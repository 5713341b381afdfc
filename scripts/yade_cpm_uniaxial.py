# A YADE uniaxial compression of its CPM concrete model, timed: the second
# peer of `make bench` (scripts/bench_yade.py runs it as
# `yade -n -jT -x scripts/yade_cpm_uniaxial.py SPHERES STEPS`). A prism of
# regularly packed spheres (w x w x 2w, about SPHERES of them) with CPM's
# bonds, compressed along z by UniaxialStrainer; prints one JSON line with the
# sphere count, the steps and the wall time of the loading steps only.
import json
import math
import sys
import time

from yade import pack
from yade.utils import uniaxialTestFeatures

spheres_asked, steps = int(sys.argv[1]), int(sys.argv[2])
width_m = 0.05
volume = width_m * width_m * 2 * width_m
# Hexagonal close packing fills pi / (3 sqrt 2) of the volume.
radius_m = (math.pi / (3 * math.sqrt(2)) * volume / (spheres_asked * 4.0 / 3.0 * math.pi)) ** (1.0 / 3.0)

concrete = O.materials.append(CpmMat(young=24e9, poisson=0.2, sigmaT=3.5e6, frictionAngle=math.atan(0.8),
                                     epsCrackOnset=1e-4, relDuctility=30, density=4800))
O.bodies.append(pack.regularHexa(pack.inAlignedBox((0, 0, 0), (width_m, width_m, 2 * width_m)), radius=radius_m,
                                 gap=0, material=concrete))
features = uniaxialTestFeatures(axis=2)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.5, label='aabb')], verletDist=0.05 * radius_m),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.5, label='geometry')],
                    [Ip2_CpmMat_CpmMat_CpmPhys()], [Law2_ScGeom_CpmPhys_Cpm()]),
    NewtonIntegrator(damping=0.4),
    UniaxialStrainer(strainRate=-0.5, axis=2, asymmetry=0, posIds=features['posIds'], negIds=features['negIds'],
                     crossSectionArea=features['area'], blockDisplacements=False, blockRotations=False,
                     setSpeeds=True),
]
O.dt = 0.8 * PWaveTimeStep()
O.step()  # bonds form within 1.5 radii, then contacts are searched at their plain reach
aabb.aabbEnlargeFactor = 1.0
geometry.interactionDetectionFactor = 1.0
start = time.time()
O.run(steps, True)
wall_s = time.time() - start
print("YADE_RESULT " + json.dumps({"spheres": len(O.bodies), "steps": steps, "wall_s": wall_s,
                                   "interactions": len(O.interactions), "dt_s": O.dt}))
