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
# The installed command hands `fit` and `serve` to libexec/needle/needle-fit-serve (before the
# consumer's line, which ctest's PASS_REGULAR_EXPRESSION reads whatever the exit status).
"$work/prefix/bin/needle" fit --help | grep -q -- --trace
"$work/consumer/consumer" cases/basu-example1.toml
"$work/consumer/consumer_before_rename" cases/basu-example1.toml
# The Python package, when the build has it: imported from the prefix alone, needle.distributed
# beside the compiled module, its command line answering.
python=$(sed -n "s/^_\?Python3_EXECUTABLE:[A-Z]*=//p" "$build/CMakeCache.txt" | head -1)
site=$(find "$work/prefix" -name 'needle.cpython-*.so' -printf '%h\n' | head -1)
if [[ -n "$site" ]]; then
  env -u PYTHONPATH PYTHONPATH="$site" "$python" -c "
import needle, needle.distributed as d
assert needle.__file__.startswith('$site/') and d.__file__ == '$site/needle/distributed.py', d
print('python package: needle', needle.__version__, 'with needle.distributed')"
  env PYTHONPATH="$site" "$python" -m needle.distributed tolerance --help | grep -q -- --scheduler
fi
