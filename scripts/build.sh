#!/usr/bin/env bash
# Builds the wasm packages and the static site into web/dist, and the release CLI.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-wasm.sh
(cd web && npm run build)
cargo build --release -p planlab-cli
