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
echo "The DEM runs, analysis, surrogates, inversion and verification join this demo as those stages land."
