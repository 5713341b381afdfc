#!/usr/bin/python3
"""TEMPLATE, NOT RUN HERE: runs LIGGGHTS on in.uniaxial.template with demcal's parameters as -var options and
turns its `DEMCAL_OUTPUT NAME VALUE` lines into out.json.  run_point_liggghts.py PARAMS_JSON OUT_JSON"""
import json
import subprocess
import sys

params_path, out_path = sys.argv[1], sys.argv[2]
request = json.load(open(params_path))
args = ["liggghts", "-in", "in.uniaxial.template", "-var", "seed", str(request["seed"])]  # Debian's liggghts 3.8 (/usr/bin/liggghts)
for name, value in request["parameters"].items():
    args += ["-var", name, repr(value)]
done = subprocess.run(args, capture_output=True, text=True)
outputs = {}
for line in done.stdout.splitlines():
    if line.startswith("DEMCAL_OUTPUT "):
        _, name, value = line.split()
        outputs[name] = float(value)
answer = ({"status": "ok", "outputs": outputs} if done.returncode == 0 and outputs else
          {"status": "failed", "reason": f"LIGGGHTS exit {done.returncode}: {done.stderr.strip()[-300:]}"})
json.dump(answer, open(out_path, "w"))
