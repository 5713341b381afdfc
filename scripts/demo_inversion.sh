#!/usr/bin/env bash
# The inversion stage of `make demo`: micro-parameters for the C30 target of
# Su et al. (30 MPa, 30 GPa, 0.2) on the quadratic surfaces fitted by the
# analysis stage, and a target beyond what the surfaces can reach.
set -euo pipefail
build=${1:-build}
bin="$build/bin"
models="$build/demo/analysis"
out="$build/demo/inversion"
mkdir -p "$out"
surfaces=(--model "$models/ccd_sigma_u.json" --model "$models/bbd_E.json" --model "$models/bbd_nu.json")

echo
echo "demcal demo: inversion of the published surfaces for C30 (sigma_u 30 MPa, E 30 GPa, nu 0.2), GA, 5 restarts, polished"
"$bin/demcal-invert" "${surfaces[@]}" --target sigma_u_MPa=30 --target E_GPa=30 --target nu=0.2 \
  --algo ga --objective sum-rel --restarts 5 --polish --seed 1 --out "$out/c30_ga.json" --history "$out/c30_ga_history.csv"
echo "  the same with the tolerance search + mean-shift (He et al. 2019), 5 % tolerance:"
"$bin/demcal-invert" "${surfaces[@]}" --target sigma_u_MPa=30 --target E_GPa=30 --target nu=0.2 \
  --algo search --samples 20000 --tolerance 0.05 --seed 1 --out "$out/c30_search.json"
/usr/bin/python3 - "$out/c30_search.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print("  %d candidate clusters; largest: %s" % (len(s["candidates"]), ", ".join(
    "%s %.3g" % kv for kv in s["candidates"][0]["x"].items()) if s["candidates"] else "none"))
PY
echo "  and a strength beyond the surfaces' reach (exit code 3 expected):"
set +e
"$bin/demcal-invert" "${surfaces[@]}" --target sigma_u_MPa=120 --target E_GPa=30 --out "$out/unreachable.json"
code=$?
set -e
[ "$code" -eq 3 ] || { echo "demo: expected exit code 3 for an unreachable target, got $code" >&2; exit 1; }
echo
echo "Inversion outputs in $out/: c30_ga.json (+ history), c30_search.json, unreachable.json"
