#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Renders triangle meshes (OFF, or ASCII PLY) side by side into a PNG, for the manual's figures.

Pure Python 3 (no numpy, no matplotlib): orthographic view, z-buffer, flat
Lambert shading, 2x supersampling, PNG written with zlib.

  render_mesh.py OUT.png PANEL [PANEL ...] [--size S] [--title-free]

PANEL is `mesh.off` (or `mesh.ply`: an ASCII PLY with per-face red/green/blue, such as
`dem --output x.ply` writes, is drawn in its own colours unless a colour option is given)
followed by comma-separated options:
  ref=input.off     colour faces by the log area ratio log((|f(T)|/sum)/(|T|/sum)),
                    mesh = the map f, ref = the input (same connectivity);
                    blue = shrunk, white = preserved, red = enlarged
  values=file.txt   colour faces by log(value) (one value per face), sequential colour map
  density=pop.txt   colour faces by log(density / mean density), density = population /
                    face area of this mesh (blue = sparse, white = mean, red = dense):
                    a density-equalizing map turns the whole output white
  area_of=mesh.off  with density=: use the face areas of that mesh (e.g. the input mesh,
                    to show on a map where the dense regions of the input went)
  az=DEG, el=DEG    view direction (azimuth about z, elevation); default az=30, el=20
  look=dense        view from the direction of the densest 5% of the faces (density=;
                    densities from the areas of look_ref=mesh.off, else area_of=, else this mesh)
  up=x|y|z          the axis drawn vertically (default z)
  edges=1           draw the mesh edges (shows how a map deforms a regular mesh)
  color=RRGGBB      uniform colour (default light grey)
  landmarks=L.txt   mark the landmark vertices (lines `vertex x y z`) with black dots and,
                    with targets=1, their target points (x, y, z) with green rings;
                    markers hidden by the mesh are not drawn, except those less than
                    hidden_depth=H (default 0.03) times the panel extent behind the surface
  range=R           half-width of the log colour scale (default 1.5; values=: automatic)
