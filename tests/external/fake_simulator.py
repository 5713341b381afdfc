#!/usr/bin/python3
"""A stand-in simulator for the external-test suite: a known response, and a fault on request.

    fake_simulator.py PARAMS_JSON OUT_JSON [--a=A]

Reads demcal's params file ({"parameters": {...}, "seed": N}) and writes OUT_JSON as an external command must.
Response: y_MPa = 2 a + 3 b + 0.01 (seed mod 5), z = a b, plus an extra output w and a three-point curve. The
parameter `mode` (rounded) asks for a fault instead: 1 reports failure, 2 hangs (with a child process, to check that
a timeout ends the whole group), 3 writes NaN, 4 writes text that is not JSON, 5 exits with status 3, 6 writes no
output file, 7 litters its own folder with files named like demcal's results and then answers, 8 answers after a
second (for a batch to be killed in)."""
import json
import os
import subprocess
import sys
import time


def main():
    params_path, out_path = sys.argv[1], sys.argv[2]
    with open(params_path) as f:
        params = json.load(f)
    x, seed = params["parameters"], params["seed"]
    if len(sys.argv) > 3 and float(sys.argv[3].split("=", 1)[1]) != x["a_MPa"]:
        sys.exit("the {a_MPa} placeholder and params.json disagree")
    mode = int(round(x.get("mode", 0)))
    print(f"fake simulator: mode {mode}, seed {seed}")
    print("fake simulator on stderr", file=sys.stderr)
    answer = {"status": "ok",
              "outputs": {"y_MPa": 2 * x["a_MPa"] + 3 * x["b_MPa"] + 0.01 * (seed % 5), "z": x["a_MPa"] * x["b_MPa"],
                          "w": 1.5},
              "curve": {"axial_strain": [0.0, 0.001, 0.002], "stress_MPa": [0.0, x["a_MPa"], 0.5 * x["a_MPa"]]}}
    if mode == 1:
        answer = {"status": "failed", "reason": "the specimen collapsed under gravity"}
    elif mode == 2:
        child = subprocess.Popen(["sleep", "60"])
        with open("hang_child.pid", "w") as f:
            f.write(str(child.pid))
        time.sleep(60)
    elif mode == 3:
        answer["outputs"]["y_MPa"] = float("nan")
    elif mode == 4:
        with open(out_path, "w") as f:
            f.write("sigma_u = 42\n")
        return
    elif mode == 5:
        print("bad things happened", file=sys.stderr)
        sys.exit(3)
    elif mode == 6:
        return
    elif mode == 7:
        for name in ("run1_seed1.json", "responses.h5", "responses.csv", "params.json.bak"):
            with open(name, "w") as f:
                f.write("litter\n")
    elif mode == 8:
        time.sleep(1.0)
    with open(out_path, "w") as f:
        json.dump(answer, f)


if __name__ == "__main__":
    main()
