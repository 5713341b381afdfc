#!/usr/bin/env bash
# The whole chain on a small study: plan, make (design -> DEM -> model ->
# solution -> verification -> refinement -> report), then make again: nothing
# reruns, and the report is there.
set -euo pipefail
bin=$1
src=$2
cd "$src"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 scripts/study.py plan tests/data/study_small.json "$work/study" > /dev/null
make --no-print-directory -f "$work/study/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/first.log" 2>&1 \
  || { cat "$work/first.log"; echo "FAIL: the study did not run"; exit 1; }
for f in g1/design.csv g1/responses.csv models/sigma_u_MPa.json solution.json verification.json refined.json report.md report.html; do
  [ -s "$work/study/$f" ] || { echo "FAIL: $f missing"; exit 1; }
done
grep -q "Verification in DEM" "$work/study/report.md" || { echo "FAIL: report without verification"; exit 1; }
grep -q "data:image/png;base64" "$work/study/report.html" || { echo "FAIL: report.html without inlined figures"; exit 1; }
/usr/bin/python3 -c "
import json, sys
v = json.load(open(sys.argv[1]))
assert v['outputs']['sigma_u_MPa']['runs'] == 2, v
" "$work/study/verification.json"
second=$(make --no-print-directory -f "$work/study/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all 2>&1)
[ -z "$(printf '%s' "$second" | grep -v 'Nothing to be done\|is up to date')" ] || { echo "FAIL: make reran: $second"; exit 1; }

# DEM in the loop: the annealing drives the DEM; the report counts its runs.
/usr/bin/python3 scripts/study.py plan tests/data/study_small_loop.json "$work/loop" > /dev/null
make --no-print-directory -f "$work/loop/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/loop.log" 2>&1 \
  || { cat "$work/loop.log"; echo "FAIL: the DEM-in-the-loop study did not run"; exit 1; }
runs=$(/usr/bin/python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
assert s['status'] == 'ok' and s['max_relative_error'] <= 0.10, s
print(s['dem']['runs'])
" "$work/loop/solution.json")
grep -q "\*\*$runs DEM runs\*\*" "$work/loop/report.md" || { echo "FAIL: report does not count the $runs DEM runs"; exit 1; }
[ -s "$work/loop/convergence.png" ] || { echo "FAIL: no convergence plot"; exit 1; }
# Screening first, factors chosen from its ANOVA, an LHS and GA-BP networks.
/usr/bin/python3 scripts/study.py plan tests/data/study_small_screening.json "$work/screen" > /dev/null
make --no-print-directory -f "$work/screen/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/screen.log" 2>&1 \
  || { cat "$work/screen.log"; echo "FAIL: the screening study did not run"; exit 1; }
/usr/bin/python3 -c "
import json, sys
chosen = json.load(open(sys.argv[1]))['g1']
# pb_sigma_c_MPa drives sigma_u and Ec_GPa drives E on this specimen; pb_tau_c_MPa and mu drive neither.
assert 'pb_sigma_c_MPa' in chosen['factors'] and 'Ec_GPa' in chosen['factors'], chosen
assert 'mu' not in chosen['factors'] and len(chosen['factors']) <= 3, chosen
assert all(chosen['p'][f] < 0.05 for f in chosen['factors']), chosen
m = json.load(open(sys.argv[2]))
assert m['kind'] == 'gabp', m['kind']
" "$work/screen/config/factors.json" "$work/screen/models/sigma_u_MPa.json"
for f in screening/anova.json screening/range.md screening/pareto_sigma_u_MPa.png g1/design.csv report.html; do
  [ -s "$work/screen/$f" ] || { echo "FAIL: screening study: $f missing"; exit 1; }
done
grep -q "Factors kept for the response surfaces" "$work/screen/report.md" || { echo "FAIL: report without the chosen factors"; exit 1; }
second=$(make --no-print-directory -f "$work/screen/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all 2>&1)
[ -z "$(printf '%s' "$second" | grep -v 'Nothing to be done\|is up to date')" ] || { echo "FAIL: make reran the screening study: $second"; exit 1; }

echo "study: the CCD points in DEM, a model, a solution, a verification and a report; a second make does nothing;"
echo "DEM in the loop: $runs DEM runs to within 10 %, verified and reported;"
echo "screening: factors chosen from its ANOVA, LHS + GA-BP surfaces, reported"
