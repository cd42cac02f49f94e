#!/usr/bin/env bash
# Regenerates the benchmark evidence: bench/*.csv, bench/*.svg and BENCHMARKS.md.
#   bash scripts/bench.sh [--quick]
# Builds first (scripts/setup.sh). Runs on one core except the overspeed speed-up and the lift
# tables (bench/lift_tables.py, some 6 minutes; skipped without SciPy), which take two.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh >/dev/null
mkdir -p bench
./build/needle-bench all --out bench --repeats 7 "$@" 2>bench/log.txt >/dev/null

for scene in soft stiff liftoff; do
  for what in lift force; do
    if [[ $what == lift ]]; then col=8; label="largest lift error (µm)"; else col=9; label="largest contact-force error (N)"; fi
    gnuplot <<GP
set datafile separator ","
set terminal svg size 760,520 font "sans,12"
set output "bench/work-precision-${scene}-${what}.svg"
set title "needle: ${scene} scene, run time against ${what} error"
set logscale xy
set format y "10^{%L}"
set xlabel "median run time (ms), one core"
set ylabel "${label}"
set key outside right
set grid
methods = "dopri5 rkf78 rosenbrock4 cvode-bdf cvode-adams exact baseline-dopri5"
plot for [m in methods] "bench/work-precision-${scene}.csv" \
  using (strcol(2) eq m && strcol(14) eq "" ? \$4 : NaN):(\$${col} > 0 ? \$${col} : NaN) \
  with linespoints title m
GP
  done
done

# Lift tables as users export them, against SciPy's peers (bench/lift_tables.py, a few minutes;
# --quick passes through). Needs python3-scipy (install-deps.sh --tests); skipped without it.
if python3 -c 'import scipy' 2>/dev/null || /usr/bin/python3 -c 'import scipy' 2>/dev/null; then
  lift_args=()
  for arg in "$@"; do [[ $arg == --quick ]] && lift_args+=(--quick); done
  python3 bench/lift_tables.py "${lift_args[@]}" >/dev/null 2>>bench/log.txt ||
    echo "bench: bench/lift_tables.py failed (bench/log.txt); BENCHMARKS.md keeps the last bench/lift-tables.md" >&2
else
  echo "bench: SciPy missing (apt-get install python3-scipy): lift tables not measured, bench/lift-tables.md not regenerated" >&2
fi

# Dense tables of 1e6 rows: needle's wall time (bench/dense_tables.py, about a minute).
if python3 -c 'import numpy' 2>/dev/null || /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  python3 bench/dense_tables.py >/dev/null 2>>bench/log.txt ||
    echo "bench: bench/dense_tables.py failed (bench/log.txt)" >&2
fi

# Python binds once and runs many (bench/python_scene.py, a few seconds; needs the module).
/usr/bin/python3 bench/python_scene.py >/dev/null 2>>bench/log.txt ||
  echo "bench: bench/python_scene.py failed (bench/log.txt); BENCHMARKS.md keeps the last bench/python-scene.md" >&2

# SciPy's solve_ivp on the same one-mass model as `exact` (bench/scipy_peer.py, about a
# minute; needs python3-scipy and the module).
if /usr/bin/python3 -c 'import scipy' 2>/dev/null; then
  PYTHONPATH=build/python /usr/bin/python3 bench/scipy_peer.py >/dev/null 2>>bench/log.txt ||
    echo "bench: bench/scipy_peer.py failed (bench/log.txt); BENCHMARKS.md keeps the last bench/scipy-peer.md" >&2
fi

# Issue 53's targets against a build of fdb02a4, the issue's baseline (bench/issue53_targets.py,
# a minute): only where NEEDLE_FDB02A4 names that build's needle; else the last table is kept.
if [[ -n ${NEEDLE_FDB02A4:-} ]]; then
  python3 bench/issue53_targets.py --old "$NEEDLE_FDB02A4" >/dev/null 2>>bench/log.txt ||
    echo "bench: bench/issue53_targets.py failed (bench/log.txt)" >&2
fi

{
  cat <<'HEAD'
# Benchmarks

Regenerate with `bash scripts/bench.sh` (about 10 s after the build); it writes the CSV files
and plots in `bench/` and this page from `bench/summary.md`. Numbers below are from the last
run on a 2-core machine of the project's kind; timings vary by a few tens of percent from run
to run; the two-core speed-up of the overspeed search most of all (1.1–1.6×: on this machine
two independent processes of the same simulations slow each other down by 1.3–1.6×). Plots:
`bench/work-precision-<scene>-lift.svg` and `-force.svg`.


HEAD
  cat bench/summary.md
  # The peer comparison (scripts/siconos_cam_follower.py compare; needs python3-siconos).
  if [[ -f bench/siconos-cam-follower.md ]]; then echo; cat bench/siconos-cam-follower.md; fi
  # Lift tables as users export them against SciPy (bench/lift_tables.py; needs python3-scipy).
  if [[ -f bench/lift-tables.md ]]; then echo; cat bench/lift-tables.md; fi
  # Dense tables of 1e6 rows: needle's wall time (bench/dense_tables.py; needs python3-numpy).
  if [[ -f bench/dense-tables.md ]]; then echo; cat bench/dense-tables.md; fi
  # Python: bind once, run many (bench/python_scene.py).
  if [[ -f bench/python-scene.md ]]; then echo; cat bench/python-scene.md; fi
  # SciPy's solve_ivp against exact (bench/scipy_peer.py).
  if [[ -f bench/scipy-peer.md ]]; then echo; cat bench/scipy-peer.md; fi
  # Issue 53's targets against fdb02a4's build (bench/issue53_targets.py).
  if [[ -f bench/issue53-targets.md ]]; then echo; cat bench/issue53-targets.md; fi
} > BENCHMARKS.md.tmp && mv BENCHMARKS.md.tmp BENCHMARKS.md
echo "wrote bench/ and BENCHMARKS.md"
