#!/usr/bin/env bash
# Builds the two wasm packages of the site (release):
#  - web/pkg:     planlab-wasm with feature robot (episodes, APF, DWA
#                 bench: the robot, compare, gallery and APF pages),
#  - web/pkg-grid: planlab-wasm with feature grid-search (maps, plans,
#                 recorded searches, D* Lite sessions: the grid, race and
#                 bench pages; the bench page loads web/pkg too, lazily,
#                 for its DWA step),
#  - web/pkg-arm: planlab-wasm-arm, the arm page's own small module (the arm
#                 page also loads three.js; one module with everything would
#                 not fit its 1.5 MB first-load budget),
#  - web/pkg-reproduce: planlab-wasm-reproduce, the reproduce registry's
#                 variants (it embeds every preset), which the robot, APF
#                 and arm pages import only for a variant link,
# then optimises each with binaryen's wasm-opt -O3 (the npm package
# `binaryen`, a web/ devDependency: wasm-pack's own download of binaryen
# is not reachable here, so its wasm-opt step is off in the crates'
# Cargo.toml) and drops the remaining custom sections
# (scripts/strip-wasm.mjs).
# WASM_OPT_LEVEL (default s) is the rustc opt-level of these builds only;
# the native release profile stays at 3. Measured (stripped playground
# module, `npm --prefix web run bench:browser` for speed):
#   rustc 3           1.48 MB
#   rustc 3 + -Oz     1.36 MB
#   rustc s           1.22 MB
#   rustc s + -O3     1.13 MB, and binaryen's inlining gives back what "s"
#                     leaves as calls (DWA step and A* wasm/native ≤ 1.5).
# The robot page (this module + ~200 kB of JS/CSS) must stay ≤ 1.5 MB.
# WASM_OPT=0 skips wasm-opt (a quicker build for debugging).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_PROFILE_RELEASE_OPT_LEVEL="${WASM_OPT_LEVEL:-s}"
wasm-pack build crates/planlab-wasm --release --target web --out-dir ../../web/pkg --no-pack -- --no-default-features --features robot
wasm-pack build crates/planlab-wasm --release --target web --out-dir ../../web/pkg-grid --no-pack -- --no-default-features --features grid-search
wasm-pack build crates/planlab-wasm-arm --release --target web --out-dir ../../web/pkg-arm --no-pack
wasm-pack build crates/planlab-wasm-reproduce --release --target web --out-dir ../../web/pkg-reproduce --no-pack
modules=(web/pkg/planlab_wasm_bg.wasm web/pkg-grid/planlab_wasm_bg.wasm web/pkg-arm/planlab_wasm_arm_bg.wasm web/pkg-reproduce/planlab_wasm_reproduce_bg.wasm)
if [ "${WASM_OPT:-1}" != 0 ]; then
  WASM_OPT_BIN=web/node_modules/.bin/wasm-opt
  if [ ! -x "$WASM_OPT_BIN" ]; then
    echo "build-wasm.sh: $WASM_OPT_BIN is missing: run scripts/setup.sh (npm ci in web/)" >&2
    exit 1
  fi
  for m in "${modules[@]}"; do
    # Features come from the module's target_features section (kept until
    # strip-wasm.mjs); floats are left exactly as rustc emitted them, so the
    # wasm trace stays bit-identical to native.
    "$WASM_OPT_BIN" -O3 "$m" -o "$m.opt"
    mv "$m.opt" "$m"
  done
fi
node scripts/strip-wasm.mjs "${modules[@]}"
