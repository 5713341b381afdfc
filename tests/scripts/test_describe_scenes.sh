#!/usr/bin/env bash
# demcal-dem describe works on every shipped scene (the external templates too), names a test, its parameters with units and its outputs.
set -euo pipefail
bin=$1
cd "$2"
count=0
for scene in $(find data/scenes data/external tests/data -name '*.json' | sort); do
  case "$(basename "$scene")" in study_*|space_*) continue ;; esac
  out=$("$bin/demcal-dem" describe --scene "$scene") || { echo "FAIL: describe $scene"; exit 1; }
  /usr/bin/python3 -c "
import json, sys
d = json.loads(sys.argv[2])
assert d['test'] and d['outputs'] and d['parameters'], sys.argv[1]
assert all(p['unit'] and p['low'] <= p['value'] <= p['high'] for p in d['parameters'].values()), sys.argv[1]
" "$scene" "$out"
  count=$((count + 1))
done
[ "$count" -ge 10 ] || { echo "FAIL: only $count scenes found"; exit 1; }
echo "describe: $count scenes"
