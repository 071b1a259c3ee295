#!/usr/bin/env bash
# Checks the package as its two kinds of users see it.
# A. A user of an installed copy:
#   1. installs the configured build tree (headers + package configuration) into a
#      temporary prefix;
#   2. fails when an installed file names a path of this machine's source or build
#      tree, or the absolute location of a dependency (the configuration must find
#      CGAL, Eigen and CHOLMOD on the consumer's machine);
#   3. moves the prefix elsewhere (the installed copy must be relocatable), then
#      configures, builds and runs test/Density_equalizing_maps/consumer with
#      find_package(Density_equalizing_maps CONFIG REQUIRED) against that prefix.
# B. A project that adds the repository with add_subdirectory():
#   4. configures and builds test/Density_equalizing_maps/subproject, whose
#      configuration fails when the package defines more than its library target
#      or changes the parent's BUILD_TESTING or CMAKE_BUILD_TYPE.
#   bash scripts/check_consumers.sh            # uses build/ (configured by setup.sh)
#   DEM_BUILD_DIR=/tmp/b bash scripts/check_consumers.sh
# The temporary prefix and the consumers' builds are removed at the end.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
if [[ ! -f "$BUILD_DIR/CMakeCache.txt" ]]; then
  cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
WORK="$(mktemp -d "${TMPDIR:-/tmp}/dem_check_consumers.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
PREFIX="$WORK/prefix"

cmake --install "$BUILD_DIR" --prefix "$PREFIX" >/dev/null
echo "check_consumers: installed into a temporary prefix: $(find "$PREFIX" -type f | wc -l) files"

# Absolute paths that must not appear: the source and build trees, and the
# folders where this machine's dependencies live (they differ on the consumer's).
forbidden=("$ROOT" "$BUILD_DIR")
for var in CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR CGAL_DIR EIGEN3_INCLUDE_DIR Eigen3_DIR; do
  value="$(sed -n "s/^$var:[A-Z]*=//p" "$BUILD_DIR/CMakeCache.txt" | head -n1)"
  if [[ -n "$value" && "$value" == /* && "$value" != *NOTFOUND ]]; then forbidden+=("$value"); fi
done
status=0
for path in "${forbidden[@]}"; do
  if grep -rlF -- "$path" "$PREFIX/share/Density_equalizing_maps" "$PREFIX/include"; then
    echo "check_consumers: FAILED: the installed files above name the build machine's $path" >&2
    status=1
  fi
done
(( status == 0 )) || exit 1
echo "check_consumers: no absolute path of the build machine in the installed files"
mv "$PREFIX" "$WORK/moved_prefix"
PREFIX="$WORK/moved_prefix"

cmake -S "$ROOT/test/Density_equalizing_maps/consumer" -B "$WORK/consumer" \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$PREFIX" >"$WORK/configure.log" \
  || { cat "$WORK/configure.log"; exit 1; }
grep "Density_equalizing_maps .* from" "$WORK/configure.log" | sed 's/^-- /check_consumers: found /'
cmake --build "$WORK/consumer" -j"${DEM_JOBS:-2}" >"$WORK/build.log" || { cat "$WORK/build.log"; exit 1; }
"$WORK/consumer/dem_consumer"

# B: the parent's configuration asserts what it expects (see its CMakeLists.txt)
cmake -S "$ROOT/test/Density_equalizing_maps/subproject" -B "$WORK/parent" \
      -DDEM_SOURCE_DIR="$ROOT" >"$WORK/parent.log" 2>&1 || { cat "$WORK/parent.log"; exit 1; }
grep "^-- parent:" "$WORK/parent.log" | sed 's/^-- parent:/check_consumers: add_subdirectory:/'
cmake --build "$WORK/parent" >"$WORK/parent_build.log" 2>&1 || { cat "$WORK/parent_build.log"; exit 1; }
"$WORK/parent/dem_parent_program"
echo "check_consumers: OK"
