#!/usr/bin/env bash
# An external command through the whole chain, with the stand-in simulator of
# tests/external: a batch whose failed points (a reported failure, a hang past
# its timeout, a non-zero exit) are recorded with their reasons while the batch
# goes on; a rerun that repeats nothing; a batch killed halfway that resumes
# without touching finished points; demcal-verify over seeds; and a small study
# (design, surface, inversion, verification, report) on it.
set -euo pipefail
bin=$1
src=$2
cd "$src"
export BIN=$bin PYTHONPATH=python
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# The shipped scene with a 2 s timeout, its driver named by absolute path.
/usr/bin/python3 - "$src" "$work/quick.json" <<'PY'
import json, sys
src, out = sys.argv[1:3]
scene = json.load(open(f"{src}/tests/data/external_fake.json"))
scene["timeout_s"] = 2
scene["inputs"] = [f"{src}/tests/external/fake_simulator.py"]
json.dump(scene, open(out, "w"))
PY
printf 'run,a_MPa,b_MPa,mode\n1,1,1,0\n2,2,1,0\n3,1,2,1\n4,3,3,2\n5,2,2,5\n6,4,1,7\n' > "$work/design.csv"

# 1. Six rows x 2 seeds; three rows fail, each for its own reason, and the batch goes on (exit 4).
set +e
"$bin/demcal-dem" batch --scene "$work/quick.json" --design "$work/design.csv" --seeds 2 --jobs 2 \
  --out "$work/r.h5" --csv "$work/r.csv" --quiet
code=$?
set -e
[ "$code" -eq 4 ] || fail "batch exit $code, not 4 (some points failed)"
/usr/bin/python3 - "$work/r.csv" "$work/r.h5.points" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 12, len(rows)
for r in rows:
    run, seed = int(r["run"]), int(r["seed"])
    reason = json.load(open(f"{sys.argv[2]}/run{run}_seed{seed}.json"))["reason"]
    if run in (1, 2, 6):
        assert r["status"] == "ok", (run, reason)
        y = 2 * float(r["a_MPa"]) + 3 * float(r["b_MPa"]) + 0.01 * (seed % 5)
        assert float(r["y_MPa"]) == y, (r["y_MPa"], y)
    else:
        expected = {3: "the command reported failure: the specimen collapsed under gravity",
                    4: "timed out after 2 s", 5: "exited with status 3; stderr: bad things happened"}[run]
        assert r["status"] == "failed: " + reason and expected in reason, (run, r["status"])
print("batch: 6 points ok with the closed-form response, 6 failed with their reasons")
PY
# The command's litter stayed in its own folder; the stored results are demcal's.
[ -f "$work/r.h5.points/run6_seed1/run1_seed1.json" ] || fail "the littering point's folder lacks its litter"
grep -q '"status":"ok"' "$work/r.h5.points/run1_seed1.json" || fail "a stored result was overwritten"

# 2. A rerun repeats nothing but the two points stopped by the wall-clock limit (the machine's load, not the point,
# decides those): no finished point's command runs again.
stamp=$(stat -c %Y.%y "$work/r.h5.points/run1_seed1/stdout.txt")
set +e
"$bin/demcal-dem" batch --scene "$work/quick.json" --design "$work/design.csv" --seeds 2 --jobs 2 \
  --out "$work/r.h5" --csv "$work/r.csv" > "$work/rerun.log" 2>&1
set -e
grep -q "resuming: 10 of 12 points already done" "$work/rerun.log" || { cat "$work/rerun.log"; fail "the rerun did not resume"; }
grep -q "2 stored point(s) failed at a wall-clock limit" "$work/rerun.log" || { cat "$work/rerun.log"; fail "the timed-out points were not run again"; }
[ "$(stat -c %Y.%y "$work/r.h5.points/run1_seed1/stdout.txt")" = "$stamp" ] || fail "the rerun ran a command again"

# 3. Killed halfway (each point takes a second), rerun: finished points are kept as they were.
printf 'run,a_MPa,b_MPa,mode\n' > "$work/slow.csv"
for k in 1 2 3 4 5 6 7 8; do printf '%d,%d,1,8\n' "$k" "$k" >> "$work/slow.csv"; done
setsid "$bin/demcal-dem" batch --scene "$work/quick.json" --design "$work/slow.csv" --jobs 2 --out "$work/s.h5" \
  --csv "$work/s.csv" --quiet &
