#!/usr/bin/env bash
# "Command two": installs missing dependencies, builds (Release) and runs the
# whole test suite. Tests needing ../shared/data are reported as skipped when
# that folder is absent.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
export DEM_BUILD_DIR="$BUILD_DIR"

start=$(date +%s)
# tests, examples and dem; the benchmark programs are not needed here
bash "$ROOT/scripts/setup.sh" dem_check_programs
built=$(date +%s)
echo "run_tests: setup + build took $((built - start)) s"

# Two tests at a time, each on one thread (no BLAS/OpenMP oversubscription):
# the suite is sized for 2 cores.
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"${DEM_TEST_JOBS:-2}" -LE known_failure
echo "run_tests: ctest took $(( $(date +%s) - built )) s"
