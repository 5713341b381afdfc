#!/usr/bin/python3
"""demcal-dem run wrapped as an external command, for the test that an external scene gives exactly the native
scene's numbers:  demcal_dem_driver.py DEMCAL_DEM SCENE PARAMS_JSON OUT_JSON"""
import json
import subprocess
import sys

program, scene, params_path, out_path = sys.argv[1:5]
with open(params_path) as f:
    params = json.load(f)
args = [program, "run", "--scene", scene, "--seed", str(params["seed"]), "--out", "native.json", "--cache", "",
        "--quiet"]
for name, value in params["parameters"].items():
    args += ["--set", f"{name}={value!r}"]
done = subprocess.run(args)
with open("native.json") as f:
    result = json.load(f)
with open(out_path, "w") as f:
    if result["status"] == "ok":
        json.dump({"status": "ok", "outputs": result["macro"]}, f)
    else:
        json.dump({"status": "failed", "reason": result["reason"]}, f)
