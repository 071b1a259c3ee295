#!/usr/bin/env bash
# "Command two": installs missing dependencies, builds (Release) and runs the
# whole test suite; before the tests it checks what a user relies on beyond them:
#   - scripts/check_consumers.sh: an installed copy found with find_package()
#     builds and runs a consumer project; add_subdirectory() defines only the
#     library target and leaves the parent's cache alone;
#   - scripts/build_docs.sh: the manual builds with zero Doxygen warnings.
# Tests needing ../shared/data (ctest label shared_data) are reported as skipped
# when that folder is absent. DEM_SKIP_DOCS=1 / DEM_SKIP_CONSUMERS=1 leave out
# the last two steps.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
export DEM_BUILD_DIR="$BUILD_DIR"

start=$(date +%s)
# tests, examples and dem; the benchmark programs are not needed here
bash "$ROOT/scripts/setup.sh" dem_check_programs
built=$(date +%s)
echo "run_tests: setup + build took $((built - start)) s"

if [[ "${DEM_SKIP_CONSUMERS:-0}" != 1 ]]; then
  step=$(date +%s)
  bash "$ROOT/scripts/check_consumers.sh"
  echo "run_tests: consumers took $(( $(date +%s) - step )) s"
fi
if [[ "${DEM_SKIP_DOCS:-0}" != 1 ]]; then
  step=$(date +%s)
  bash "$ROOT/scripts/build_docs.sh"
  echo "run_tests: documentation took $(( $(date +%s) - step )) s"
fi

# ctest last, so that its summary closes the output (it prints its own time)
echo "run_tests: $(( $(date +%s) - start )) s before ctest"
# Two tests at a time, each on one thread (no BLAS/OpenMP oversubscription):
# the suite is sized for 2 cores.
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"${DEM_TEST_JOBS:-2}" -LE known_failure
