#!/usr/bin/env bash
# Runs one study file into BUILD/studies/NAME (plan, then make on its plan) and
# keeps the wall time of every invocation that changed its report in
# make_wall_s.csv, so the report can state the study's time over resumed runs.
#   scripts/run_study.sh STUDY.json BUILD JOBS [make output filter: quiet]
set -euo pipefail
study=$1
build=$2
jobs=$3
filter=${4:-}
name=$(basename "$study" .json)
# The study layer is the package python/demcal_study.
export PYTHONPATH=python${PYTHONPATH:+:$PYTHONPATH}
dir="$build/studies/$name"
BIN="$build/bin" /usr/bin/python3 -m demcal_study plan "$study" "$dir" > /dev/null
report="$dir/report.md"
before=$(stat -c %Y "$report" 2>/dev/null || echo none)
start=$(date +%s.%N)
if [ "$filter" = quiet ]; then
  set +e
  make --no-print-directory -f "$dir/plan.mk" BIN="$build/bin" CACHE="$build/cache" JOBS="$jobs" all 2>&1 \
    | grep -v '^build/bin/\|^/usr/bin/python3 \|^mv \|^\$'
  code=${PIPESTATUS[0]}
  set -e
  [ "$code" -eq 0 ] || { echo "$name: the study stopped (make exit $code); run it again to resume" >&2; exit 1; }
else
  make --no-print-directory -f "$dir/plan.mk" BIN="$build/bin" CACHE="$build/cache" JOBS="$jobs" all
fi
after=$(stat -c %Y "$report" 2>/dev/null || echo none)
if [ "$before" != "$after" ]; then
  [ -f "$dir/make_wall_s.csv" ] || echo "finished,wall_s,jobs" > "$dir/make_wall_s.csv"
  echo "$(date -Iseconds),$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN{printf "%.1f", e - s}'),$jobs" >> "$dir/make_wall_s.csv"
  # The report states the time: write it again now that this run's time is known.
  BIN="$build/bin" /usr/bin/python3 -m demcal_study report "$dir" > /dev/null
fi
echo "report: $dir/report.md and report.html"
