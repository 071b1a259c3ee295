#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Remeshing quality through the five routes of paper 000's Table 7.

Runs `dem remesh MESH --via ROUTE --vertices N` (default population: the input
face areas, i.e. area-preserving maps, as in the paper's remeshing experiment;
EDEM and EDEQ get the radii of MESH.params.txt, else the radii ECM used)
for every mesh and route and prints a Markdown table of delta_shape / delta_size,
with the remeshing time (after the map) and the map's own seconds.

  remesh_table.py [--dem build/bin/dem] [--data ../shared/data] [--vertices 8500]
                  [--meshes maxplanck,brain_landmarks,...] [--routes spherical-conformal,...]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROUTES = ["spherical-conformal", "ellipsoidal-conformal", "sdem", "edem", "edeq"]
LABELS = {"spherical-conformal": "SCM", "ellipsoidal-conformal": "ECM", "sdem": "SDEM", "edem": "EDEM", "edeq": "EDEQ"}
MESHES = ["maxplanck", "twistedball", "brain_landmarks", "david_enlarge", "sphere_landmarks",
          "edem_ellipsoid1", "edem_ellipsoid2", "edem_ellipsoid3", "edem_sphere",
          "edeq_ellipsoid1", "edeq_ellipsoid2", "edeq_ellipsoid3", "edeq_sphere"]


def params_radii(mesh, route):
    """Radii from MESH.params.txt (a, b, c for EDEM; a0, b0, c0, the initial radii, for EDEQ)."""
    path = mesh[:-4] + ".params.txt"
    if not os.path.exists(path):
        return None
    values = {}
    for line in open(path):
        if "=" in line:
            k, v = line.split("=", 1)
            values[k.strip()] = float(v)
    keys = ["a0", "b0", "c0"] if route == "edeq" and "a0" in values else ["a", "b", "c"]
    return [values[k] for k in keys] if all(k in values for k in keys) else None


def run(dem, mesh, route, vertices, timeout, radii=None):
    with tempfile.TemporaryDirectory() as tmp:
        metrics = os.path.join(tmp, "m.json")
        cmd = [dem, "remesh", mesh, "--via", route, "--vertices", str(vertices), "--metrics", metrics, "--quiet"]
        if radii:
            cmd += ["--radii"] + ["%.17g" % r for r in radii]
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return None, "timeout"
        if p.returncode != 0:
            return None, "exit %d: %s" % (p.returncode, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "")
        with open(metrics) as f:
            return json.load(f), ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dem", default="build/bin/dem")
    ap.add_argument("--data", default="../shared/data")
    ap.add_argument("--vertices", type=int, default=8500)
    ap.add_argument("--meshes", default=",".join(MESHES))
    ap.add_argument("--routes", default=",".join(ROUTES))
    ap.add_argument("--timeout", type=float, default=900)
    a = ap.parse_args()
    routes = a.routes.split(",")
    print("| surface | " + " | ".join(LABELS.get(r, r) for r in routes) + " |")
    print("|---|" + "---|" * len(routes))
    notes = []
    for name in a.meshes.split(","):
        cells = []
        ecm_radii = None  # EDEM and EDEQ need radii: the mesh's parameters, else those ECM chose
        for r in routes:
            mesh = os.path.join(a.data, name + ".off")
            radii = (params_radii(mesh, r) or ecm_radii) if r in ("edem", "edeq") else None
            m, why = run(a.dem, mesh, r, a.vertices, a.timeout, radii)
            if m is not None and r == "ellipsoidal-conformal":
                ecm_radii = m.get("radii")
            if m is None:
                cells.append("failed")
                notes.append("%s via %s: %s" % (name, r, why))
            else:
                cells.append("%.3f / %.2f (%.2f s + %.2f s)" % (m["delta_shape"], m["delta_size"], m["seconds"],
                                                                 m["remesh_seconds"]))
            sys.stderr.write("%s %s %s\n" % (name, r, cells[-1]))
        print("| %s | %s |" % (name, " | ".join(cells)))
        sys.stdout.flush()
    for n in notes:
        print("\n- " + n)


if __name__ == "__main__":
    main()
