#!/usr/bin/env bash
# Installs needle from BUILD into a temporary prefix, builds tests/consumer against it with
# find_package(needle), and runs it on Example 1.   bash scripts/consumer-test.sh [BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S tests/consumer -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer" cases/basu-example1.toml
