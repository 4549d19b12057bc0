#!/usr/bin/env bash
# Builds the wasm package and the static site into web/dist, and the release CLI.
set -euo pipefail
cd "$(dirname "$0")/.."
wasm-pack build crates/planlab-wasm --release --target web --out-dir ../../web/pkg --no-pack
(cd web && npm run build)
cargo build --release -p planlab-cli
