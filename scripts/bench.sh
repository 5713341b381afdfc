#!/usr/bin/env bash
# `make bench`: timings of the stages, with the machine they ran on: designs,
# the DEM hot path (particle-steps per second), batches (processes and MPI
# ranks) and the inversion algorithms.
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

# The DEM hot path: the parallel-bonded UCS at two sizes, on one thread and on
# every core (--threads 0). Packing is cached (build/cache); its time is
# reported apart from the loading.
dem_bench() {
  local label=$1 scene=$2 threads=$3
  "$bin/demcal-dem" run --scene "$scene" --out "$tmp/dem.json" --cache "$build/cache" --threads "$threads" --quiet
  /usr/bin/python3 - "$tmp/dem.json" "$label" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
m = r["macro"]
print("%-40s %6d disks %8d steps  %d thread(s)  loading %6.2f s  total %6.2f s  %5.2f M particle-steps/s  (sigma_u %.1f MPa, E %.1f GPa, nu %.3f)"
      % (sys.argv[2], r["particles"], r["steps"], r.get("threads", 1), r["test_wall_s"], r["wall_s"],
         r["particle_steps_per_s"] / 1e6, m.get("sigma_u_MPa", float("nan")), m.get("E_GPa", float("nan")),
         m.get("nu", float("nan"))))
PY
}
for threads in 1 0; do
  dem_bench "dem: UCS parallel bond, 25 x 50 mm" data/scenes/ucs_rock_pb.json "$threads"
  dem_bench "dem: UCS parallel bond, 50 x 100 mm" data/scenes/bench/ucs_pb_9k.json "$threads"
done

# The same specimens against LAMMPS (installed on demand), same contact law and steps.
echo
/usr/bin/python3 scripts/bench_lammps.py --build "$build"
# The 3D engine against LAMMPS (3D granular Hooke with history), and its cost against the sphere count.
echo
/usr/bin/python3 scripts/bench_lammps_3d.py --build "$build"
# And YADE's CPM concrete in compression (another model, 3D): per particle-step only.
echo
/usr/bin/python3 scripts/bench_yade.py --build "$build"
# LIGGGHTS (installed on demand) on the rotating drum both codes run the same way: angles and cost, one seed each.
echo
/usr/bin/python3 scripts/liggghts_peer.py --build "$build" --seeds 1 --out "$tmp/liggghts_peer"

# Batches: the same 16 design points one at a time, two processes at once, and
# over MPI ranks (rank 0 hands out, 2 worker ranks run); specimens cached first.
echo
printf 'run,pb_sigma_c_MPa\n' > "$tmp/batch_design.csv"
for r in $(seq 1 16); do printf '%d,%d\n' "$r" $((10 + r)) >> "$tmp/batch_design.csv"; done
"$bin/demcal-dem" batch --scene data/scenes/ucs_rock_pb.json --design "$tmp/batch_design.csv" --out "$tmp/warm.h5" \
  --seeds 1 --jobs 2 --cache "$build/cache" --quiet > /dev/null 2>&1 || true
batch_args=(batch --scene data/scenes/ucs_rock_pb.json --design "$tmp/batch_design.csv" --cache "$build/cache" --quiet)
time_it "dem batch: 16 points of the 25 x 50 mm UCS, --jobs 1 (2 threads each)" "$bin/demcal-dem" "${batch_args[@]}" --out "$tmp/b1.h5" --jobs 1
time_it "dem batch: the same, --jobs 2 (1 thread each)" "$bin/demcal-dem" "${batch_args[@]}" --out "$tmp/b2.h5" --jobs 2
if command -v mpirun > /dev/null; then
  time_it "dem batch: the same, mpirun -np 3 (2 worker ranks)" \
    mpirun -np 3 --oversubscribe --allow-run-as-root "$bin/demcal-dem" "${batch_args[@]}" --out "$tmp/b3.h5"
fi

# The inversion stage: five algorithms x 20 seeds on one problem (medians).
echo
echo "inversion: GA, SA, WCA, LHS-WCA and search, 20 seeds each, 20,000 evaluations, C30 target on the published surfaces"
scripts/inversion_comparison.sh "$build" "$build/inversion_comparison" | grep -v '^build/'
