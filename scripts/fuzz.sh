#!/usr/bin/env bash
# Runs the cargo fuzz targets of fuzz/ (libFuzzer, nightly) for SECONDS each
# (default 60), seeded with the same corpus as the stable mutation test
# (crates/planlab-core/tests/mutation.rs). Usage:
#   scripts/fuzz.sh [SECONDS] [TARGET...]
# Needs `cargo install cargo-fuzz` and a nightly toolchain (`cargo +nightly`);
# without nightly, RUSTC_BOOTSTRAP=1 lets stable build it (FUZZ_TOOLCHAIN=stable).
# Each target's executions and any crash input (fuzz/artifacts/) are printed.
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${1:-60}"
shift || true
toolchain="${FUZZ_TOOLCHAIN:-nightly}"
seeds=fuzz/corpus
PLANLAB_WRITE_SEEDS="$PWD/$seeds" PLANLAB_MUTATION_ITERS=0 \
  cargo test -q -p planlab-core --test mutation >/dev/null
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets < <(cd fuzz && cargo +"$toolchain" fuzz list)
fi
for t in "${targets[@]}"; do
  log="fuzz/artifacts/$t.log"
  mkdir -p fuzz/artifacts
  if [ "$toolchain" = stable ]; then export RUSTC_BOOTSTRAP=1; fi
  (cd fuzz && cargo +"$toolchain" fuzz run -O "$t" "corpus/$t" -- \
     -max_total_time="$secs" -rss_limit_mb=4096 -timeout=10 -print_final_stats=1) \
     >"$log" 2>&1 || { echo "$t: FAILED, see $log"; tail -30 "$log"; exit 1; }
  echo "$t: $(grep -m1 stat::number_of_executed_units "$log" | awk '{print $2}') executions in ${secs} s"
done
