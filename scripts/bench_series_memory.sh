#!/usr/bin/env bash
# The peak memory of `needle simulate --csv` against the series' length: a streamed series
# keeps it flat (docs/commands.md, simulate). One stiff train over 100 revolutions at three
# tolerances (the finer, the more rows); each line: rtol, rows written, wall time, peak RSS.
# Usage: scripts/bench_series_memory.sh [NEEDLE_BINARY]   (default: build/needle)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
needle="${1:-$here/build/needle}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf '%-6s %9s %8s %10s\n' rtol rows wall_s peak_MiB
for rtol in 1e-8 1e-10 1e-12; do
  /usr/bin/time -f '%e %M' -o "$out/time" "$needle" simulate \
    "$here/cases/basu-cam4-stiff-train.toml" --cycles 100 --method dopri5 --rtol "$rtol" \
    --dynamic --csv "$out/series.csv" >/dev/null || true
  read -r wall kb <"$out/time"
  rows=$(($(wc -l <"$out/series.csv") - 1))
  printf '%-6s %9d %8.2f %10.1f\n' "$rtol" "$rows" "$wall" "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')"
done
