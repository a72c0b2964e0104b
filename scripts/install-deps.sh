#!/usr/bin/env bash
# Installs the dependencies of floorgrid from Debian's packages. Idempotent: packages already
# present are not touched, so a second run is quick and needs no network. Run as root.
#
#   scripts/install-deps.sh          everything: the build, the tests, benchmarks, fuzzing (make test)
#   scripts/install-deps.sh --demo   only what the floorgrid program needs to build (make demo)
set -euo pipefail

mode=all
case "${1:-}" in
  "") ;;
  --demo) mode=demo ;;
  *)
    echo "install-deps: unknown option '$1' (use --demo, or nothing for every dependency)" >&2
    exit 2
    ;;
esac

# What the floorgrid program needs: the toolchain and the libraries it links.
packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # libraries linked by floorgrid (all BSD/MIT/Apache/MPL compatible; no GPL)
  libeigen3-dev libnanoflann-dev libopencv-core-dev libopencv-imgproc-dev
  libpng-dev zlib1g-dev libyaml-cpp-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libspdlog-dev libcpp-httplib-dev
  # robot-log containers: ROS 1 bags (bz2, lz4 chunks), MCAP (lz4, zstd), rosbag2 (sqlite3)
  liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev
)
# The report's uPlot and the viewer's Leaflet come from npm (below). Machines here come with
# Node and npm; Debian's are installed only where npm is missing.
if ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi
if [ "$mode" = all ]; then
  packages+=(
    # make format
    clang-format
    # tests and benchmarks; libdime (BSD) is a third, independent DXF reader in the tests only
    libgtest-dev libgmock-dev libbenchmark-dev libdime-dev
    # the Python module (pybind11, Debian's /usr/bin/python3 and numpy) and its tests
    pybind11-dev python3-dev python3-numpy python3-pytest
    # OpenCV calib3d: only bench/ransac_bench links it (cv::estimateAffinePartial2D comparison)
    libopencv-calib3d-dev
    # independent DXF reader used only by tests (never linked)
    python3-ezdxf
    # independent writers of test bags (ROS 1: python3-rosbag and its message packages) and
    # GDAL's tools that check the exported VRT (test tools only, never linked)
    python3-rosbag python3-roslz4 python3-sensor-msgs python3-nav-msgs python3-tf2-msgs
    python3-geometry-msgs gdal-bin
    # the browser tests of report.html and the viewer (driven by playwright-core from npm)
    chromium
    # make fuzz: libFuzzer from clang-16 (clang-14 cannot compile libstdc++ 12's <ranges>)
    clang-16 libclang-rt-16-dev
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# npm packages of the test bag writers, installed once from the lock file: later runs find
# tests/bags/node_modules and need no network. A failure only skips the MCAP writer's tests.
install_bag_writers() {
  [ "$mode" = all ] || return 0
  local bags
  bags="$(cd "$(dirname "$0")/.." && pwd)/tests/bags"
  if [ -d "$bags/node_modules/@mcap/core" ] || ! command -v npm >/dev/null; then
    return 0
  fi
  echo "install-deps: npm ci in tests/bags (the MCAP test writer)"
  npm ci --prefix "$bags" --no-audit --no-fund --loglevel=error ||
    echo "install-deps: npm ci failed: the MCAP writer tests will be skipped" >&2
}

# npm packages of a folder with a package-lock.json, installed once (never a browser download):
# later runs find its node_modules and need no network.
#   install_npm_packages FOLDER WHAT PACKAGE...   (installs unless every PACKAGE is there)
install_npm_packages() {
  local folder package
  folder="$(cd "$(dirname "$0")/.." && pwd)/$1"
  local what=$2
  shift 2
  for package in "$@"; do
    if [ ! -d "$folder/node_modules/$package" ]; then
      echo "install-deps: npm ci in $folder ($what)"
      PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --prefix "$folder" --no-audit --no-fund \
        --loglevel=error
      return
    fi
  done
}

# The report's uPlot (embedded into report.html at build time: the configure fails without it)
# and its browser test's playwright-core; the viewer's Leaflet (served by `floorgrid serve`)
# and its browser tests' playwright-core.
install_page_packages() {
  install_npm_packages report "uPlot for report.html, playwright-core for its test" \
    uplot playwright-core
  install_npm_packages web "Leaflet for the viewer, playwright-core for its tests" \
    leaflet playwright-core
}

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present ($mode)"
  install_bag_writers
  install_page_packages
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "install-deps: run as root (or: sudo $0)" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_bag_writers
install_page_packages
