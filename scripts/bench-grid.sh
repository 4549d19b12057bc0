#!/usr/bin/env bash
# Runs `planlab bench grid` on the four Moving AI maps in tests/data in one go and
# prints each report plus the geometric means of the speed-ups.
# Usage: scripts/bench-grid.sh [DATA_DIR] [REPS]   (needs target/release/planlab)
set -euo pipefail
cd "$(dirname "$0")/.."
D="${1:-tests/data/movingai}"
REPS="${2:-3}"
[ -x target/release/planlab ] || cargo build --release -p planlab-cli
out=$(for m in dao/arena dao/arena2 maze/maze512-1-0 random/random512-10-0; do
  printf '{"map":"%s",' "$m"
  target/release/planlab bench grid "$D/$m.map" "$D/$m.map.scen" --reps "$REPS" | sed 's/^{//'
done)
echo "$out"
echo "$out" | python3 -c '
import json, math, sys
rows = [json.loads(l) for l in sys.stdin if l.strip()]
g = lambda k: math.exp(sum(math.log(r[k]) for r in rows) / len(rows))
print(json.dumps({"geomean_astar_speedup": round(g("astar_speedup"), 3),
                  "geomean_jps_speedup": round(g("jps_speedup"), 3)}))'
