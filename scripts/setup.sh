#!/usr/bin/env bash
# Installs the build dependencies (Debian/Ubuntu, apt-get) if any is missing,
# then configures and builds the package into build/ (Release).
#
#   bash scripts/setup.sh            # deps + configure + build everything (all programs)
#   bash scripts/setup.sh TARGET...  # deps + configure + build only these targets
#   DEM_SKIP_DEPS=1 bash scripts/setup.sh   # do not touch the system packages
#   DEM_BUILD_DIR=/tmp/b bash scripts/setup.sh  # other build directory
#   DEM_FORMAT_CHECKS=1 bash scripts/setup.sh   # also the file-format readers of the tests
#
# Idempotent: when every package is installed and the build is up to date it
# only runs `dpkg -s` and an incremental `cmake --build` (a few seconds).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
JOBS="${DEM_JOBS:-$(nproc 2>/dev/null || echo 2)}"

# The build dependencies. The documentation tools (doxygen, libjs-mathjax) are
# installed by scripts/build_docs.sh, which is the only command that needs them.
PACKAGES=(libcgal-dev libeigen3-dev libboost-dev libgmp-dev libmpfr-dev
          libsuitesparse-dev libopenblas0-pthread cmake g++ ccache
          zlib1g-dev   # zlib: GIfTI arrays in the GZipBase64Binary encoding
          libtbb-dev   # oneTBB: the parallel loops (concurrency_tag, dem --threads)
          nlohmann-json3-dev librsvg2-bin)  # dem cartogram: GeoJSON parsing, PNG pictures
# Third-party readers of the test test_formats_third_party (skipped without
# them): installed too when DEM_FORMAT_CHECKS=1 (CI sets it).
if [[ "${DEM_FORMAT_CHECKS:-0}" == 1 ]]; then
  PACKAGES+=(python3-nibabel python3-vtk9 python3-meshio gifti-bin)
fi

configure_and_build() {
  # Configure only once (or when the cache is gone): re-running cmake on an
  # existing tree is done automatically by the build when CMakeLists change.
  if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
    cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  fi
  local targets=()
  if (( $# > 0 )); then targets=(--target "$@"); fi
  cmake --build "$BUILD_DIR" -j"$JOBS" "${targets[@]}"
}

bash "$ROOT/scripts/install_packages.sh" "${PACKAGES[@]}"
configure_and_build "$@"
