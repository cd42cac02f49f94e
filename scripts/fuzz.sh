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
# runs in 5 s against 10,982 on the bundled corpus), with line tables only, as AddressSanitizer's
# documentation suggests (a report's stack keeps its files and lines; full -g took 14 % more a
# heavy file). NEEDLE_FUZZ_OPT=-O0 (ctest's 20 s run, which a CI run waits on) built and ran in
# 3 min 19 s (324 s of CPU) against -O1's 7 min 6 s (748 s) 40 minutes before on this 2-core
# machine, with 9,123 runs in 21 s against 19,819.
opt=${NEEDLE_FUZZ_OPT:--O1}
case "$opt" in
  -O0|-O1|-O2) ;;
  *) echo "fuzz.sh: NEEDLE_FUZZ_OPT: expected -O0, -O1 or -O2, got '$opt'" >&2; exit 2 ;;
esac
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DNEEDLE_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$opt -gline-tables-only -DNDEBUG" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target case_loader_fuzz >/dev/null
corpus=$(mktemp -d)
cp cases/*.toml cases/*.csv tests/data/*.csv "$corpus"/
NEEDLE_FUZZ_LOADER="$loader" ./build-fuzz/case_loader_fuzz -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 "$corpus" 2>&1 | tail -n 12
status=${PIPESTATUS[0]}
rm -rf "$corpus"
exit "$status"
