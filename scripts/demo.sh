#!/usr/bin/env bash
# `make demo`: runs the stages of the default study that exist so far and says
# where the outputs are. Today: the designs of the concrete study (Su et al.
# 2021) in natural units with their property reports.
set -euo pipefail
build=${1:-build}
bin="$build/bin"
out="$build/demo"
mkdir -p "$out"

echo "demcal demo: designs of the concrete study (13 micro-parameters, data/spaces/su2021_*.json)"
"$bin/demcal-doe" oa --space data/spaces/su2021_concrete.json --runs 64 --blank 1 \
  --out "$out/screening_L64.csv" --report --quiet > "$out/screening_L64.md"
"$bin/demcal-doe" oa --space data/spaces/su2021_concrete.json --runs 64 --blank 1 \
  --out "$out/screening_L64.h5" --quiet
"$bin/demcal-doe" ccd --space data/spaces/su2021_ccd_sigma_u.json --out "$out/ccd_sigma_u.csv" --report --quiet \
  > "$out/ccd_sigma_u.md"
"$bin/demcal-doe" bbd --space data/spaces/su2021_bbd_E.json --out "$out/bbd_E.csv" --report --quiet > "$out/bbd_E.md"
"$bin/demcal-doe" bbd --space data/spaces/su2021_bbd_nu.json --out "$out/bbd_nu.csv" --report --quiet > "$out/bbd_nu.md"

cat "$out/screening_L64.md"
echo
echo "First runs of the screening plan (natural units):"
head -4 "$out/screening_L64.csv" | cut -d, -f1-14
echo
echo "Outputs in $out/:"
for f in screening_L64.csv screening_L64.h5 screening_L64.md ccd_sigma_u.csv ccd_sigma_u.md bbd_E.csv bbd_E.md bbd_nu.csv bbd_nu.md; do
  echo "  $out/$f"
done

echo
echo "demcal demo: DEM, uniaxial compression of the parallel-bonded scene at its defaults (data/scenes/ucs_rock_pb.json)"
"$bin/demcal-dem" run --scene data/scenes/ucs_rock_pb.json --out "$out/ucs_default.json" --curve "$out/ucs_default_curve.csv" \
  --cache "$build/cache" --quiet
/usr/bin/python3 - "$out/ucs_default.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
m = r["macro"]
print("  %s: sigma_u %.2f MPa, E %.2f GPa, E50 %.2f GPa, nu %.3f, peak strain %.5f, cracks %d tension / %d shear"
      % (r["status"], m["sigma_u_MPa"], m["E_GPa"], m["E50_GPa"], m["nu"], m["peak_strain"], m["cracks_tension"], m["cracks_shear"]))
print("  %d disks, %d steps, %.1f s, %.1f M particle-steps/s" % (r["particles"], r["steps"], r["wall_s"], r["particle_steps_per_s"] / 1e6))
PY

echo
echo "demcal demo: DEM batch over the 13-run CCD of the bond strengths (resumable; rerun skips finished points)"
"$bin/demcal-dem" batch --scene data/scenes/ucs_rock_pb.json --design "$out/ccd_sigma_u.csv" --out "$out/ccd_sigma_u_responses.h5" \
  --csv "$out/ccd_sigma_u_responses.csv" --jobs "$(scripts/cpu_count.sh)" --cache "$build/cache"
/usr/bin/python3 - "$out/ccd_sigma_u_responses.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("  %4s %15s %13s %6s %12s %8s %6s" % ("run", "pb_sigma_c_MPa", "pb_tau_c_MPa", "status", "sigma_u_MPa", "E_GPa", "nu"))
for r in rows:
    print("  %4s %15.3f %13.3f %6s %12.2f %8.2f %6.3f" % (r["run"], float(r["pb_sigma_c_MPa"]), float(r["pb_tau_c_MPa"]),
          r["status"][:6], float(r["sigma_u_MPa"]), float(r["E_GPa"]), float(r["nu"])))
PY
echo
echo "Also in $out/: ucs_default.json, ucs_default_curve.csv, ccd_sigma_u_responses.h5 (+ .points/), ccd_sigma_u_responses.csv"

scripts/demo_analysis.sh "$build"
scripts/demo_inversion.sh "$build"

echo
echo "demcal demo: the whole chain on our DEM, data/studies/demo.json (design -> DEM -> surfaces -> inversion -> verification -> report)"
scripts/run_study.sh data/studies/demo.json "$build" "$(scripts/cpu_count.sh)" quiet
