#!/usr/bin/env python3
# Copyright (c) 2026 Density_equalizing_maps contributors.
# This file is part of Density_equalizing_maps, a third-party CGAL package.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark harness: runs build/bin/dem on named meshes several times.

  python3 benchmark/run_benchmarks.py --method spherical-conformal \
      --meshes maxplanck twistedball brain_landmarks bumpy_sphere_100k --repeat 5 --out results.json

For every run it records the exit status, the mapping time reported by dem
(metric "seconds": the mapping only, no file I/O), the CPU time of the mapping
(from dem's summary line), the wall time and CPU time
of the whole process, the peak resident memory of the process (ru_maxrss of
the child, from wait4) and every metric of the JSON contract. It writes one
CSV row per run and a JSON file with the runs, the medians per mesh and the
environment, and prints a table of medians.

Meshes are names of the shared data folder (../shared/data/NAME.off), names of
the generated meshes (bumpy_sphere_100k, bumpy_torus_100k: written by the
make_benchmark_meshes program into BUILD/benchmark_meshes on first use) or
paths to mesh files. Sidecar files sharing the mesh's base name are passed
automatically where the method uses them: NAME.population.txt (--population,
density-equalizing methods), NAME.landmarks.txt (--landmarks), NAME.params.txt
(a b c -> --radii, a0 b0 c0 -> --radii for edeq, R r -> --torus) and
NAME.cut_edges.txt (--cut-edges, toroidal-parameterization).
"""

import argparse
import csv
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

METHODS = ["spherical-conformal", "ellipsoidal-conformal", "ellipsoidal-quasiconformal", "sdem", "lsdem",
           "edem", "edeq", "tdem", "toroidal-parameterization"]
POPULATION_METHODS = {"sdem", "lsdem", "edem", "edeq", "tdem"}
LANDMARK_METHODS = {"lsdem", "ellipsoidal-quasiconformal"}
RADII_METHODS = {"ellipsoidal-conformal", "ellipsoidal-quasiconformal", "edem", "edeq"}
TORUS_METHODS = {"tdem", "toroidal-parameterization"}
GENERATED = {"bumpy_sphere_100k": {}, "bumpy_torus_100k": {"R": 3.0, "r": 1.0}}
METRIC_KEYS = ["method", "vertices", "faces", "seconds", "iterations", "converged", "fold_overs", "mean_abs_mu",
               "sd_abs_mu", "mean_abs_darea", "sd_abs_darea", "density_var_initial", "density_var_final",
               "face_density_var_initial", "face_density_var_final", "landmark_error", "radii"]


def read_params(path):
    """key=value lines with numeric values ('#' comments)."""
    params = {}
    with open(path) as f:
        for n, line in enumerate(f, 1):
            body = line.split("#", 1)[0].strip()
            if not body:
                continue
            if "=" not in body:
                raise ValueError(f"{path} line {n}: expected key=value")
            k, v = body.split("=", 1)
            params[k.strip()] = float(v)
    return params


def resolve_mesh(name, data_dir, build_dir):
    """Returns (mesh path, sidecar base path or None, built-in params)."""
    if os.path.sep in name or os.path.splitext(name)[1]:
        path = os.path.abspath(name)
        return path, os.path.splitext(path)[0], {}
    if name in GENERATED:
        out_dir = os.path.join(build_dir, "benchmark_meshes")
        path = os.path.join(out_dir, name + ".off")
        if not os.path.exists(path):
            gen = os.path.join(build_dir, "bin", "make_benchmark_meshes")
            if not os.path.exists(gen):
                sys.exit(f"{path} is missing and {gen} is not built "
                         f"(cmake --build {build_dir} --target make_benchmark_meshes)")
            os.makedirs(out_dir, exist_ok=True)
            subprocess.run([gen, out_dir], check=True, stdout=subprocess.DEVNULL)
        return path, None, dict(GENERATED[name])
    path = os.path.join(data_dir, name + ".off")
    if not os.path.exists(path):
        sys.exit(f"unknown mesh {name}: {path} does not exist")
    return path, os.path.join(data_dir, name), {}


def sidecar_arguments(method, base, params):
    """The dem options that the mesh's sidecar files provide for this method."""
    args = []
    if base:
        def side(suffix):
            p = base + suffix
            return p if os.path.exists(p) else None
        if method in POPULATION_METHODS and side(".population.txt"):
            args += ["--population", side(".population.txt")]
        if method in LANDMARK_METHODS and side(".landmarks.txt"):
            args += ["--landmarks", side(".landmarks.txt")]
        if method == "toroidal-parameterization" and side(".cut_edges.txt"):
            args += ["--cut-edges", side(".cut_edges.txt")]
        if side(".params.txt"):
            params = {**read_params(side(".params.txt")), **params}
    if method in RADII_METHODS:
        keys = ["a0", "b0", "c0"] if method == "edeq" and "a0" in params else ["a", "b", "c"]
        if all(k in params for k in keys):
            args += ["--radii"] + [repr(params[k]) for k in keys]
    if method in TORUS_METHODS and "R" in params and "r" in params:
        args += ["--torus", repr(params["R"]), repr(params["r"])]
    return args


def run_once(cmd, metrics_path, timeout=None):
    """Runs dem; returns exit code, wall time, CPU time, peak RSS (KiB), metrics, stdout, stderr.
    With a timeout (wall seconds) the run is killed when it exceeds it; the exit code is then "timeout"."""
    if os.path.exists(metrics_path):
        os.remove(metrics_path)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=out, stderr=err)
        timer = threading.Timer(timeout, p.kill) if timeout else None
        if timer:
            timer.start()
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        timed_out = timer is not None and not timer.is_alive() and wall >= timeout
        if timer:
            timer.cancel()
        p.returncode = "timeout" if timed_out else os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read().decode(errors="replace"), err.read().decode(errors="replace")
    metrics = None
    if os.path.exists(metrics_path) and p.returncode != "timeout":
        with open(metrics_path) as f:
            metrics = json.load(f)
    return p.returncode, wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss, metrics, stdout, stderr