"""
import math
import struct
import sys
import zlib


def read_ply(path):
    """ASCII PLY: vertices x y z, faces as vertex_indices lists; per-face red green blue if present."""
    with open(path) as f:
        if f.readline().strip() != 'ply':
            raise SystemExit(f'{path}: not a PLY file')
        elements, fmt = [], None
        for line in f:
            t = line.split()
            if not t or t[0] in ('comment', 'obj_info'):
                continue
            if t[0] == 'format':
                fmt = t[1]
            elif t[0] == 'element':
                elements.append((t[1], int(t[2]), []))
            elif t[0] == 'property':
                elements[-1][2].append(t[-1] if t[1] != 'list' else ('list', t[-1]))
            elif t[0] == 'end_header':
                break
        if fmt != 'ascii':
            raise SystemExit(f'{path}: only ASCII PLY is rendered')
        V, F, C = [], [], []
        for name, count, props in elements:
            for _ in range(count):
                tok = f.readline().split()
                vals, pos = {}, 0
                for pr in props:
                    if isinstance(pr, tuple):
                        k = int(tok[pos])
                        vals[pr[1]] = [int(x) for x in tok[pos + 1:pos + 1 + k]]
                        pos += 1 + k
                    else:
                        vals[pr] = float(tok[pos])
                        pos += 1
                if name == 'vertex':
                    V.append((vals['x'], vals['y'], vals['z']))
                elif name == 'face':
                    idx = vals.get('vertex_indices', vals.get('vertex_index'))
                    for j in range(1, len(idx) - 1):
                        F.append((idx[0], idx[j], idx[j + 1]))
                        if 'red' in vals:
                            C.append((vals['red'] / 255.0, vals['green'] / 255.0, vals['blue'] / 255.0))
        return V, F, (C if len(C) == len(F) else None)


def read_mesh(path):
    """(V, F, face colours or None) of an OFF or ASCII PLY file."""
    if path.lower().endswith('.ply'):
        return read_ply(path)
    V, F = read_off(path)
    return V, F, None


def read_off(path):
    with open(path) as f:
        tokens = []
        for line in f:
            line = line.split('#', 1)[0].split()
            tokens.extend(line)
    if not tokens[0].endswith('OFF'):
        raise SystemExit(f'{path}: not an OFF file')
    pos = 1
    nv, nf = int(tokens[pos]), int(tokens[pos + 1])
    pos += 3
    V = []
    for _ in range(nv):
        V.append((float(tokens[pos]), float(tokens[pos + 1]), float(tokens[pos + 2])))
        pos += 3
    F = []
    for _ in range(nf):
        k = int(tokens[pos])
        idx = [int(t) for t in tokens[pos + 1:pos + 1 + k]]
        pos += 1 + k
        for j in range(1, k - 1):  # fan-triangulate polygons
            F.append((idx[0], idx[j], idx[j + 1]))
    return V, F


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def face_areas(V, F):
    return [0.5 * norm(cross(sub(V[j], V[i]), sub(V[k], V[i]))) for i, j, k in F]


def lerp_colors(stops, t):
    t = min(max(t, 0.0), 1.0)
    for (t0, c0), (t1, c1) in zip(stops, stops[1:]):
        if t <= t1:
            s = 0 if t1 == t0 else (t - t0) / (t1 - t0)
            return tuple(c0[m] + s * (c1[m] - c0[m]) for m in range(3))
    return stops[-1][1]


DIVERGING = [(0.0, (0.23, 0.30, 0.75)), (0.5, (0.92, 0.92, 0.92)), (1.0, (0.71, 0.02, 0.15))]
SEQUENTIAL = [(0.0, (0.27, 0.00, 0.33)), (0.25, (0.23, 0.32, 0.55)), (0.5, (0.13, 0.57, 0.55)),
              (0.75, (0.37, 0.79, 0.38)), (1.0, (0.99, 0.91, 0.14))]


def read_values(path, n):
    vals = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].strip()
            if line:
                vals.append(float(line.split()[0]))
    if len(vals) != n:
        raise SystemExit(f'{path}: {len(vals)} values for {n} faces')
    return vals


def panel_colors(V, F, opts):
    n = len(F)
    if 'ref' in opts:
        R, RF, _ = read_mesh(opts['ref'])
        if len(RF) != n:
            raise SystemExit('ref mesh has another number of faces')
        a, b = face_areas(V, F), face_areas(R, RF)
        sa, sb = sum(a), sum(b)
        rng = float(opts.get('range', 1.5))
        out = []
        for x, y in zip(a, b):
            d = math.log(max(x / sa, 1e-300) / max(y / sb, 1e-300))
            out.append(lerp_colors(DIVERGING, 0.5 + 0.5 * d / rng))
        return out
    if 'density' in opts:
        # log of the face density relative to the mean density sum(P)/sum(area)
        p = read_values(opts['density'], n)
        a = face_areas(*read_mesh(opts['area_of'])[:2]) if 'area_of' in opts else face_areas(V, F)
        mean = sum(p) / sum(a)
        rng = float(opts.get('range', 1.5))
        return [lerp_colors(DIVERGING, 0.5 + 0.5 * math.log(max(pi / max(ai, 1e-300) / mean, 1e-300)) / rng)
                for pi, ai in zip(p, a)]
    if 'values' in opts:
        logs = [math.log(max(x, 1e-300)) for x in read_values(opts['values'], n)]
        srt = sorted(logs)
        lo, hi = srt[int(0.02 * (n - 1))], srt[int(0.98 * (n - 1))]
        if 'range' in opts:
            mid = 0.5 * (lo + hi)
            lo, hi = mid - float(opts['range']), mid + float(opts['range'])
        span = hi - lo if hi > lo else 1.0
        return [lerp_colors(SEQUENTIAL, (x - lo) / span) for x in logs]
    c = opts.get('color', 'c8c8c8')
    rgb = tuple(int(c[m:m + 2], 16) / 255.0 for m in (0, 2, 4))
    return [rgb] * n


def read_landmarks(path, nv):
    out = []
    with open(path) as f:
        for line in f:
            t = line.split('#', 1)[0].split()
            if t:
                v = int(t[0])
                if not 0 <= v < nv:
                    raise SystemExit(f'{path}: vertex {v} out of range')
                out.append((v, tuple(float(x) for x in t[1:4])))
    return out


def look_at_dense(V, F, opts):
    """Sets az/el so that the area-weighted centroid of the densest faces faces the viewer."""
    n = len(F)
    p = read_values(opts['density'], n)
    ref = opts.get('look_ref', opts.get('area_of'))
    a = face_areas(*read_mesh(ref)[:2]) if ref else face_areas(V, F)
    rho = [pi / max(ai, 1e-300) for pi, ai in zip(p, a)]
    cut = sorted(rho)[int(0.95 * (n - 1))]
    c = [sum(v[m] for v in V) / len(V) for m in range(3)]
    own = face_areas(V, F)
    d = [0.0, 0.0, 0.0]
    for (i, j, k), r, w in zip(F, rho, own):
        if r >= cut:
            for m in range(3):
                d[m] += w * ((V[i][m] + V[j][m] + V[k][m]) / 3 - c[m])
    perm = {'z': (0, 1, 2), 'y': (2, 0, 1), 'x': (1, 2, 0)}[opts.get('up', 'z')]
    x, y, z = d[perm[0]], d[perm[1]], d[perm[2]]
    opts['az'] = math.degrees(math.atan2(-x, -y))
    opts['el'] = math.degrees(math.atan2(z, math.hypot(x, y)))


def view_transform(V, opts):
    az = math.radians(float(opts.get('az', 30)))
    el = math.radians(float(opts.get('el', 20)))
    up = opts.get('up', 'z')
    perm = {'z': (0, 1, 2), 'y': (2, 0, 1), 'x': (1, 2, 0)}[up]
    out = []
    ca, sa, ce, se = math.cos(az), math.sin(az), math.cos(el), math.sin(el)
    for p in V:
        x, y, z = p[perm[0]], p[perm[1]], p[perm[2]]
        # rotate about the vertical axis, then tilt toward the viewer (camera looks along -Y')
        x1, y1 = ca * x - sa * y, sa * x + ca * y
        y2, z2 = ce * y1 - se * z, se * y1 + ce * z
        out.append((x1, z2, y2))  # screen x, screen y (up), depth (larger = farther)
    return out


def draw_disc(img, W, H, x0, pw, cx, cy, r_in, r_out, rgb):
    for py in range(max(int(cy - r_out), 0), min(int(cy + r_out) + 2, H)):
        for px in range(max(int(cx - r_out), x0), min(int(cx + r_out) + 2, x0 + pw)):
            d = math.hypot(px + 0.5 - cx, py + 0.5 - cy)
            if r_in <= d <= r_out:
                q = 3 * (py * W + px)
                img[q:q + 3] = rgb


def render_panel(img, depth, W, H, x0, pw, V, F, colors, opts, markers=()):
    P = view_transform(list(V) + [m[0] for m in markers], opts)
    P, M = P[:len(V)], P[len(V):]
    xs, ys = [p[0] for p in P], [p[1] for p in P]
    cx, cy = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
    ext = max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
    s = 0.92 * min(pw, H) / ext
    S = [(x0 + 0.5 * pw + s * (p[0] - cx), 0.5 * H - s * (p[1] - cy), p[2]) for p in P]
    edges = opts.get('edges', '0') not in ('0', 'no', 'false')
    edge_width = 1.0  # in supersampled pixels
    light = (-0.45, 0.55, -0.70)  # towards the viewer, from the upper left
    ln = norm(light)
    light = tuple(c / ln for c in light)
    for (i, j, k), col in zip(F, colors):
        a, b, c = S[i], S[j], S[k]
        # signed screen area; faces of an outward closed mesh seen from the back are culled
        area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if area2 >= 0:  # screen y points down: front faces have negative area here
            continue
        n3 = cross(sub(P[j], P[i]), sub(P[k], P[i]))
        nn = norm(n3) or 1.0
        lam = max(0.0, -(n3[0] * light[0] + n3[1] * light[1] + n3[2] * light[2]) / nn)
        shade = 0.30 + 0.70 * lam
        rgb = bytes(int(255 * min(1.0, c_ * shade)) for c_ in col)
        minx, maxx = max(int(min(a[0], b[0], c[0])), x0), min(int(max(a[0], b[0], c[0])) + 1, x0 + pw - 1)
        miny, maxy = max(int(min(a[1], b[1], c[1])), 0), min(int(max(a[1], b[1], c[1])) + 1, H - 1)
        inv = 1.0 / area2
        if edges:
            # distance (pixels) from a point to the edge opposite corner m = w_m * |area2| / |edge|
            la = math.hypot(c[0] - b[0], c[1] - b[1]) or 1.0
            lb = math.hypot(a[0] - c[0], a[1] - c[1]) or 1.0
            lc = math.hypot(b[0] - a[0], b[1] - a[1]) or 1.0
            ka, kb, kc = -area2 / la, -area2 / lb, -area2 / lc
            dark = bytes(int(v * 0.55) for v in rgb)
        for py in range(miny, maxy + 1):
            fy = py + 0.5
            row = py * W
            for px in range(minx, maxx + 1):
                fx = px + 0.5
                w0 = ((b[0] - fx) * (c[1] - fy) - (b[1] - fy) * (c[0] - fx)) * inv
                w1 = ((c[0] - fx) * (a[1] - fy) - (c[1] - fy) * (a[0] - fx)) * inv
                w2 = 1.0 - w0 - w1
                if w0 < 0 or w1 < 0 or w2 < 0:
                    continue
                z = w0 * a[2] + w1 * b[2] + w2 * c[2]
                q = row + px
                if z < depth[q]:
                    depth[q] = z
                    if edges and min(w0 * ka, w1 * kb, w2 * kc) < edge_width:
                        img[3 * q:3 * q + 3] = dark
                    else:
                        img[3 * q:3 * q + 3] = rgb
    # markers (point, kind) over the shaded mesh, if not hidden: kind 'dot' or 'ring'
    eps = float(opts.get('hidden_depth', 0.03)) * ext
    for (_, kind), p in sorted(zip(markers, M), key=lambda t: t[0][1] != 'ring'):
        mx, my = x0 + 0.5 * pw + s * (p[0] - cx), 0.5 * H - s * (p[1] - cy)
        px, py = int(mx), int(my)
        if not (x0 <= px < x0 + pw and 0 <= py < H):
            continue
        near = min(depth[yy * W + xx] for yy in range(max(py - 2, 0), min(py + 3, H))
                   for xx in range(max(px - 2, x0), min(px + 3, x0 + pw)))
        if p[2] > near + eps:
            continue
        if kind == 'ring':
            draw_disc(img, W, H, x0, pw, mx, my, 7.0, 10.0, b'\x00\xa0\x00')
        else:
            draw_disc(img, W, H, x0, pw, mx, my, 0.0, 5.0, b'\xff\xff\xff')
            draw_disc(img, W, H, x0, pw, mx, my, 0.0, 3.5, b'\x00\x00\x00')


def write_png(path, W, H, img):
    raw = b''.join(b'\x00' + bytes(img[3 * W * y:3 * W * (y + 1)]) for y in range(H))
    def chunk(tag, data):
        return struct.pack('>I', len(data)) + tag + data + struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def main(argv):
    size = 360
    args = []
    it = iter(argv[1:])
    for a in it:
        if a == '--size':
            size = int(next(it))
        else:
            args.append(a)
    if len(args) < 2:
        raise SystemExit(__doc__)
    out, panels = args[0], args[1:]
    ss = 2  # supersampling
    H, pw = size * ss, size * ss
    W = pw * len(panels)
    img = bytearray(b'\xff' * (3 * W * H))
    depth = [float('inf')] * (W * H)
    for p, spec in enumerate(panels):
        parts = spec.split(',')
        opts = dict(x.split('=', 1) for x in parts[1:])
        V, F, file_colors = read_mesh(parts[0])
        if opts.get('look') == 'dense':
            look_at_dense(V, F, opts)
        markers = []
        if 'landmarks' in opts:
            lm = read_landmarks(opts['landmarks'], len(V))
            if opts.get('targets', '0') not in ('0', 'no', 'false'):
                markers += [(t, 'ring') for _, t in lm]
            markers += [(V[v], 'dot') for v, _ in lm]
        own = file_colors is not None and not any(k in opts for k in ('ref', 'density', 'values', 'color'))
        colors = file_colors if own else panel_colors(V, F, opts)
        render_panel(img, depth, W, H, p * pw, pw, V, F, colors, opts, markers)
    # box-filter down-sampling
    w, h = W // ss, H // ss
    small = bytearray(3 * w * h)
    for y in range(h):
        for x in range(w):
            for ch in range(3):
                acc = 0
                for dy in range(ss):
                    base = 3 * ((y * ss + dy) * W + x * ss) + ch
                    for dx in range(ss):
                        acc += img[base + 3 * dx]
                small[3 * (y * w + x) + ch] = acc // (ss * ss)
    write_png(out, w, h, small)


if __name__ == '__main__':
    main(sys.argv)
