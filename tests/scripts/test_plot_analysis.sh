#!/usr/bin/env bash
# The plot script on real outputs of demcal-analyze and demcal-fit: every
# sub-command writes a non-empty PNG, and a missing input is one error line
# with exit code 2.
set -euo pipefail
bin=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lit="$src/data/literature"
plot="/usr/bin/python3 $src/scripts/plot_analysis.py"
factors=Ec_GPa,kn_ks,pb_sigma_c_MPa,pb_tau_c_MPa,mu,Ec_g_GPa,kn_ks_g,mu_g,Ec_j_GPa,kn_ks_j,pb_sigma_c_j_MPa,pb_tau_c_j_MPa,mu_j,null_column

"$bin/demcal-analyze" range --data "$lit/su2021_L64_orthogonal.csv" --factors "$factors" --responses nu --format json --out "$work/range.json"
"$bin/demcal-analyze" anova --data "$lit/su2021_L64_orthogonal.csv" --factors "$factors" --responses nu,E_GPa --format json --out "$work/anova.json"
"$bin/demcal-fit" quadratic --data "$lit/su2021_BBD4_nu.csv" --x Ec_GPa,kn_ks,mu,kn_ks_j --y nu --out "$work/nu.json" --residuals "$work/res.csv" --quiet
$plot main-effects "$work/range.json" --out "$work/main.png"
$plot pareto "$work/anova.json" --out "$work/pareto.png"
$plot fit "$work/res.csv" --out "$work/fit.png"
for f in main.png pareto_nu.png pareto_E_GPa.png fit.png; do
  [ -s "$work/$f" ] || { echo "FAIL: $f not written"; exit 1; }
  head -c 8 "$work/$f" | grep -q PNG || { echo "FAIL: $f is not a PNG"; exit 1; }
done
set +e
err=$($plot pareto "$work/missing.json" --out "$work/x.png" 2>&1 >/dev/null)
code=$?
set -e
[ "$code" -eq 2 ] || { echo "FAIL: missing input exit code $code, expected 2"; exit 1; }
[ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: expected one error line, got: $err"; exit 1; }
echo "plot_analysis.py: 4 PNGs written, missing input rejected"
