#!/usr/bin/env python3
"""Writes a landmark file for a genus-0 mesh: K vertices drawn with a fixed
seed, each sent to its own direction (from the centroid) rotated by ANGLE
radians about the z axis, on the unit sphere (the `dem` ellipsoidal tools
scale unit-sphere targets onto the target ellipsoid).

usage: make_landmarks.py MESH.off OUT.landmarks.txt [K=20] [ANGLE=0.1] [SEED=3]
"""
import math
import random
import sys


def read_off_vertices(path):
    with open(path) as f:
        tokens = [t for line in f for t in line.split('#')[0].split()]
    if tokens[0] != 'OFF':
        raise SystemExit(f'{path}: not an OFF file')
    nv = int(tokens[1])
    xs = tokens[4:4 + 3 * nv]
    return [tuple(float(v) for v in xs[3 * i:3 * i + 3]) for i in range(nv)]


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    mesh, out = sys.argv[1], sys.argv[2]
    k = int(sys.argv[3]) if len(sys.argv) > 3 else 20
    angle = float(sys.argv[4]) if len(sys.argv) > 4 else 0.1
    seed = int(sys.argv[5]) if len(sys.argv) > 5 else 3
    v = read_off_vertices(mesh)
    c = [sum(p[a] for p in v) / len(v) for a in range(3)]
    if not 0 < k <= len(v):
        raise SystemExit(f'{mesh}: cannot draw {k} landmarks from {len(v)} vertices')
    rng = random.Random(seed)
    chosen = sorted(rng.sample(range(len(v)), k))
    ca, sa = math.cos(angle), math.sin(angle)
    with open(out, 'w') as f:
        f.write(f'# {k} landmarks of {mesh}: own direction rotated by {angle} rad about z (seed {seed})\n')
        for i in chosen:
            x, y, z = (v[i][a] - c[a] for a in range(3))
            r = math.sqrt(x * x + y * y + z * z)
            x, y, z = x / r, y / r, z / r
            f.write(f'{i} {ca * x - sa * y:.17g} {sa * x + ca * y:.17g} {z:.17g}\n')


if __name__ == '__main__':
    main()
