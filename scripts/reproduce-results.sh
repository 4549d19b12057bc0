#!/usr/bin/env bash
# Regenerates assets/reproduce-results.jsonl, the family results that the
# gallery cards show (verdict, success rates, effects, deviations): one JSON
# line per experiment from `planlab reproduce --variants 60 --seed 0 --json`.
# Rerun it whenever a planner or the reproduce registry changes; the test
# crates/planlab-core/tests/gallery.rs fails while the file is stale (ids,
# relation or family differ from the registry's).
# VARIANTS and SEED override the family size (60: enough that the verdict
# rule's Wilson bound decides shares near 80 %; about 10 min on 2 cores)
# and seed.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p planlab-cli
out=assets/reproduce-results.jsonl
./target/release/planlab reproduce --variants "${VARIANTS:-60}" --seed "${SEED:-0}" --json >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out ($(wc -l <"$out") experiments)"
