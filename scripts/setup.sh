#!/usr/bin/env bash
# Installs whatever planlab's build and tests need and is missing. Idempotent:
# every step checks first. Usage: scripts/setup.sh [--browser | --serve]
#   --browser  also install Chromium + ChromeDriver (needed by the tests only).
#   --serve    only what building and serving the playground needs (Rust,
#              wasm-pack, wasm-bindgen, Node's packages): no Python
#              environment, no browser (scripts/serve.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

log() { printf '\033[1;34m[setup]\033[0m %s\n' "$*"; }
SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null 2>&1; then SUDO=sudo; fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "cargo not found: install Rust with rustup first (https://rustup.rs)" >&2
  exit 1
fi
if command -v rustup >/dev/null 2>&1; then
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    log "adding the wasm32-unknown-unknown target"
    rustup target add wasm32-unknown-unknown
  fi
  for comp in clippy rustfmt; do
    if ! rustup component list --installed | grep -q "^$comp"; then
      log "adding rustup component $comp"
      rustup component add "$comp"
    fi
  done
fi

if ! command -v wasm-pack >/dev/null 2>&1; then
  log "installing wasm-pack (about 2 minutes)"
  cargo install wasm-pack --locked
fi

# wasm-pack would try to download wasm-bindgen; install the exact version the
# lock file pins from crates.io instead (its CLI must match the library).
WB_VERSION=$(awk '/^name = "wasm-bindgen"$/ {getline; gsub(/"/, "", $3); print $3; exit}' Cargo.lock)
if [ -n "$WB_VERSION" ] && [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$WB_VERSION" ]; then
  log "installing wasm-bindgen-cli $WB_VERSION (about 3 minutes)"
  # Not --locked: its lock pins a webpki-roots release the registry no longer serves.
  cargo install wasm-bindgen-cli --version "$WB_VERSION" --force
fi

if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  log "installing Node.js and npm"
  $SUDO apt-get update -qq && $SUDO apt-get install -y -qq nodejs npm
fi

# npm ci only when the lock file changed since the last install.
if [ ! -f web/node_modules/.package-lock.json ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then
  log "installing the page's npm packages"
  (cd web && npm ci --no-audit --no-fund)
fi

MODE="${1:-}"
case "$MODE" in
  ""|--browser|--serve) ;;
  *) echo "setup.sh: unknown option $MODE (use --browser or --serve)" >&2; exit 2 ;;
esac

if [ "$MODE" = "--serve" ]; then
  log "set-up for serving complete"
  exit 0
fi

# The Python package's virtual environment: .venv at the root (git-ignored)
# with the pinned dev requirements of crates/planlab-py; pip runs only when
# the venv is new or the requirements file changed since the last install.
PY_REQ=crates/planlab-py/requirements-dev.txt
if ! command -v python3 >/dev/null 2>&1; then
  log "installing Python 3"
  $SUDO apt-get update -qq && $SUDO apt-get install -y -qq python3 python3-venv
fi
if [ ! -x .venv/bin/python ]; then
  if ! python3 -c 'import ensurepip' >/dev/null 2>&1; then
    log "installing python3-venv"
    $SUDO apt-get update -qq && $SUDO apt-get install -y -qq python3-venv
  fi
  log "creating the Python virtual environment .venv"
  python3 -m venv .venv
fi
if ! cmp -s "$PY_REQ" .venv/.requirements-dev.txt; then
  log "installing the Python dev requirements into .venv (maturin, pytest, numpy, gymnasium, ray, matplotlib, mcap, ompl)"
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -r "$PY_REQ"
  cp "$PY_REQ" .venv/.requirements-dev.txt
fi

if [ "$MODE" = "--browser" ]; then
  if ! command -v chromium >/dev/null 2>&1 || ! command -v chromedriver >/dev/null 2>&1; then
    log "installing Chromium and ChromeDriver (Debian packages)"
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq chromium chromium-driver
  fi
fi
log "set-up complete"
