#!/usr/bin/env bash
# `make bench`: timings of the stages that exist so far, with the machine they
# ran on. The DEM benchmark (particle-steps per second) joins with the engine.
set -euo pipefail
build=${1:-build}
bin="$build/bin"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
time_it() {
  local label=$1; shift
  local start end
  start=$(date +%s%N)
  "$@" > /dev/null
  end=$(date +%s%N)
  awk -v l="$label" -v ns=$((end - start)) 'BEGIN { printf "%-58s %8.3f s\n", l, ns / 1e9 }'
}
time_it "doe: L64 (3^14) collapsed plan + report" \
  "$bin/demcal-doe" oa --runs 64 --levels 3 --factors 14 --out "$tmp/l64.csv" --report --quiet
time_it "doe: LHS 100 x 13, phi_p optimised (ESE)" \
  "$bin/demcal-doe" lhs --runs 100 --factors 13 --criterion phip --out "$tmp/lhs.csv" --quiet
time_it "doe: LHS 500 x 13, phi_p optimised (ESE)" \
  "$bin/demcal-doe" lhs --runs 500 --factors 13 --criterion phip --out "$tmp/lhs500.csv" --quiet
time_it "doe: scrambled Sobol 4096 x 13" \
  "$bin/demcal-doe" sobol --runs 4096 --factors 13 --out "$tmp/sobol.csv" --quiet
