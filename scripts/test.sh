#!/usr/bin/env bash
# Runs every check planlab promises: formatting, clippy (native and wasm32),
# native unit/integration/doc tests, benches once, docs, the wasm build,
# wasm-pack browser tests, the browser end-to-end tests and the Python
# package's tests (pytest in .venv).
# Installs what is missing first. Exits non-zero on the first failure.
set -euo pipefail
cd "$(dirname "$0")/.."
step() { printf '\n\033[1;32m==> %s\033[0m\n' "$*"; }

step "set-up"
bash scripts/setup.sh --browser
export CHROMEDRIVER="${CHROMEDRIVER:-$(command -v chromedriver)}"
export CHROME_BIN="${CHROME_BIN:-$(command -v chromium)}"

step "cargo fmt --check"
cargo fmt --all -- --check

step "clippy (native, all targets)"
cargo clippy --workspace --all-targets -- -D warnings

step "clippy (wasm32)"
cargo clippy --target wasm32-unknown-unknown -p planlab-core -p planlab-wasm -p planlab-wasm-arm -p planlab-wasm-reproduce -- -D warnings

step "native tests (unit, integration, doc)"
cargo test --workspace

step "benches, once each"
cargo test -p planlab-core --benches

step "docs without warnings"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps

step "wasm package, site and release CLI"
bash scripts/build.sh

step "wasm-pack test --headless --chrome"
wasm-pack test --headless --chrome crates/planlab-wasm

step "browser end-to-end tests"
(cd web && npm run e2e)

step "python package: build the wheel into .venv, pytest"
# The dev profile (planlab-core itself is optimised in it) reuses what
# `cargo test` built above; the tests compare with the release CLI.
(cd crates/planlab-py && VIRTUAL_ENV="$PWD/../../.venv" PATH="$PWD/../../.venv/bin:$PATH" \
  maturin develop --profile dev --quiet)
PLANLAB_CLI="${CARGO_TARGET_DIR:-$PWD/target}/release/planlab" .venv/bin/python -m pytest -q crates/planlab-py/tests

step "all checks passed"
