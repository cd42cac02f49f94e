#!/usr/bin/env bash
# The whole test suite under AddressSanitizer (with LeakSanitizer) and UndefinedBehaviorSanitizer:
# a separate build in build-asan, every test binary and the `needle` the CLI tests call
# instrumented. Any sanitizer report aborts the process and fails its test.
#   bash scripts/sanitize.sh            (after scripts/setup.sh has installed the dependencies)
# The fuzz test is left out: it is a sanitized libFuzzer build of its own (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake -S . -B build-asan -DNEEDLE_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-asan -j"$jobs" 2>&1 | grep -E "error|warning: .*sanitize" || true
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j"$jobs" -E "fuzz" "$@"
