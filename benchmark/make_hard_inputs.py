#!/usr/bin/env python3
"""Generates the hard inputs of issue 14 as OFF files (and population files).

  python3 benchmark/make_hard_inputs.py OUTDIR

Writes: tetra.off, bipyramid.off (10 vertices), icosphere4.off, sliver4.off
(the same sphere with sliver faces of ~1e-4 of the mean area), scaled copies
bumpy_e+100.off / bumpy_e-100.off of bumpy4.off, capsules capsule10/30/100.off,
stretched30.off (1:1:30 bumpy), and step / bump populations of ratios 1e2..1e6
on icosphere4 (pop_step_1eK.txt, pop_bump_1eK.txt) and on a torus.
"""
import math
import os
import sys


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
        for v in V:
            f.write("%.17g %.17g %.17g\n" % tuple(v))
        for t in F:
            f.write("3 %d %d %d\n" % tuple(t))


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def icosphere(s):
    t = (1 + math.sqrt(5)) / 2
    V = [normalize(v) for v in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(s):
        mid = {}

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                mid[k] = len(V)
                V.append(normalize([(V[a][i] + V[b][i]) / 2 for i in range(3)]))
            return mid[k]
        G = []
        for a, b, c in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    return V, F


def area(V, t):
    a, b, c = (V[i] for i in t)
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    x = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    return 0.5 * math.sqrt(sum(q * q for q in x))


def slivered(V, F, fraction=0.02, ratio=1e-4, seed=7):
    """Splits a `fraction` of the edges (a,b) at the point p = a + ratio (b - a)
    on the edge: each of the two faces on the edge becomes a sliver (area
    `ratio` times the face's) and a near copy of itself. The surface does not
    change (p is on the edge), so the unsplit mesh is the sliver-free remesh."""
    import random
    rnd = random.Random(seed)
    V = [list(v) for v in V]
    F = [list(t) for t in F]
    edge_faces = {}
    for k, t in enumerate(F):
        for c in range(3):
            a, b = t[c], t[(c + 1) % 3]
            edge_faces.setdefault((min(a, b), max(a, b)), []).append(k)
    used = set()
    edges = list(edge_faces.keys())
    rnd.shuffle(edges)
    target = int(fraction * len(F))
    done = 0
    for e in edges:
        if done >= target:
            break
        fs = edge_faces[e]
        if any(k in used for k in fs):
            continue
        a, b = e
        p = [V[a][i] + ratio * (V[b][i] - V[a][i]) for i in range(3)]
        ip = len(V)
        V.append(p)
        for k in fs:
            used.add(k)
            t = F[k]
            # rotate so that the edge is (t0,t1) in face order
            while not ({t[0], t[1]} == {a, b}):
                t = t[1:] + t[:1]
            x, y, z = t
            F[k] = [x, ip, z]
            F.append([ip, y, z])
        done += 1
    return V, F


def capsule(L, nr=24, h=None):
    """Capsule of radius 1 and total length L (axis z): a cylinder of length
    L-2 with hemispherical caps, with near-equilateral triangles."""
    h = h or (2 * math.pi / nr)
    V, F = [], []
    rings = []
    # hemisphere rings (south), cylinder rings, hemisphere rings (north)
    ncap = max(2, int(round((math.pi / 2) / h)))
    zs = []
    for i in range(1, ncap):
        th = -math.pi / 2 + i * (math.pi / 2) / ncap
        zs.append((-(L / 2 - 1) + math.sin(th), math.cos(th)))
    ncyl = max(1, int(round((L - 2) / h)))
    for i in range(ncyl + 1):
        zs.append((-(L / 2 - 1) + i * (L - 2) / ncyl, 1.0))
    for i in range(1, ncap):
        th = i * (math.pi / 2) / ncap
        zs.append(((L / 2 - 1) + math.sin(th), math.cos(th)))
    V.append([0, 0, -L / 2])
    for j, (z, r) in enumerate(zs):
        ring = []
        off = 0.5 * (j % 2)
        for k in range(nr):
            ph = 2 * math.pi * (k + off) / nr
            ring.append(len(V))
            V.append([r * math.cos(ph), r * math.sin(ph), z])
        rings.append(ring)
    top = len(V)
    V.append([0, 0, L / 2])
    for k in range(nr):
        F.append([0, rings[0][(k + 1) % nr], rings[0][k]])
    for j in range(len(rings) - 1):
        A, B = rings[j], rings[j + 1]
        for k in range(nr):
            k1 = (k + 1) % nr
            if j % 2 == 0:
                F.append([A[k], A[k1], B[k]])
                F.append([A[k1], B[k1], B[k]])
            else:
                F.append([A[k], B[k1], B[k]])
                F.append([A[k], A[k1], B[k1]])
    last = rings[-1]
    for k in range(nr):
        F.append([top, last[k], last[(k + 1) % nr]])
    return V, F


def bumpy(s, amp=0.25, stretch=(1, 1, 1)):
    V, F = icosphere(s)
    W = []
    for x, y, z in V:
        r = 1 + amp * math.sin(3 * x) * math.sin(2 * y + 0.5) * math.cos(4 * z)
        W.append([r * x * stretch[0], r * y * stretch[1], r * z * stretch[2]])
    return W, F


def tetra():
    return [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]


def bipyramid(k=8):
    V = [[math.cos(2 * math.pi * i / k), math.sin(2 * math.pi * i / k), 0] for i in range(k)]
    V += [[0, 0, 1], [0, 0, -1]]
    F = []
    for i in range(k):
        j = (i + 1) % k
        F.append([i, j, k])
        F.append([j, i, k + 1])
    return V, F


def populations(V, F, ratio, kind):
    out = []
    for t in F:
        c = [sum(V[i][d] for i in t) / 3 for d in range(3)]
        if kind == "step":
            rho = ratio if c[0] > 0.3 else 1.0
        else:
            g = math.exp(-((c[0] - 1) ** 2 + c[1] ** 2 + c[2] ** 2) / 0.18)
            rho = math.exp(math.log(ratio) * g)
        out.append(rho * area(V, t))
    return out


def torus(R=2, r=1, nu=40, nv=20):
    V, F = [], []
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            V.append([(R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v)])
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            F += [[a, b, c], [a, c, d]]
    return V, F


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "hard_inputs"
    os.makedirs(out, exist_ok=True)
    w = lambda name, VF: write_off(os.path.join(out, name), *VF)
    w("tetra.off", tetra())
    w("bipyramid.off", bipyramid())
    ico = icosphere(4)
    w("icosphere4.off", ico)
    w("sliver4.off", slivered(*bumpy(4, 0.15)))
    w("bumpy4_clean.off", bumpy(4, 0.15))
    b = bumpy(4)
    w("bumpy4.off", b)
    for e in (100, -100):
        w("bumpy4_e%+d.off" % e, ([[c * 10.0 ** e for c in v] for v in b[0]], b[1]))
    for L in (10, 30, 100):
        w("capsule%d.off" % L, capsule(L))
    w("stretched30.off", bumpy(4, 0.15, (1, 1, 30)))
    tor = torus()
    w("torus.off", tor)
    for k in (2, 4, 6):
        for kind in ("step", "bump"):
            with open(os.path.join(out, "pop_%s_1e%d.txt" % (kind, k)), "w") as f:
                f.write("\n".join("%.17g" % p for p in populations(*ico, 10.0 ** k, kind)) + "\n")
            with open(os.path.join(out, "torus_pop_%s_1e%d.txt" % (kind, k)), "w") as f:
                f.write("\n".join("%.17g" % p for p in populations([[c / 3 for c in v] for v in tor[0]], tor[1], 10.0 ** k, kind)) + "\n")


if __name__ == "__main__":
    main()
