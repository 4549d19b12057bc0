#!/usr/bin/env bash
# One command from a fresh machine to the playground on http://127.0.0.1:8080:
# installs what is missing for that (no Python, no browser), builds, serves
# (precompressed: the build writes .br/.gz twins). Stop with Ctrl-C.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --serve
bash scripts/build.sh
exec target/release/planlab serve --dir web/dist --host 127.0.0.1 --port "${PORT:-8080}"
