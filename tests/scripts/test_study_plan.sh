#!/usr/bin/env bash
# Study files: a valid study plans into file-target stages; a change to one
# part rewrites only that stage's config; bad studies stop with one line
# naming the field.
set -euo pipefail
export BIN=$1  # the study layer asks the executables about scenes, designs and algorithms
src=$2
cd "$src"
export PYTHONPATH=python  # the study layer: python/demcal_study
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
study="/usr/bin/python3 -m demcal_study"

$study plan data/studies/demo.json "$work/demo" > /dev/null
for f in plan.mk config/design_g1.json config/space_g1.json config/inversion.json config/verification.json; do
  [ -s "$work/demo/$f" ] || { echo "FAIL: $f not written"; exit 1; }
done
grep -q '^\$(D)/solution.json:' "$work/demo/plan.mk" || { echo "FAIL: no solution stage"; exit 1; }

# Changing the targets touches the inversion config, not the design's.
design_before=$(stat -c %Y "$work/demo/config/design_g1.json")
sleep 1
sed 's/"sigma_u_MPa": 25/"sigma_u_MPa": 24/' data/studies/demo.json > "$work/changed.json"
$study plan "$work/changed.json" "$work/demo" > /dev/null
[ "$(stat -c %Y "$work/demo/config/design_g1.json")" = "$design_before" ] || { echo "FAIL: design config rewritten"; exit 1; }
grep -q '"sigma_u_MPa": 24' "$work/demo/config/inversion.json" || { echo "FAIL: inversion config not updated"; exit 1; }

expect_error() {  # file fragment
  set +e
  err=$($study plan "$1" "$work/bad" 2>&1 >/dev/null)
  code=$?
  set -e
  [ "$code" -eq 2 ] || { echo "FAIL: $1: exit $code, expected 2"; exit 1; }
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || { echo "FAIL: more than one error line: $err"; exit 1; }
  printf '%s' "$err" | grep -q "$2" || { echo "FAIL: '$err' lacks '$2'"; exit 1; }
}
sed 's/"surrogate"/"surogate"/' data/studies/demo.json > "$work/typo.json"
expect_error "$work/typo.json" 'unknown field "surogate"'
/usr/bin/python3 -c "
import json
d = json.load(open('data/studies/demo.json'))
d['surfaces'][0]['factors'][-1] = 'kn_ks_x'
print(json.dumps(d))" > "$work/factor.json"
expect_error "$work/factor.json" 'factor kn_ks_x is not a parameter'
sed 's/"nu": 0.2/"density": 2400/' data/studies/demo.json > "$work/target.json"
expect_error "$work/target.json" 'targets.density: not a DEM output'
expect_error "$work/missing.json" 'cannot open study'

edit() {  # OUT SOURCE PYTHON: the study SOURCE edited by PYTHON (on d) into OUT
  /usr/bin/python3 -c "
import json
d = json.load(open('$2'))
$3
print(json.dumps(d))" > "$1"
}
edit "$work/auto.json" data/studies/demo.json "d['surfaces'][0]['factors'] = 'auto'"
expect_error "$work/auto.json" 'add a "screening" stage'
edit "$work/loop_surfaces.json" data/studies/rock_dem_in_the_loop.json "d['surfaces'] = []"
expect_error "$work/loop_surfaces.json" '"surfaces" does not apply to strategy dem_in_the_loop'
edit "$work/loop_polish.json" data/studies/rock_dem_in_the_loop.json "d['inversion']['polish'] = True"
expect_error "$work/loop_polish.json" 'polish needs a smooth surrogate'
edit "$work/screen_kind.json" data/studies/rock_response_surface.json "d['screening']['design']['kind'] = 'lhs'"
expect_error "$work/screen_kind.json" 'screening: design.kind must be "oa"'
edit "$work/strategy.json" data/studies/demo.json "d['strategy'] = 'dem-in-loop'"
expect_error "$work/strategy.json" 'strategy must be one of'

# A study whose factors come from its screening plans the screening first, then plans again.
/usr/bin/python3 -m demcal_study plan data/studies/rock_response_surface.json "$work/rrs" > /dev/null
grep -q '^\$(D)/screening/anova.json:' "$work/rrs/plan.mk" || { echo "FAIL: no screening stage"; exit 1; }
grep -q 'demcal_study plan data/studies/rock_response_surface.json' "$work/rrs/plan.mk" || { echo "FAIL: no re-plan after the screening"; exit 1; }
echo "study plan: stages written, a target change leaves the design alone, 9 bad studies rejected, auto factors re-plan"
