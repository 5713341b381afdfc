#!/usr/bin/env bash
# The whole chain on three small studies: DEM in the loop; a screening whose
# ANOVA chooses the factors of an LHS with GA-BP networks; and a CCD with a
# quadratic surface, refinement, the stability checks and the speed-versus-
# accuracy comparison with the other two. Each runs plan + make; a second
# make does nothing.
set -euo pipefail
bin=$1
export BIN=$bin  # the study layer asks the executables about scenes, designs and algorithms
src=$2
cd "$src"
export PYTHONPATH=python  # the study layer: python/demcal_study
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run_study() {  # NAME: plan and make tests/data/NAME.json into $work/NAME
  /usr/bin/python3 -m demcal_study plan "tests/data/$1.json" "$work/$1" > /dev/null
  make --no-print-directory -f "$work/$1/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/$1.log" 2>&1 \
    || { cat "$work/$1.log"; echo "FAIL: study $1 did not run"; exit 1; }
}
nothing_reruns() {  # NAME
  local second
  second=$(make --no-print-directory -f "$work/$1/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all 2>&1) \
    || { echo "FAIL: the second make of $1 failed: $second"; exit 1; }
  [ -z "$(printf '%s' "$second" | grep -v 'Nothing to be done\|is up to date')" ] || { echo "FAIL: make reran $1: $second"; exit 1; }
}

# DEM in the loop: the annealing drives the DEM; the report counts its runs.
run_study study_small_loop
runs=$(/usr/bin/python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
assert s['status'] == 'ok' and s['max_relative_error'] <= 0.10, s
print(s['dem']['runs'])
" "$work/study_small_loop/solution.json")
grep -q "\*\*$runs DEM runs\*\*" "$work/study_small_loop/report.md" || { echo "FAIL: report does not count the $runs DEM runs"; exit 1; }
[ -s "$work/study_small_loop/convergence.png" ] || { echo "FAIL: no convergence plot"; exit 1; }

# Screening first, factors chosen from its ANOVA, an LHS and GA-BP networks.
run_study study_small_screening
/usr/bin/python3 -c "
import json, sys
chosen = json.load(open(sys.argv[1]))['g1']
# pb_sigma_c_MPa drives sigma_u and Ec_GPa drives E on this specimen; pb_tau_c_MPa and mu drive neither.
assert 'pb_sigma_c_MPa' in chosen['factors'] and 'Ec_GPa' in chosen['factors'], chosen
assert 'mu' not in chosen['factors'] and len(chosen['factors']) <= 3, chosen
assert all(chosen['p'][f] < 0.05 for f in chosen['factors']), chosen
m = json.load(open(sys.argv[2]))
assert m['kind'] == 'gabp', m['kind']
" "$work/study_small_screening/config/factors.json" "$work/study_small_screening/models/sigma_u_MPa.json"
for f in screening/anova.json screening/range.md screening/pareto_sigma_u_MPa.png g1/design.csv report.html; do
  [ -s "$work/study_small_screening/$f" ] || { echo "FAIL: screening study: $f missing"; exit 1; }
done
grep -q "Factors kept for the response surfaces" "$work/study_small_screening/report.md" || { echo "FAIL: report without the chosen factors"; exit 1; }
nothing_reruns study_small_screening

# A CCD, a quadratic surface, refinement, stability checks, the comparison.
run_study study_small
for f in g1/design.csv g1/responses.csv models/sigma_u_MPa.json solution.json verification.json refined.json \
         stability.json report.md report.html speed_accuracy.png; do
  [ -s "$work/study_small/$f" ] || { echo "FAIL: $f missing"; exit 1; }
done
grep -q "Verification in DEM" "$work/study_small/report.md" || { echo "FAIL: report without verification"; exit 1; }
grep -q "data:image/png;base64" "$work/study_small/report.html" || { echo "FAIL: report.html without inlined figures"; exit 1; }
/usr/bin/python3 -c "
import json, sys
v = json.load(open(sys.argv[1]))
assert v['outputs']['sigma_u_MPa']['runs'] == 2, v
st = json.load(open(sys.argv[2]))
assert len(st['seeds']) == 2 and st['edge']['fraction'] == 0.98, st
# Too few runs for a quadratic: the fit refuses and says why.
assert 'needs at least' in st['small_design'][0]['message'], st['small_design'][0]
" "$work/study_small/verification.json" "$work/study_small/stability.json"
rows=$(grep -c '^| study_small' "$work/study_small/report.md" || true)
[ "$rows" -eq 3 ] || { echo "FAIL: the comparison has $rows studies, not 3"; exit 1; }
nothing_reruns study_small
echo "studies: DEM in the loop ($runs DEM runs to within 10 %), screening -> chosen factors -> LHS + GA-BP,"
echo "CCD + quadratic + refinement + stability + comparison of the three; second makes do nothing"
