#!/usr/bin/env bash
# Installs the Debian packages needle builds with; with --tests, also those only the tests use
# (Chromium for the report's browser test, pytest for the Python module's, SciPy for the
# lift-table benchmark bench/lift_tables.py). Then the design page's npm packages, pinned in
# apps/serve/web/package-lock.json: uPlot (its charts), and with --tests puppeteer-core (its
# browser test). Safe to run twice: only what is missing is installed.
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

# Node.js and npm for the page's packages: Debian's, unless this machine has its own npm.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
else
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The design page's npm packages, exactly as package-lock.json pins them (npm ci), unless they
# are there already; puppeteer-core only for the tests.
web="$(dirname "$0")/../apps/serve/web"
want=(uplot)
if ((tests)); then want+=(puppeteer-core); fi
need_npm=0
for m in "${want[@]}"; do [[ -f "$web/node_modules/$m/package.json" ]] || need_npm=1; done
if ((need_npm)); then
  echo "install-deps: npm ci in apps/serve/web (${want[*]})"
  if ((tests)); then
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
  else
    (cd "$web" && npm ci --omit=dev --no-audit --no-fund --loglevel=error)
  fi
fi
