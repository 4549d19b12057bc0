#!/usr/bin/env bash
# Builds the two wasm packages of the site (release):
#  - web/pkg:     planlab-wasm without the arm (index, robot, apf, bench and
#                 every other page),
#  - web/pkg-arm: planlab-wasm-arm, the arm page's own small module (the arm
#                 page also loads three.js; one module with everything would
#                 not fit its 1.5 MB first-load budget),
# then drops their custom sections (function names; scripts/strip-wasm.mjs).
# WASM_OPT_LEVEL (default s) is the rustc opt-level of these builds only;
# the native release profile stays at 3. "s" makes the playground module
# smaller than 3 (1.22 MB instead of 1.43 MB with planlab-core at 3, stripped), which keeps
# every page's first load ≤ 1.5 MB with room to grow; the wasm/native
# ratios stay ≤ 1.5 (npm --prefix web run bench:browser).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_PROFILE_RELEASE_OPT_LEVEL="${WASM_OPT_LEVEL:-s}"
wasm-pack build crates/planlab-wasm --release --target web --out-dir ../../web/pkg --no-pack -- --no-default-features
wasm-pack build crates/planlab-wasm-arm --release --target web --out-dir ../../web/pkg-arm --no-pack
node scripts/strip-wasm.mjs web/pkg/planlab_wasm_bg.wasm web/pkg-arm/planlab_wasm_arm_bg.wasm
