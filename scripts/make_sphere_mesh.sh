#!/usr/bin/env bash
# Writes a closed genus-0 triangle mesh (OFF) to stdout: an icosahedron
# subdivided LEVEL times (default 3: 642 vertices, 1280 faces), projected to
# the unit sphere, then radially deformed into a bumpy peanut so that the
# conformal map has visible area distortion. Pure awk: no dependency.
#   bash scripts/make_sphere_mesh.sh [LEVEL] > mesh.off
set -euo pipefail
LEVEL="${1:-3}"
awk -v level="$LEVEL" '
function add_vertex(x, y, z,   r) {
  r = sqrt(x*x + y*y + z*z); X[nv] = x/r; Y[nv] = y/r; Z[nv] = z/r; return nv++
}
function midpoint(a, b,   key) {               # one shared vertex per edge
  key = (a < b) ? a "," b : b "," a
  if (!(key in mid)) mid[key] = add_vertex((X[a]+X[b])/2, (Y[a]+Y[b])/2, (Z[a]+Z[b])/2)
  return mid[key]
}
BEGIN {
  t = (1 + sqrt(5)) / 2; nv = 0
  add_vertex(-1, t, 0); add_vertex(1, t, 0); add_vertex(-1, -t, 0); add_vertex(1, -t, 0)
  add_vertex(0, -1, t); add_vertex(0, 1, t); add_vertex(0, -1, -t); add_vertex(0, 1, -t)
  add_vertex(t, 0, -1); add_vertex(t, 0, 1); add_vertex(-t, 0, -1); add_vertex(-t, 0, 1)
  split("0 11 5 0 5 1 0 1 7 0 7 10 0 10 11 1 5 9 5 11 4 11 10 2 10 7 6 7 1 8 " \
        "3 9 4 3 4 2 3 2 6 3 6 8 3 8 9 4 9 5 2 4 11 6 2 10 8 6 7 9 8 1", f, " ")
  nf = 20; for (i = 0; i < 60; i++) F[i] = f[i+1]
  for (l = 0; l < level; l++) {
    delete mid; m = 0
    for (i = 0; i < nf; i++) {
      a = F[3*i]; b = F[3*i+1]; c = F[3*i+2]
      ab = midpoint(a, b); bc = midpoint(b, c); ca = midpoint(c, a)
      G[m++] = a;  G[m++] = ab; G[m++] = ca
      G[m++] = b;  G[m++] = bc; G[m++] = ab
      G[m++] = c;  G[m++] = ca; G[m++] = bc
      G[m++] = ab; G[m++] = bc; G[m++] = ca
    }
    nf = m / 3; for (i = 0; i < m; i++) F[i] = G[i]
  }
  print "OFF"; print nv, nf, 0
  for (i = 0; i < nv; i++) {
    # star-shaped radial deformation: elongate along x, pinch the middle, add bumps
    r = 1 + 0.35 * X[i] * X[i] - 0.25 * exp(-8 * X[i] * X[i]) + 0.08 * Y[i] * Z[i]
    printf "%.10f %.10f %.10f\n", 1.6 * r * X[i], r * Y[i], r * Z[i]
  }
  for (i = 0; i < nf; i++) print 3, F[3*i], F[3*i+1], F[3*i+2]
}'
