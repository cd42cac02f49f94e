#!/usr/bin/env bash
# Builds the libFuzzer target for the case loader with clang and runs it for a bounded time,
# seeded with the bundled cases.   bash scripts/fuzz.sh [SECONDS]   (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
# The root project with NEEDLE_FUZZ: the real libraries, instrumented, and the fuzz target.
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DNEEDLE_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target case_loader_fuzz >/dev/null
corpus=$(mktemp -d)
cp cases/*.toml "$corpus"/
./build-fuzz/case_loader_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
  -print_final_stats=1 "$corpus" 2>&1 | tail -n 12
status=${PIPESTATUS[0]}
rm -rf "$corpus"
exit "$status"
