#!/usr/bin/python3
"""The YADE peers of `make bench`, one thread each, per particle-step:

1. its CPM concrete in uniaxial compression (scripts/yade_cpm_uniaxial.py) at
   two sizes against our 2D parallel-bonded UCS at similar particle counts: a
   different model, and 3D spheres (about 30 interactions each, as YADE counts
   them) against 2D disks (a few bonds each), so not equal work;
2. its cohesive-frictional model (CohFrictMat: normal, shear, rolling and
   twisting bonds; scripts/yade_cohfrict_uniaxial.py) on our own exported 3D
   cylinder with our exported material, against our 3D parallel-bonded UCS of
   that cylinder: the same spheres and bonds per sphere, a related (not the
   same) bond law.

Debian's yade is installed here on demand, never by `make test`.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import debian_package

YADE_SIZES = [(3000, 400), (12000, 100)]  # spheres asked, steps
OURS = [("data/scenes/ucs_rock_pb.json", "25 x 50 mm"), ("data/scenes/bench/ucs_pb_9k.json", "50 x 100 mm")]


def run_yade(spheres, steps, workdir):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "yade_cpm_uniaxial.py")
    out = subprocess.run(["yade", "-n", "-j1", "-x", script, str(spheres), str(steps)], capture_output=True,
                         text=True, cwd=workdir)
    for line in out.stdout.splitlines():
        if line.startswith("YADE_RESULT "):
            return json.loads(line[len("YADE_RESULT "):])
    sys.exit("bench_yade: YADE printed no result:\n" + (out.stdout + out.stderr)[-2000:])


SCENE_3D = "data/scenes/ucs_rock_pb_3d.json"
YADE_3D_STEPS = 10000


def run_yade_cohfrict(binary, cache, workdir, dt_s, platen_speed_m_s):
    """Exports the 3D scene's packing and its material at the scene's defaults, runs YADE on them."""
    spheres = os.path.join(workdir, "spheres.txt")
    subprocess.run([binary, "export", "--scene", SCENE_3D, "--cache", cache, "--yade", spheres, "--quiet"], check=True)
    described = json.loads(subprocess.run([binary, "describe", "--scene", SCENE_3D], check=True, capture_output=True,
                                          text=True).stdout)
    parameters = os.path.join(workdir, "parameters.json")
    with open(parameters, "w") as f:
        json.dump({"parameters": described["parameters"]}, f)
    material = os.path.join(workdir, "material.py")
    env = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"),
               BIN=os.path.dirname(binary))
    subprocess.run([sys.executable, "-m", "demcal_study", "export", "--solution", parameters, "--scene", SCENE_3D,
                    "--to", "yade", "--out", material], check=True, env=env, capture_output=True)
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "yade_cohfrict_uniaxial.py")
    out = subprocess.run(["yade", "-n", "-j1", "-x", script, spheres, material, str(YADE_3D_STEPS), repr(dt_s),
                          repr(platen_speed_m_s)], capture_output=True, text=True, cwd=workdir)
    for line in out.stdout.splitlines():
        if line.startswith("YADE_RESULT "):
            return json.loads(line[len("YADE_RESULT "):])
    sys.exit("bench_yade: YADE printed no result:\n" + (out.stdout + out.stderr)[-2000:])


def run_ours(binary, scene, cache, workdir):
    out = os.path.join(workdir, "ours.json")
    subprocess.run([binary, "run", "--scene", scene, "--cache", cache, "--threads", "1", "--quiet", "--out", out],
                   check=True)
    with open(out) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    args = parser.parse_args()
    debian_package.ensure("yade", "yade", "bench_yade")
    binary = os.path.join(args.build, "bin", "demcal-dem")
    cache = os.path.join(args.build, "cache")
    print(f"peer: YADE {debian_package.version('yade')}, CPM uniaxial compression of a prism "
          "(3D spheres); demcal: parallel-bonded UCS (2D disks); one thread each")
    print(f"{'YADE spheres':>12} {'steps':>6} {'interactions/sphere':>19} {'M/s':>7}   {'demcal disks':>12} {'steps':>6} "
          f"{'M/s':>7}   {'ratio per particle-step':>23}")
    with tempfile.TemporaryDirectory() as workdir:
        for (spheres, steps), (scene, _) in zip(YADE_SIZES, OURS):
            yade = run_yade(spheres, steps, workdir)
            ours = run_ours(binary, scene, cache, workdir)
            yade_rate = yade["spheres"] * yade["steps"] / yade["wall_s"]
            ours_rate = ours["particles"] * ours["steps"] / ours["test_wall_s"]
            print(f"{yade['spheres']:>12} {yade['steps']:>6} {2 * yade['interactions'] / yade['spheres']:>19.1f} "
                  f"{yade_rate / 1e6:>7.2f}   {ours['particles']:>12} {ours['steps']:>6} {ours_rate / 1e6:>7.2f}   "
                  f"{ours_rate / yade_rate:>22.1f}x")
    print("ratio: demcal particle-steps/s over YADE's (different models and dimensions: a per-particle figure only)")

    print()
    print(f"3D: YADE {debian_package.version('yade')} CohFrictMat (normal, shear, rolling and twisting bonds) against "
          f"demcal's parallel bond, uniaxial compression of the same exported cylinder ({SCENE_3D}), one thread each")
    with tempfile.TemporaryDirectory() as workdir:
        ours = run_ours(binary, SCENE_3D, cache, workdir)
        with open(SCENE_3D) as f:
            speed = json.load(f)["loading"]["platen_velocity_m_s"]
        yade = run_yade_cohfrict(binary, cache, workdir, ours["dt_s"], speed)
    yade_rate = yade["spheres"] * yade["steps"] / yade["wall_s"]
    ours_rate = ours["particles"] * ours["steps"] / ours["test_wall_s"]
    print(f"{'':>8} {'spheres':>8} {'steps':>7} {'bonds/sphere':>12} {'wall s':>8} {'M particle-steps/s':>19}")
    print(f"{'YADE':>8} {yade['spheres']:>8} {yade['steps']:>7} {2 * yade['bonds'] / yade['spheres']:>12.2f} "
          f"{yade['wall_s']:>8.1f} {yade_rate / 1e6:>19.2f}   (platen stress at the end {yade['platen_stress_MPa']:.2f} MPa)")
    print(f"{'demcal':>8} {ours['particles']:>8} {ours['steps']:>7} {ours['specimen']['bonds_per_sphere']:>12.2f} "
          f"{ours['test_wall_s']:>8.1f} {ours_rate / 1e6:>19.2f}   (to failure: sigma_u {ours['macro']['sigma_u_MPa']:.2f} MPa)")
    print(f"ratio per particle-step: {ours_rate / yade_rate:.2f}x (same spheres and bonds per sphere; related, not "
          "identical, bond laws; YADE over its first steps, demcal over the whole test)")


if __name__ == "__main__":
    main()
