#!/usr/bin/env bash
# Builds the libFuzzer target of the loaders with clang and runs it for a bounded time, seeded
# with the bundled cases and CSV tables.
#   bash scripts/fuzz.sh [SECONDS] [LOADER]   (default 20 s, every loader on every input)
# LOADER (case, engine, synth or csv) fuzzes one loader alone; the long runs of issue 38 were
#   for l in case engine synth csv; do bash scripts/fuzz.sh 1800 $l; done
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
loader=${2:-}
case "$loader" in
  ""|case|engine|synth|csv) ;;
  *) echo "fuzz.sh: LOADER: expected case, engine, synth or csv, got '$loader'" >&2; exit 2 ;;
esac
# The root project with NEEDLE_FUZZ: the real libraries, instrumented, and the fuzz target, at
# -O1 as libFuzzer's documentation builds them (268 s against -O2's 305 s on 2 cores, and 10,561
# runs in 5 s against 10,982 on the bundled corpus; -O0 saved only 13 %), with line tables only,
# as AddressSanitizer's documentation suggests (a report's stack keeps its files and lines; full
# -g took 14 % more a heavy file). A CI run waits on this build.
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DNEEDLE_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target case_loader_fuzz >/dev/null
corpus=$(mktemp -d)
cp cases/*.toml cases/*.csv tests/data/*.csv "$corpus"/
NEEDLE_FUZZ_LOADER="$loader" ./build-fuzz/case_loader_fuzz -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 "$corpus" 2>&1 | tail -n 12
status=${PIPESTATUS[0]}
rm -rf "$corpus"
exit "$status"
