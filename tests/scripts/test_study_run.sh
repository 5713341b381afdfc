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
echo "study: the CCD points in DEM, a model, a solution, a verification and a report; a second make does nothing"
