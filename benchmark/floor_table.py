#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# This file is part of Density_equalizing_maps, a third-party CGAL package.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Each method's time as a multiple of the floor: one sparse factorization.

For every mesh, runs build/bin/factorization_floor (median full and
numeric-only factorization of the pinned cotangent Laplacian with the
package's default solver, and the full one with the cheap ordering the
conformal maps use), then `dem` once per method and repeat, interleaved
(method A, B, C, A, B, C, ...: this machine drifts by tens of percent from
minute to minute), and prints a Markdown table of medians with each method's
mapping time ("seconds" of the metrics JSON) divided by the full
factorization.

  python3 benchmark/floor_table.py MESH.off [MESH2.off ...] [--repeat 5]
      [--methods spherical-conformal spherical-conformal:--mobius ellipsoidal-conformal sdem]
      [--torus R r]   (then the default methods are tdem and toroidal-parameterization)
      [--old-build-dir DIR]  (also runs DIR/bin/dem, interleaved with the new one
                              run by run, and prints its median and peak memory)
      [--dem-threads 1 2]    (runs the new dem once per thread count, with
                              --threads N, interleaved; default: dem's own, every core)

The median CPU time of the mapping (from dem's summary line; one thread:
on a busy machine closer to the unloaded wall time than the wall time) is
printed beside the wall time. The peak resident memory of each dem run (the process's maximum RSS, from
wait4) is printed as MiB and bytes per face (the largest over the repeats).

A method may carry dem options after a colon, separated by commas:
"spherical-conformal:--mobius", "edem:--radii,1,1,2".
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile


def run_floor(exe, mesh, repeat):
    out = subprocess.run([exe, mesh, str(repeat)], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def run_dem(dem, method_spec, mesh, extra, threads):
    """(seconds of the mapping, its CPU seconds, peak RSS in bytes, exit status)."""
    name, _, opts = method_spec.partition(":")
    args = [dem[0], name, mesh] + [o for o in opts.split(",") if o] + dem[1] + extra
    env = dict(os.environ)
    if threads:
        for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
            env[k] = str(threads)
    with tempfile.NamedTemporaryFile(suffix=".json") as m:
        with tempfile.TemporaryFile(mode="w+") as out:
            p = subprocess.Popen(args + ["--metrics", m.name, "--quiet"], stdout=out,
                                 stderr=subprocess.DEVNULL, env=env)
            _, status, usage = os.wait4(p.pid, 0)
            out.seek(0)
            summary = out.read()
        p.returncode = os.waitstatus_to_exitcode(status)
        rss = usage.ru_maxrss * 1024  # kilobytes on Linux
        if p.returncode != 0:
            return None, None, rss, p.returncode
        # the summary line says "(X s CPU)": the mapping's CPU time, a better
        # estimate of its unloaded wall time on a busy machine (one thread)
        cpu = re.search(r"\(([0-9.eE+-]+) s CPU\)", summary)
        with open(m.name) as f:
            return json.load(f)["seconds"], float(cpu.group(1)) if cpu else float("nan"), rss, 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--methods", nargs="+")
    ap.add_argument("--torus", nargs=2, metavar=("R", "r"))
    ap.add_argument("--build-dir", default=os.environ.get("DEM_BUILD_DIR", "build"))
    ap.add_argument("--threads", type=int, default=0, help="OMP/BLAS threads for dem (0: leave as is)")
    ap.add_argument("--old-build-dir", help="a build of the old sources: its dem runs interleaved with the new one")
    ap.add_argument("--dem-threads", type=int, nargs="+",
                    help="run the new dem with --threads N for each N (its parallel loops)")
    a = ap.parse_args()
    floor_exe = os.path.join(a.build_dir, "bin", "factorization_floor")
    new_dem = os.path.join(a.build_dir, "bin", "dem")
    if a.dem_threads:
        builds = [(f"new, {n} thread{'s' if n > 1 else ''}", (new_dem, ["--threads", str(n)])) for n in a.dem_threads]
    else:
        builds = [("new", (new_dem, []))]
    if a.old_build_dir:
        builds.append(("old", (os.path.join(a.old_build_dir, "bin", "dem"), [])))
    extra = ["--torus", a.torus[0], a.torus[1]] if a.torus else []
    methods = a.methods or (["tdem", "toroidal-parameterization"] if a.torus else
                            ["spherical-conformal", "spherical-conformal:--mobius", "ellipsoidal-conformal", "sdem"])
    runs = [(b, m) for m in methods for b, _ in builds]
    print("| mesh | faces | full factorization (s) | numeric only (s) | full, fast ordering (s) | method | build | "
          "median (s) | x floor | median CPU (s) | peak RSS (MiB) | B/face |")
    print("|---|---:|---:|---:|---:|---|---|---:|---:|---:|---:|---:|")
    for mesh in a.meshes:
        floor = run_floor(floor_exe, mesh, a.repeat)
        times = {r: [] for r in runs}
        cpus = {r: [] for r in runs}
        peak = {r: 0 for r in runs}
        failed = {}
        for _ in range(a.repeat):
            for m in methods:
                for b, dem in builds:
                    r = (b, m)
                    if r in failed:
                        continue
                    t, cpu, rss, rc = run_dem(dem, m, mesh, extra, a.threads)
                    peak[r] = max(peak[r], rss)
                    if t is None:
                        failed[r] = rc
                    else:
                        times[r].append(t)
                        cpus[r].append(cpu)
        full = floor["full_factorization_seconds"]
        faces = floor["faces"]
        for i, (b, m) in enumerate(runs):
            head = (f"| {os.path.basename(mesh)} | {faces} | {full:.3f} | "
                    f"{floor['numeric_factorization_seconds']:.3f} | "
                    f"{floor.get('full_factorization_fast_ordering_seconds', float('nan')):.3f} |"
                    ) if i == 0 else "| | | | | |"
            memory = f"{peak[(b, m)] / 2**20:.0f} | {peak[(b, m)] / faces:.0f}"
            if (b, m) in failed:
                print(f"{head} {m} | {b} | exit {failed[(b, m)]} | | | {memory} |")
            else:
                med = statistics.median(times[(b, m)])
                cpu = statistics.median(cpus[(b, m)])
                print(f"{head} {m} | {b} | {med:.3f} | {med / full:.2f} | {cpu:.3f} | {memory} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
