#!/usr/bin/env bash
# The analysis and surrogate stage of `make demo`: range analysis and ANOVA of
# the published 64-run screening (Su et al. 2021), the published
# response-surface runs and our own DEM CCD fitted as quadratic surfaces, the
# GA-BP network on the published database of He et al. (2019), and the plots.
set -euo pipefail
build=${1:-build}
bin="$build/bin"
out="$build/demo/analysis"
lit=data/literature
plot="/usr/bin/python3 scripts/plot_analysis.py"
mkdir -p "$out"

l64_factors=Ec_GPa,kn_ks,pb_sigma_c_MPa,pb_tau_c_MPa,mu,Ec_g_GPa,kn_ks_g,mu_g,Ec_j_GPa,kn_ks_j,pb_sigma_c_j_MPa,pb_tau_c_j_MPa,mu_j,null_column
echo
echo "demcal demo: range analysis and ANOVA of the published L64 screening ($lit/su2021_L64_orthogonal.csv)"
for format in md json; do
  "$bin/demcal-analyze" range --data "$lit/su2021_L64_orthogonal.csv" --factors "$l64_factors" \
    --responses sigma_u_MPa,E_GPa,nu --format "$format" --out "$out/l64_range.$format"
  "$bin/demcal-analyze" anova --data "$lit/su2021_L64_orthogonal.csv" --factors "$l64_factors" \
    --responses sigma_u_MPa,E_GPa,nu --format "$format" --out "$out/l64_anova.$format"
done
$plot main-effects "$out/l64_range.json" --out "$out/main_effects.png" > /dev/null
$plot pareto "$out/l64_anova.json" --out "$out/pareto.png" > /dev/null
/usr/bin/python3 - "$out/l64_anova.json" <<'PY'
import json, sys
anova = json.load(open(sys.argv[1]))
for response, table in anova.items():
    marks = ["%s%s" % (name, row["significance"]) for name, row in sorted(table.items(), key=lambda kv: -(kv[1].get("F") or 0))
             if name != "error" and row.get("significance")]
    print("  %-12s significant (p < 0.05; ** p < 0.01): %s" % (response, ", ".join(marks)))
PY

echo
echo "demcal demo: quadratic response surfaces of the published CCD and Box-Behnken runs"
fit() {  # name data x y [options]
  local name=$1 data=$2 x=$3 y=$4
  shift 4
  "$bin/demcal-fit" quadratic --data "$data" --x "$x" --y "$y" --out "$out/$name.json" --report "$out/$name.md" \
    --residuals "$out/${name}_residuals.csv" --quiet "$@"
  $plot fit "$out/${name}_residuals.csv" --out "$out/${name}_fit.png" > /dev/null
  /usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print('  %-18s R^2 %.4f  adjusted %.4f  predicted %.4f' % (sys.argv[2], m['r2'], m['r2_adj'], m['r2_pred']))" \
    "$out/$name.json" "$name"
}
fit ccd_sigma_u "$lit/su2021_CCD2_sigma_u.csv" pb_sigma_c_MPa,pb_tau_c_MPa sigma_u_MPa --space data/spaces/su2021_ccd_sigma_u.json
fit bbd_E "$lit/su2021_BBD5_E.csv" Ec_GPa,kn_ks,mu,Ec_j_GPa,kn_ks_j E_GPa
fit bbd_nu "$lit/su2021_BBD4_nu.csv" Ec_GPa,kn_ks,mu,kn_ks_j nu
if [ -f "$build/demo/ccd_sigma_u_responses.csv" ]; then
  echo "  and the same CCD run through our DEM (failed points, if any, are left out with a warning):"
  fit our_dem_ccd_sigma_u "$build/demo/ccd_sigma_u_responses.csv" pb_sigma_c_MPa,pb_tau_c_MPa sigma_u_MPa \
    --space data/spaces/su2021_ccd_sigma_u.json
fi

echo
echo "demcal demo: GA-BP network on the published database ($lit/he2019_gabp_train.csv, 80 rows, 25 % held out)"
"$bin/demcal-fit" gabp --data "$lit/he2019_gabp_train.csv" --x e_pp,mu_pp,e_pw,mu_pw,surface_energy_as_printed \
  --y aor_deg --seed 1 --out "$out/gabp_aor.json" --report "$out/gabp_aor.md" --residuals "$out/gabp_aor_residuals.csv" --quiet
$plot fit "$out/gabp_aor_residuals.csv" --out "$out/gabp_aor_fit.png" > /dev/null
/usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print('  hidden %d (auto), validation R^2 %.4f' % (m['network']['hidden'], m['validation']['r2']['aor_deg']))" \
  "$out/gabp_aor.json"
"$bin/demcal-analyze" sobol --model "$out/bbd_E.json" --samples 4096 --out "$out/bbd_E_sobol.md"

echo
echo "Analysis outputs in $out/: l64_range.md/.json, l64_anova.md/.json, main_effects_*.png, pareto_*.png,"
echo "  <model>.json (saved models), <model>.md (Minitab-style tables), <model>_fit_*.png, bbd_E_sobol.md"
