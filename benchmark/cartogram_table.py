#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# This file is part of Density_equalizing_maps, a third-party CGAL package.
# SPDX-License-Identifier: GPL-3.0-or-later
"""The world population cartogram (issue 17 item 5): time, memory and accuracy.

Runs `dem cartogram` on the shipped Natural Earth countries and their population
(examples/Density_equalizing_maps/data) with all four outputs (GeoJSON, PLY, PNG,
metrics), `--repeat` times per globe size, and prints a Markdown table of medians:
the wall time of the whole command (reading, globe, populations, passes,
correction, boundary transfer, writing), the time before writing (from the
metrics), the peak resident memory (from wait4), and the accuracy of the run
(largest and mean relative area error over the regions covering >= 50 faces,
measured on the output polygons; fold-overs).

  python3 benchmark/cartogram_table.py [--vertices 10000 50000] [--repeat 3]
      [--dem build/bin/dem] [--compare OPTION | --old-dem PATH]

--compare OPTION also runs the same dem with that option (e.g. --single-level),
and --old-dem another build's dem; either is interleaved with the default run by
run (this machine drifts by tens of percent from minute to minute).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "examples", "Density_equalizing_maps", "data")


def run(dem, vertices, extra, folder):
    out = {k: os.path.join(folder, "world." + k) for k in ("geojson", "ply", "png", "json")}
    cmd = [dem, "cartogram", os.path.join(DATA, "countries110.geojson"), "--values",
           os.path.join(DATA, "population.csv"), "--id-property", "adm0_a3", "--value-column", "pop_est",
           "--vertices", str(vertices), "--quiet", "--output-geojson", out["geojson"], "--output", out["ply"],
           "--image", out["png"], "--metrics", out["json"]] + extra
    start = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.monotonic() - start
    p.stdout.close()
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("failed: " + " ".join(cmd))
    with open(out["json"]) as f:
        m = json.load(f)
    return {"wall": wall, "before_writing": m["seconds_before_writing"], "rss_mb": usage.ru_maxrss / 1024,
            "faces": m["faces"], "max": m["max_relative_area_error"], "mean": m["mean_relative_area_error"],
            "folds": m["fold_overs"], "coarse": [c["vertices"] for c in m.get("coarse_globes", [])],
            "iterations": m["correction_iterations"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--vertices", type=int, nargs="+", default=[10000, 50000])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--dem", default=os.path.join(ROOT, "build", "bin", "dem"))
    ap.add_argument("--compare", default=None, help="a dem option to run interleaved, e.g. --single-level")
    ap.add_argument("--old-dem", default=None, help="another build's dem to run interleaved")
    a = ap.parse_args()
    variants = [("default", a.dem, [])]
    if a.compare:
        variants.append((a.compare, a.dem, [a.compare]))
    if a.old_dem:
        variants.append(("old build", a.old_dem, []))
    print("| vertices (faces) | run | wall s (median) | before writing s | peak MiB | largest error | mean error | "
          "fold-overs | coarse globes | correction its |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for v in a.vertices:
            results = {name: [] for name, _, _ in variants}
            for _ in range(a.repeat):
                for name, dem, extra in variants:
                    results[name].append(run(dem, v, extra, folder))
            for name, _, _ in variants:
                r = results[name]
                med = lambda k: statistics.median(x[k] for x in r)
                last = r[-1]
                print(f"| {v} ({last['faces']}) | {name} | {med('wall'):.2f} | {med('before_writing'):.2f} | "
                      f"{max(x['rss_mb'] for x in r):.0f} | {med('max'):.4f} | {med('mean'):.4f} | "
                      f"{max(x['folds'] for x in r)} | {last['coarse']} | {last['iterations']} |", flush=True)


if __name__ == "__main__":
    main()
