#!/usr/bin/env bash
# Installs the Debian packages needle builds with; with --tests, also those only the tests use
# (Chromium for the report's browser test, pytest for the Python module's, SciPy for the
# lift-table benchmark bench/lift_tables.py). Safe to run twice:
# only packages that are missing are installed; nothing is downloaded otherwise.
set -euo pipefail
tests=0
for arg in "$@"; do
  case "$arg" in
    --tests) tests=1 ;;
    *) echo "install-deps: unknown option $arg (expected --tests)" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake pkg-config
  libeigen3-dev          # splines: banded / dense linear algebra
  libboost-dev           # Odeint (header-only) and Boost.Math
  libsundials-dev        # CVODE
  libgtest-dev libgmock-dev
  libtomlplusplus-dev    # case files
  libcli11-dev           # command line
  nlohmann-json3-dev     # JSON output
  libbenchmark-dev       # micro-benchmarks
  gnuplot-nox            # figures: needle check reports, scripts/bench.sh
  clang libclang-rt-14-dev  # libFuzzer target for the case loader
  pybind11-dev python3-dev python3-numpy  # the Python module (apps/python)
  python3-distributed    # Dask: python3 -m needle.distributed (docs/distributed.md)
  libcpp-httplib-dev     # needle serve: the design page's HTTP server (apps/serve)
  libjs-chart.js         # needle serve: the page's charts, served from the install
  libceres-dev           # needle fit: Ceres Solver's nonlinear least squares
)
if ((tests)); then
  packages+=(
    chromium        # the report and the design page in a real browser (check_report_test,
                    # design_server_test)
    python3-pytest  # the Python module's tests (tests/apps/python)
    python3-scipy   # bench/lift_tables.py: SciPy's smoothing spline and Savitzky-Golay as peers
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
