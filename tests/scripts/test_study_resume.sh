#!/usr/bin/env bash
# Killing `make` on a study halfway (SIGKILL to the whole process group, as a
# crash or a cancelled job does) and running it again repeats no finished DEM
# point: every point file written before the kill is still the same file.
set -euo pipefail
bin=$1
export BIN=$bin  # the study layer asks the executables about scenes, designs and algorithms
src=$2
cd "$src"
export PYTHONPATH=python  # the study layer: python/demcal_study
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The small study with 4 seeds per point: 40 DEM points in its design batch.
/usr/bin/python3 -c "
import json, sys
d = json.load(open('tests/data/study_small.json'))
d['seeds_per_point'] = 4
for key in ('stability', 'compare_with'):
    d.pop(key)
print(json.dumps(d))" > "$work/study_resume.json"
/usr/bin/python3 -m demcal_study plan "$work/study_resume.json" "$work/s" > /dev/null
points="$work/s/g1/responses.h5.points"

setsid make --no-print-directory -f "$work/s/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/first.log" 2>&1 &
pid=$!
for _ in $(seq 1 6000); do
  n=$( (ls "$points" 2>/dev/null || true) | grep -c '\.json$' || true)
  [ "$n" -ge 8 ] && break
  sleep 0.01
done
kill -9 -- "-$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
sleep 0.2
before=$(cd "$points" && ls | grep '\.json$' | sort)
count=$(printf '%s\n' "$before" | wc -l)
[ "$count" -ge 8 ] || { echo "FAIL: only $count points before the kill"; exit 1; }
[ "$count" -lt 40 ] || { echo "FAIL: the batch finished before it could be killed"; exit 1; }
[ ! -f "$work/s/report.md" ] || { echo "FAIL: the study finished before it could be killed"; exit 1; }
(cd "$points" && stat -c '%n %Y.%y %s' $before | sort) > "$work/before.txt"
(cd "$points" && md5sum $before) > "$work/before.md5"

make --no-print-directory -f "$work/s/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/second.log" 2>&1 \
  || { cat "$work/second.log"; echo "FAIL: the rerun did not finish"; exit 1; }
[ -s "$work/s/report.md" ] || { echo "FAIL: no report after the rerun"; exit 1; }
after_count=$(ls "$points" | grep -c '\.json$' || true)
[ "$after_count" -eq 40 ] || { echo "FAIL: $after_count points after the rerun, not 40"; exit 1; }
(cd "$points" && stat -c '%n %Y.%y %s' $before | sort) > "$work/after.txt"
diff -q "$work/before.txt" "$work/after.txt" > /dev/null || { echo "FAIL: finished points were written again"; diff "$work/before.txt" "$work/after.txt"; exit 1; }
(cd "$points" && md5sum -c --quiet "$work/before.md5") || { echo "FAIL: finished points changed"; exit 1; }
grep -q "resuming: $count of 40 points already done" "$work/second.log" || { echo "FAIL: the rerun did not say it resumed $count points"; cat "$work/second.log"; exit 1; }
echo "study killed after $count of 40 DEM points; the rerun kept all $count and ran the other $((40 - count))"
