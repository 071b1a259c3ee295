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

    return 1 if failures else 0


if __name__ == "__main__":
    args = sys.argv[1:]
    dem = None
    if "--dem" in args:
        i = args.index("--dem")
        dem = args[i + 1]
        del args[i:i + 2]
    sys.exit(main(args[0] if args else "formats_out", dem))
