#!/usr/bin/env bash
# Installs what is missing (Debian packages), configures and builds needle into build/.
# --tests: also what only the tests use (Chromium, pytest; README's test command).
# Safe to run twice: the install step skips present packages, the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh "$@"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
