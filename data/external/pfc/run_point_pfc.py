# TEMPLATE, NOT RUN HERE (PFC is not available on this machine): a demcal external-test driver for PFC2D 7 or
# later, run by PFC's embedded Python. Fill in the lines marked FILL IN; docs/howto/own_simulator.md says how the scene calls it.
#
# demcal writes params.json ({"parameters": {...}, "seed": N}) and expects out.json; this script reads the one and
# writes the other around your own PFC model (a restored specimen, your loading, your measurement).
import json
import sys

import itasca as it  # only inside PFC

params_path, out_path = sys.argv[1], sys.argv[2]
with open(params_path) as f:
    request = json.load(f)
p, seed = request["parameters"], request["seed"]

try:
    it.command("model new")
    it.command(f"model random {seed}")
    # FILL IN: build or restore the specimen of this seed, e.g. it.command("model restore 'specimen_%d'" % seed).
    # The names below are those of the scene data/external/pfc/pfc_linearpbond.json; PFC's own property names:
    it.command(f"contact method bond gap 0.0")
    it.command("contact model linearpbond")
    it.command(f"contact method deform emod {p['Ec_GPa'] * 1e9} krat {p['kn_ks']}")
    it.command(f"contact method pb_deform emod {p['Ec_GPa'] * 1e9} krat {p['kn_ks']}")
    it.command(f"contact property pb_ten {p['pb_sigma_c_MPa'] * 1e6} pb_coh {p['pb_tau_c_MPa'] * 1e6} "
               f"fric {p['mu']}")
    # FILL IN: your UCS loading (wall servo or velocity), cycling until the stress falls to 70 % of the peak,
    # recording the axial stress and strain; then compute the outputs below from your history.
    sigma_u_MPa = float("nan")  # FILL IN
    E_GPa = float("nan")        # FILL IN
    answer = {"status": "ok", "outputs": {"sigma_u_MPa": sigma_u_MPa, "E_GPa": E_GPa}}
except Exception as e:  # a failed point is recorded with this reason and the batch goes on
    answer = {"status": "failed", "reason": f"PFC: {e}"}
with open(out_path, "w") as f:
    json.dump(answer, f)