pid=$!
for _ in $(seq 1 3000); do
  n=$( (ls "$work/s.h5.points" 2>/dev/null || true) | grep -c '\.json$' || true)
  [ "$n" -ge 2 ] && break
  sleep 0.01
done
kill -9 -- "-$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
before=$(cd "$work/s.h5.points" && ls | grep '\.json$' | sort)
count=$(printf '%s\n' "$before" | wc -l)
[ "$count" -ge 2 ] && [ "$count" -lt 8 ] || fail "$count points before the kill (want 2-7)"
(cd "$work/s.h5.points" && md5sum $before) > "$work/before.md5"
"$bin/demcal-dem" batch --scene "$work/quick.json" --design "$work/slow.csv" --jobs 2 --out "$work/s.h5" \
  --csv "$work/s.csv" > "$work/resume.log" 2>&1 || { cat "$work/resume.log"; fail "the resumed batch failed"; }
grep -q "resuming: $count of 8 points already done" "$work/resume.log" || { cat "$work/resume.log"; fail "no resume"; }
(cd "$work/s.h5.points" && md5sum -c --quiet "$work/before.md5") || fail "finished points changed"
[ "$(grep -c ',ok,' "$work/s.csv")" -eq 8 ] || fail "not every point of the resumed batch is ok"

# 4. demcal-verify over seeds: y's mean is the closed form's over seeds 1-4.
printf '{"status": "ok", "x": {"a_MPa": 2, "b_MPa": 1}, "targets": {"y_MPa": 7.02}}\n' > "$work/solution.json"
"$bin/demcal-verify" --solution "$work/solution.json" --scene "$work/quick.json" --seeds 4 --max-seeds 4 \
  --out "$work/verify.json" --quiet
/usr/bin/python3 - "$work/verify.json" <<'PY'
import json, sys
v = json.load(open(sys.argv[1]))
row = [r for r in v["outputs"] if r["output"] == "y_MPa"][0] if isinstance(v["outputs"], list) else v["outputs"]["y_MPa"]
mean = sum(7 + 0.01 * (s % 5) for s in range(1, 5)) / 4
assert abs(row["mean"] - mean) < 1e-12, (row["mean"], mean)
print(f"verify: y_MPa mean {row['mean']} over 4 seeds (closed form {mean})")
PY

# 5. A small study: a CCD over a and b, a quadratic surface of y, GA inversion, verification, report.
/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
json.dump({"name": "external_small", "scene": f"{work}/quick.json", "space": f"{work}/space.json",
           "targets": {"y_MPa": 9.5}, "fixed": "reference",
           "surfaces": [{"outputs": ["y_MPa"], "factors": ["a_MPa", "b_MPa"], "design": {"kind": "ccd", "center": 1}}],
           "surrogate": "quadratic", "inversion": {"algorithm": "ga", "objective": "sum-rel", "restarts": 2, "seed": 1},
           "verification": {"seeds": 2, "max_seeds": 2, "tolerance": 0.05}, "refinement": {"rounds": 0}},
          open(f"{work}/study.json", "w"))
json.dump({"parameters": [{"name": "a_MPa", "low": 0.6, "high": 3, "unit": "MPa"},
                          {"name": "b_MPa", "low": 0.6, "high": 3, "unit": "MPa"}], "fixed": {"mode": 0}},
          open(f"{work}/space.json", "w"))
PY
/usr/bin/python3 -m demcal_study plan "$work/study.json" "$work/study" > /dev/null
make --no-print-directory -f "$work/study/plan.mk" BIN="$bin" CACHE="$work/cache" JOBS=2 all > "$work/study.log" 2>&1 \
  || { cat "$work/study.log"; fail "the study failed"; }
[ -s "$work/study/report.md" ] || fail "no study report"
/usr/bin/python3 - "$work/study/verification.json" <<'PY'
import json, sys
v = json.load(open(sys.argv[1]))
rows = v["outputs"] if isinstance(v["outputs"], dict) else {r["output"]: r for r in v["outputs"]}
err = rows["y_MPa"]["relative_error_pct"]
assert abs(err) < 5, err  # y is linear in a and b: the quadratic surface is exact up to the seed term
print(f"study: verified y_MPa within {err:+.2f} % of its target")
PY
echo "external: batch with failures, rerun, kill and resume, verify and a study all ran on the stand-in simulator"
