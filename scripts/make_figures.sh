#!/usr/bin/env bash
# Regenerates the figures of the user manual (doc/Density_equalizing_maps/fig/*.png)
# from the shared meshes, with build/bin/dem and scripts/render_mesh.py (python3 only).
#   bash scripts/make_figures.sh [FIGURE ...]     default: all figures
# Requires a built tree (bash scripts/setup.sh) and ../shared/data beside the repository.
# A figure whose method the dem tool does not (yet) support is skipped with a message.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${DEM_BUILD_DIR:-$ROOT/build}"
DATA="${DEM_DATA_DIR:-$ROOT/../shared/data}"
FIG="$ROOT/doc/Density_equalizing_maps/fig"
WORK="$BUILD_DIR/figures"
DEM="$BUILD_DIR/bin/dem"
RENDER=(python3 "$ROOT/scripts/render_mesh.py")
mkdir -p "$FIG" "$WORK"
[[ -x "$DEM" ]] || { echo "make_figures: $DEM not built (run bash scripts/setup.sh)" >&2; exit 1; }
[[ -d "$DATA" ]] || { echo "make_figures: no mesh folder $DATA" >&2; exit 1; }

# dem METHOD MESH OUT [options...]; returns non-zero (and says why) if the method fails
map_mesh() {
  local method=$1 mesh=$2 out=$3; shift 3
  if ! "$DEM" "$method" "$mesh" --output "$out" "$@" > "$out.log" 2>&1; then
    echo "make_figures: skipped: dem $method $(basename "$mesh") failed:" >&2
    tail -3 "$out.log" >&2
    return 1
  fi
}

fig_spherical_conformal_map() {
  local m="$DATA/maxplanck.off"
  map_mesh spherical-conformal "$m" "$WORK/mp_scm.off" || return 0
  map_mesh spherical-conformal "$m" "$WORK/mp_scm_mobius.off" --mobius || return 0
  "${RENDER[@]}" "$FIG/spherical_conformal_map.png" --size 300 \
    "$m,up=y,az=60,el=10" \
    "$WORK/mp_scm.off,ref=$m,up=y,az=60,el=10" \
    "$WORK/mp_scm_mobius.off,ref=$m,up=y,az=60,el=10"
  "${RENDER[@]}" "$FIG/density_equalizing_maps_logo.png" --size 120 \
    "$WORK/mp_scm_mobius.off,ref=$m,up=y,az=60,el=10"
}

fig_spherical_density_equalizing_map() {
  local m="$DATA/david_enlarge.off" p="$DATA/david_enlarge.population.txt"
  map_mesh sdem "$m" "$WORK/david_sdem.off" --population "$p" || return 0
  "${RENDER[@]}" "$FIG/spherical_density_equalizing_map.png" --size 300 \
    "$m,density=$p,up=z,az=200,el=10" \
    "$WORK/david_sdem.off,density=$p,area_of=$m,look=dense" \
    "$WORK/david_sdem.off,density=$p,look=dense,look_ref=$m"
}

fig_landmark_aligned_spherical_density_equalizing_map() {
  local m="$DATA/brain_landmarks.off" p="$DATA/brain_landmarks.population.txt"
  local l="$DATA/brain_landmarks.landmarks.txt"
  map_mesh sdem "$m" "$WORK/brain_sdem.off" --population "$p" || return 0
  map_mesh lsdem "$m" "$WORK/brain_lsdem.off" --population "$p" --landmarks "$l" || return 0
  grep -hE '^l?sdem:' "$WORK/brain_sdem.off.log" "$WORK/brain_lsdem.off.log"
  "${RENDER[@]}" "$FIG/landmark_aligned_spherical_density_equalizing_map.png" --size 300 \
    "$m,landmarks=$l,hidden_depth=0.15,az=270,el=10" \
    "$WORK/brain_sdem.off,ref=$m,landmarks=$l,targets=1,az=30,el=20" \
    "$WORK/brain_lsdem.off,ref=$m,landmarks=$l,targets=1,az=30,el=20"
}

fig_ellipsoidal_conformal_map() {
  local m="$DATA/maxplanck.off"
  map_mesh ellipsoidal-conformal "$m" "$WORK/mp_ecm.off" || return 0
  map_mesh ellipsoidal-conformal "$m" "$WORK/mp_ecm_opt.off" --optimize-radii || return 0
  grep -h '^ellipsoidal-conformal:' "$WORK/mp_ecm.off.log" "$WORK/mp_ecm_opt.off.log"
  "${RENDER[@]}" "$FIG/ellipsoidal_conformal_map.png" --size 300 \
    "$m,up=y,az=60,el=10" \
    "$WORK/mp_ecm.off,ref=$m,az=20,el=10" \
    "$WORK/mp_ecm_opt.off,ref=$m,az=20,el=10"
}

fig_ellipsoidal_density_equalizing_map() {
  local m="$DATA/edem_ellipsoid1.off" p="$DATA/edem_ellipsoid1.population.txt"
  local a b c
  a=$(sed -n 's/^a=//p' "$DATA/edem_ellipsoid1.params.txt"); b=$(sed -n 's/^b=//p' "$DATA/edem_ellipsoid1.params.txt")
  c=$(sed -n 's/^c=//p' "$DATA/edem_ellipsoid1.params.txt")
  map_mesh edem "$m" "$WORK/edem1.off" --population "$p" --radii "$a" "$b" "$c" || return 0
  "${RENDER[@]}" "$FIG/ellipsoidal_density_equalizing_map.png" --size 300 \
    "$m,density=$p,az=30,el=10" "$WORK/edem1.off,density=$p,area_of=$m,az=30,el=10" \
    "$WORK/edem1.off,density=$p,az=30,el=10"
}

fig_toroidal_density_equalizing_map() {
  local m="$DATA/tdem_torus_1.off" p="$DATA/tdem_torus_1.population.txt"
  local R r
  R=$(sed -n 's/^R=//p' "$DATA/tdem_torus_1.params.txt"); r=$(sed -n 's/^r=//p' "$DATA/tdem_torus_1.params.txt")
  map_mesh tdem "$m" "$WORK/tdem1.off" --population "$p" --torus "$R" "$r" || return 0
  "${RENDER[@]}" "$FIG/toroidal_density_equalizing_map.png" --size 300 \
    "$m,density=$p,az=30,el=45,edges=1" "$WORK/tdem1.off,density=$p,area_of=$m,az=30,el=45,edges=1" \
    "$WORK/tdem1.off,density=$p,az=30,el=45,edges=1"
}

ALL=(spherical_conformal_map spherical_density_equalizing_map
     landmark_aligned_spherical_density_equalizing_map ellipsoidal_conformal_map
     ellipsoidal_density_equalizing_map toroidal_density_equalizing_map)
for f in "${@:-${ALL[@]}}"; do
  echo "make_figures: $f"
  "fig_$f"
done
ls -la "$FIG"