def median(values):
    values = [v for v in values if isinstance(v, (int, float)) and v is not None]
    return statistics.median(values) if values else None


def git_commit():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--method", nargs="+", required=True, choices=METHODS)
    ap.add_argument("--meshes", nargs="+", required=True, help="shared-data names, generated names or paths")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--out", default="benchmark_results.json",
                    help="results file (.json or .csv); the other format is written beside it")
    ap.add_argument("--build-dir", default=os.environ.get("DEM_BUILD_DIR", os.path.join(ROOT, "build")))
    ap.add_argument("--dem", help="dem executable (default BUILD/bin/dem)")
    ap.add_argument("--data-dir", default=os.path.join(os.path.dirname(ROOT), "shared", "data"))
    ap.add_argument("--no-sidecars", action="store_true", help="do not pass the meshes' sidecar files")
    ap.add_argument("--threads", type=int, default=None,
                    help="set OMP/OPENBLAS/MKL thread counts of the runs (default: inherit)")
    ap.add_argument("--extra", default="", help="extra dem options, e.g. --extra='--mobius'")
    ap.add_argument("--timeout", type=float, default=None,
                    help="kill a run after this many wall seconds (recorded with exit code 'timeout')")
    a = ap.parse_args()

    dem = a.dem or os.path.join(a.build_dir, "bin", "dem")
    if not os.path.exists(dem):
        sys.exit(f"{dem} not found: build it first (cmake --build {a.build_dir} --target dem)")
    if a.threads:
        for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
            os.environ[v] = str(a.threads)
    version = subprocess.run([dem, "--version"], capture_output=True, text=True).stdout.strip()
    base_out = os.path.splitext(a.out)[0]
    json_path, csv_path = base_out + ".json", base_out + ".csv"
    tmp = tempfile.mkdtemp(prefix="dem_bench_")
    metrics_path = os.path.join(tmp, "metrics.json")

    env = {"host": platform.node(), "cpus": os.cpu_count(), "python": platform.python_version(),
           "dem": os.path.abspath(dem), "dem_version": version, "git_commit": git_commit(),
           "load_average_start": list(os.getloadavg()), "threads": a.threads, "repeat": a.repeat,
           "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    runs, summary = [], []
    for method in a.method:
        for name in a.meshes:
            path, base, params = resolve_mesh(name, a.data_dir, a.build_dir)
            extra = sidecar_arguments(method, None if a.no_sidecars else base, params)
            extra += a.extra.split() if a.extra else []
            cmd = [dem, method, path, "--quiet", "--metrics", metrics_path] + extra
            print("$ " + " ".join(cmd), flush=True)
            mesh_runs = []
            for r in range(a.repeat):
                code, wall, cpu, rss, m, stdout, stderr = run_once(cmd, metrics_path, a.timeout)
                row = {"mesh": name, "method": method, "run": r, "exit_code": code, "wall_seconds": wall,
                       "cpu_seconds": cpu, "peak_rss_kib": rss, "command": " ".join(cmd)}
                faces = (m or {}).get("faces")
                row["peak_rss_bytes_per_face"] = rss * 1024.0 / faces if faces else None
                cpu_match = re.search(r"\(([0-9.]+) s CPU\)", stdout)
                row["map_cpu_seconds"] = float(cpu_match.group(1)) if cpu_match else None
                for k in METRIC_KEYS:
                    row[k] = (m or {}).get(k)
                if code not in (0, 4):
                    row["stderr"] = stderr.strip()
                    print(f"  run {r}: exit {code}: {stderr.strip()}", flush=True)
                runs.append(row)
                mesh_runs.append(row)
                if code == "timeout":
                    print(f"  run {r}: killed after {wall:.0f} s; no further runs of this mesh", flush=True)
                    break
            ok = [x for x in mesh_runs if x["seconds"] is not None]
            s = {"mesh": name, "method": method, "runs": len(mesh_runs),
                 "exit_codes": sorted({x["exit_code"] for x in mesh_runs}, key=str),
                 "vertices": ok[0]["vertices"] if ok else None, "faces": ok[0]["faces"] if ok else None}
            for k in ("seconds", "map_cpu_seconds", "wall_seconds", "cpu_seconds", "peak_rss_kib", "peak_rss_bytes_per_face",
                      "iterations", "fold_overs", "mean_abs_mu", "mean_abs_darea", "density_var_initial",
                      "density_var_final", "face_density_var_final", "landmark_error"):
                s["median_" + k] = median([x[k] for x in mesh_runs])
            s["min_seconds"] = min((x["seconds"] for x in ok), default=None)
            s["radii"] = ok[-1]["radii"] if ok else None
            summary.append(s)

    env["load_average_end"] = list(os.getloadavg())
    with open(json_path, "w") as f:
        json.dump({"environment": env, "summary": summary, "runs": runs}, f, indent=2)
    fields = ["mesh", "method", "run", "exit_code", "map_cpu_seconds", "wall_seconds", "cpu_seconds", "peak_rss_kib",
              "peak_rss_bytes_per_face"] + METRIC_KEYS[1:] + ["command"]
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for row in runs:
            w.writerow({k: json.dumps(v) if isinstance(v, (list, bool)) else v for k, v in row.items()})

    def fmt(v, spec):
        return format(v, spec) if isinstance(v, (int, float)) else "-"
    print(f"\nmedians of {a.repeat} runs ({version}; load average {env['load_average_start'][0]:.2f} -> "
          f"{env['load_average_end'][0]:.2f}, {os.cpu_count()} CPUs)")
    print(f"{'method':<22} {'mesh':<20} {'faces':>7} {'map s':>8} {'min s':>8} {'map cpu':>8} {'wall s':>8} {'cpu s':>8} "
          f"{'MiB':>7} {'B/face':>7} {'iters':>6} {'folds':>5} {'|mu|':>7} {'|darea|':>8} {'var_fin':>9} exit")
    for s in summary:
        print(f"{s['method']:<22} {s['mesh']:<20} {fmt(s['faces'], 'd'):>7} {fmt(s['median_seconds'], '.3f'):>8} "
              f"{fmt(s['min_seconds'], '.3f'):>8} {fmt(s['median_map_cpu_seconds'], '.3f'):>8} "
              f"{fmt(s['median_wall_seconds'], '.3f'):>8} "
              f"{fmt(s['median_cpu_seconds'], '.3f'):>8} "
              f"{fmt(s['median_peak_rss_kib'] / 1024 if s['median_peak_rss_kib'] else None, '.1f'):>7} "
              f"{fmt(s['median_peak_rss_bytes_per_face'], '.0f'):>7} {fmt(s['median_iterations'], '.0f'):>6} "
              f"{fmt(s['median_fold_overs'], '.0f'):>5} {fmt(s['median_mean_abs_mu'], '.4f'):>7} "
              f"{fmt(s['median_mean_abs_darea'], '.4f'):>8} {fmt(s['median_density_var_final'], '.3g'):>9} "
              f"{','.join(map(str, s['exit_codes']))}")
    print(f"\nwrote {json_path} and {csv_path}")
    return 0 if all(set(s["exit_codes"]) <= {0} for s in summary) else 1


if __name__ == "__main__":
    sys.exit(main())
