#!/usr/bin/env bash
# "Command one": installs missing build dependencies, builds (Release) the one
# program it runs, the `dem` tool, then maps a genus-0 mesh conformally onto the
# unit sphere with the Moebius area correction and prints the metrics.
#   bash scripts/run_example.sh [MESH.off]
# Mesh: the argument, else ../shared/data/maxplanck.off beside the repository,
# else a bumpy icosphere written by scripts/make_sphere_mesh.sh.
# Results go to build/example_output/{out.off,metrics.json}.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
export DEM_BUILD_DIR="$BUILD_DIR"

bash "$ROOT/scripts/setup.sh" dem

OUT_DIR="$BUILD_DIR/example_output"
mkdir -p "$OUT_DIR"
if [[ $# -ge 1 ]]; then
  MESH="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
elif [[ -f "$ROOT/../shared/data/maxplanck.off" ]]; then
  MESH="$(cd "$ROOT/../shared/data" && pwd)/maxplanck.off"
else
  MESH="$OUT_DIR/bumpy_icosphere.off"
  bash "$ROOT/scripts/make_sphere_mesh.sh" 4 > "$MESH"
fi

cd "$OUT_DIR"
echo "run_example: $BUILD_DIR/bin/dem spherical-conformal $MESH --mobius --output out.off --metrics metrics.json"
"$BUILD_DIR/bin/dem" spherical-conformal "$MESH" --mobius --output out.off --metrics metrics.json
echo "run_example: mapped mesh  $OUT_DIR/out.off"
echo "run_example: metrics      $OUT_DIR/metrics.json"
cat metrics.json
echo
