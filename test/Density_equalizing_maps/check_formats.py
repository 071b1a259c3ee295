#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads the files test_formats writes (formats_out/) with third-party readers:
nibabel (FreeSurfer, GIfTI), VTK's Python module (VTK legacy, VTP, OBJ with
texture coordinates) and meshio (PLY, VTK, VTP), plus gifti_tool when it is
installed. Compares the arrays with the values test_formats wrote as text.
Exit 0 = every check passed, 1 = a check failed, 77 = a reader is missing (skipped).

  check_formats.py DIR [--dem PATH_TO_DEM]
"""
import os
import shutil
import subprocess
import sys

try:
    import numpy as np
    import nibabel as nib
    import nibabel.freesurfer as fs
    import meshio
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # a reader is missing: skipped, not failed
    print(f"check_formats: skipped ({e}); install python3-nibabel python3-vtk9 python3-meshio")
    sys.exit(77)

failures = 0


def check(ok, what):
    global failures
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures += 1
    return ok


def close(a, b, tol=1e-12):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and np.allclose(a, b, rtol=tol, atol=tol)


def vtk_cell_array(data, name):
    arr = data.GetCellData().GetArray(name)
    return None if arr is None else vtk_to_numpy(arr)


def main(d, dem):
    face = np.loadtxt(os.path.join(d, "bumpy_sphere_face_data.txt"))
    names = ["population", "density_ratio", "log_area_ratio", "abs_mu"]
    m = face.shape[0]

    # --- PLY through meshio (the CGAL writer's per-face properties)
    ply = meshio.read(os.path.join(d, "bumpy_sphere.ply"))
    tri = ply.cells_dict.get("triangle")
    check(tri is not None and len(tri) == m, f"meshio PLY: {0 if tri is None else len(tri)} triangles")
    for k, n in enumerate(names):
        v = ply.cell_data.get(n)
        check(v is not None and close(v[0], face[:, k]), f"meshio PLY cell data {n}")
    check(all(c in ply.point_data for c in ("red", "green", "blue")), "meshio PLY vertex colours red/green/blue")
    check(all(c in ply.cell_data for c in ("red", "green", "blue")), "meshio PLY face colours red/green/blue")

    # --- VTK legacy through vtk and meshio
    r = vtk.vtkUnstructuredGridReader()
    r.SetFileName(os.path.join(d, "bumpy_sphere.vtk"))
    r.ReadAllScalarsOn()
    r.Update()
    g = r.GetOutput()
    check(g.GetNumberOfCells() == m, f"vtk legacy: {g.GetNumberOfCells()} cells")
    for k, n in enumerate(names):
        check(close(vtk_cell_array(g, n), face[:, k]), f"vtk legacy cell data {n}")
    col = vtk_cell_array(g, "colors")
    check(col is not None and col.shape == (m, 3), "vtk legacy cell colours (m x 3)")
    mv = meshio.read(os.path.join(d, "bumpy_sphere.vtk"))
    for k, n in enumerate(names):
        check(close(np.ravel(mv.cell_data[n][0]), face[:, k]), f"meshio legacy vtk cell data {n}")

    # --- VTP through vtk and meshio
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(d, "bumpy_sphere.vtp"))
    r.Update()
    p = r.GetOutput()
    check(p.GetNumberOfPolys() == m, f"vtk XML PolyData: {p.GetNumberOfPolys()} polygons")
    for k, n in enumerate(names):
        check(close(vtk_cell_array(p, n), face[:, k]), f"vtp cell data {n}")
    check(p.GetCellData().GetScalars() is not None and p.GetCellData().GetScalars().GetName() == "abs_mu",
          "vtp active cell scalars = abs_mu (coloured by mu)")
    fr = vtk_to_numpy(p.GetFieldData().GetArray("color_range"))
    check(close(fr, [0, 1]), f"vtp field color_range = {list(fr)}")
    # (meshio 5 reads .vtu but not .vtp: the VTP file is checked with vtk only)

    # --- OBJ with texture coordinates through vtkOBJReader
    for name, exact in (("sphere_equirectangular.obj", False), ("ellipsoid_equirectangular.obj", False),
                        ("torus_flat.obj", True)):
        r = vtk.vtkOBJReader()
        r.SetFileName(os.path.join(d, name))
        r.Update()
        o = r.GetOutput()
        tc = o.GetPointData().GetTCoords()
        if not check(tc is not None, f"vtkOBJReader {name}: texture coordinates present"):
            continue
        uv = vtk_to_numpy(tc)
        polys = vtk_to_numpy(o.GetPolys().GetData()).reshape(-1, 4)[:, 1:]
        a, b, c = uv[polys[:, 0]], uv[polys[:, 1]], uv[polys[:, 2]]
        area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1]))
        check((area > 0).all(), f"{name}: {len(area)} texture triangles, all positive ({(area <= 0).sum()} not)")
        total = area.sum()
        # flat torus: the layout tiles the cell exactly; equirectangular: up to the
        # v-height of the faces that touch a pole line (see test_formats.cpp)
        v = uv[:, 1][polys]
        top, bottom = (v == 1).any(axis=1), (v == 0).any(axis=1)
        band = (1 - v[top].min() if top.any() else 0) + (v[bottom].max() if bottom.any() else 0)
        tol = 1e-6 if exact else band
        check(abs(total - 1) <= tol, f"{name}: total texture area {total:.6f} (unit square = 1, tolerance {tol:.4f})")

    # --- FreeSurfer through nibabel
    coords, faces = fs.read_geometry(os.path.join(d, "lh.bumpy"))
    gii = nib.load(os.path.join(d, "bumpy.surf.gii"))
    gc, gf = gii.agg_data(("pointset", "triangle"))
    check(coords.shape[1] == 3 and faces.shape[1] == 3, f"nibabel read_geometry: {coords.shape[0]} vertices, {faces.shape[0]} faces")
    check(np.array_equal(coords, gc) and np.array_equal(faces, gf),
          "FreeSurfer and GIfTI files of the same mesh agree (nibabel)")
    curv = fs.read_morph_data(os.path.join(d, "lh.bumpy.curv"))
    check(close(curv, np.loadtxt(os.path.join(d, "lh.bumpy.expected_curv.txt")), 1e-7),
          f"nibabel read_morph_data: {len(curv)} values")
    ps = gii.get_arrays_from_intent("NIFTI_INTENT_POINTSET")[0]
    check(ps.coordsys is not None, "GIfTI POINTSET has a coordinate system")
    shape = nib.load(os.path.join(d, "bumpy.shape.gii"))
    check(close(shape.agg_data(), np.loadtxt(os.path.join(d, "bumpy.expected_shape.txt")), 1e-7),
          "nibabel GIfTI shape data array")

    tool = shutil.which("gifti_tool")
    if tool:
        for f in ("bumpy.surf.gii", "bumpy.shape.gii"):
            res = subprocess.run([tool, "-infile", os.path.join(d, f), "-gifti_test"], capture_output=True, text=True)
            text = (res.stdout + res.stderr).strip()
            check(res.returncode == 0 and "invalid" not in text.lower(), f"gifti_tool -gifti_test {f}: {text}")
    else:
        print("note    gifti_tool not installed (Debian gifti-bin): skipped its validation")

    if dem:
        check_cli(d, dem)
    return 1 if failures else 0


def run_dem(dem, *args):
    res = subprocess.run([dem, *args], capture_output=True, text=True)
    return res.returncode, res.stdout + res.stderr


def check_cli(d, dem):
    """The dem tool on neuroimaging files, read back with nibabel / meshio; format errors."""
    out = os.path.join(d, "cli")
    os.makedirs(out, exist_ok=True)
    coords, faces = fs.read_geometry(os.path.join(d, "lh.bumpy"))
    # dem spherical-conformal lh.white --output lh.sphere / lh.sphere.gii
    rc, text = run_dem(dem, "spherical-conformal", os.path.join(d, "lh.bumpy"), "--output", os.path.join(out, "lh.sphere"),
                       "--quiet")
    check(rc == 0, f"dem spherical-conformal lh.bumpy --output lh.sphere: exit {rc}")
    if rc == 0:
        sc, sf = fs.read_geometry(os.path.join(out, "lh.sphere"))
        r = np.linalg.norm(sc, axis=1)
        check(np.array_equal(sf, faces) and abs(r - 1).max() < 1e-6,
              f"nibabel reads dem's FreeSurfer sphere: same faces, |radius - 1| <= {abs(r - 1).max():.1e}")
    rc, text = run_dem(dem, "spherical-conformal", os.path.join(d, "lh.bumpy"), "--output",
                       os.path.join(out, "lh.sphere.gii"), "--output-scale", "100", "--quiet")
    check(rc == 0, f"dem ... --output lh.sphere.gii --output-scale 100: exit {rc}")
    if rc == 0:
        g = nib.load(os.path.join(out, "lh.sphere.gii"))
        gc, gf = g.agg_data(("pointset", "triangle"))
        r = np.linalg.norm(gc, axis=1)
        check(np.array_equal(gf, faces) and abs(r - 100).max() < 1e-4,
              f"nibabel reads dem's GIfTI sphere: radius 100 to {abs(r - 100).max():.1e}")

    # files nibabel writes (GZipBase64Binary by default) read by dem, with a per-vertex population
    dens = 1 + 0.5 * (coords[:, 2] > 0)
    surf = nib.gifti.GiftiImage(darrays=[
        nib.gifti.GiftiDataArray(coords.astype(np.float32), intent="NIFTI_INTENT_POINTSET"),
        nib.gifti.GiftiDataArray(faces.astype(np.int32), intent="NIFTI_INTENT_TRIANGLE")])
    nib.save(surf, os.path.join(out, "nib.surf.gii"))
    shape = nib.gifti.GiftiImage(darrays=[nib.gifti.GiftiDataArray(dens.astype(np.float32), intent="NIFTI_INTENT_SHAPE")])
    nib.save(shape, os.path.join(out, "nib.shape.gii"))
    enc = surf.darrays[0].encoding
    rc, text = run_dem(dem, "sdem", os.path.join(out, "nib.surf.gii"), "--vertex-population",
                       os.path.join(out, "nib.shape.gii"), "--output", os.path.join(out, "sdem.ply"),
                       "--color-by", "density", "--output-input-colored", os.path.join(out, "input.vtk"), "--quiet")
    check(rc == 0, f"dem sdem nib.surf.gii (nibabel encoding {enc}) --vertex-population nib.shape.gii: exit {rc} {text.strip()[:200]}")
    if rc == 0:
        m = meshio.read(os.path.join(out, "sdem.ply"))
        a, b, c = (coords[faces[:, k]] for k in range(3))
        area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
        expected = area * dens[faces].mean(axis=1)
        check(close(m.cell_data["population"][0], expected, 1e-5),
              "face population = input area x mean corner density (meshio on dem's PLY)")
        dr = np.asarray(m.cell_data["density_ratio"][0])
        check(dr.var(ddof=1) < 1e-2, f"sdem output density ratio close to 1: variance {dr.var(ddof=1):.2e}")
        mi = meshio.read(os.path.join(out, "input.vtk"))
        check(close(np.ravel(mi.cell_data["population"][0]), expected, 1e-5) and close(mi.points, coords, 1e-6),
              "--output-input-colored: the input geometry with the same cell data (meshio)")

    # a negative curv file is not a population
    rc, text = run_dem(dem, "sdem", os.path.join(d, "lh.bumpy"), "--vertex-population", os.path.join(d, "lh.bumpy.curv"))
    check(rc == 3 and "positive" in text, f"negative curv as population: exit {rc}: {text.strip()[:160]}")

    # the torus to an OBJ with flat-torus texture coordinates
    nu, nv = 24, 12
    with open(os.path.join(out, "torus.off"), "w") as f:
        f.write(f"OFF\n{nu * nv} {2 * nu * nv} 0\n")
        for i in range(nu):
            for j in range(nv):
                s_, t_ = 2 * np.pi * i / nu, 2 * np.pi * j / nv
                f.write(f"{(3 + np.cos(t_)) * np.cos(s_)} {(3 + np.cos(t_)) * np.sin(s_)} {np.sin(t_)}\n")
        for i in range(nu):
            for j in range(nv):
                a, b = i * nv + j, ((i + 1) % nu) * nv + j
                c, e = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
                f.write(f"3 {a} {b} {c}\n3 {a} {c} {e}\n")
    rc, text = run_dem(dem, "tdem", os.path.join(out, "torus.off"), "--torus", "3", "1", "--output",
                       os.path.join(out, "torus.obj"), "--quiet")
    check(rc == 0, f"dem tdem torus.off --output torus.obj: exit {rc} {text.strip()[:200]}")
    if rc == 0:
        r = vtk.vtkOBJReader()
        r.SetFileName(os.path.join(out, "torus.obj"))
        r.Update()
        o = r.GetOutput()
        uv = vtk_to_numpy(o.GetPointData().GetTCoords())
        polys = vtk_to_numpy(o.GetPolys().GetData()).reshape(-1, 4)[:, 1:]
        a, b, c = uv[polys[:, 0]], uv[polys[:, 1]], uv[polys[:, 2]]
        area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1]))
        check((area > 0).all() and abs(area.sum() - 1) < 1e-6,
              f"dem's torus OBJ: {len(area)} texture triangles, {(area <= 0).sum()} not positive, total {area.sum():.9f}")

    # format errors come before the work
    rc, text = run_dem(dem, "spherical-conformal", os.path.join(d, "lh.bumpy"), "--output", os.path.join(out, "x.xyz"))
    check(rc == 2 and "cannot tell the format" in text and not os.path.exists(os.path.join(out, "x.xyz")),
          f"unknown output extension: exit {rc}: {text.strip()[:120]}")
    with open(os.path.join(out, "mesh.vtp"), "w") as f:
        f.write("<VTKFile/>")
    rc, text = run_dem(dem, "spherical-conformal", os.path.join(out, "mesh.vtp"))
    check(rc == 3 and "built with VTK" in text and "PLY" in text, f"VTK XML input: exit {rc}: {text.strip()[:160]}")
    rc, text = run_dem(dem, "sdem", "--help")
    check(rc == 0 and "default 0.001" in text and "examples:" in text and ".gii" in text,
          "dem sdem --help: defaults, formats, examples")


if __name__ == "__main__":
    args = sys.argv[1:]
    dem = None
    if "--dem" in args:
        i = args.index("--dem")
        dem = args[i + 1]
        del args[i:i + 2]
    sys.exit(main(args[0] if args else "formats_out", dem))
