#!/usr/bin/env python3
"""Mutation check: does the test suite catch a deliberate breakage of each
method's defining step?

Each mutation below replaces one exact piece of a library header (the text must
occur exactly once) in a scratch copy of the repository, rebuilds only the test
programs named for it (in a build folder of its own; ccache makes the unchanged
sources cheap), runs their ctest tests and reports which of them failed. A
mutation is *caught* when at least one of its tests fails; a test that is
skipped (exit 77, shared data absent) does not count. The working tree is never
modified.

    python3 scripts/mutation_check.py                 # every mutation
    python3 scripts/mutation_check.py --only mobius_noop tdem_repair_off
    python3 scripts/mutation_check.py --list
    python3 scripts/mutation_check.py --baseline      # also run the tests unmutated first

Options: --work DIR (scratch folder, default /tmp/dem_mutation_check),
--data DIR (shared data, default ../shared/data next to the repository; a
missing folder leaves only the generated-mesh tests), --jobs N (default 2),
--tests T... (run these test programs for every chosen mutation instead of
its own list, e.g. to measure a mutation's effect on the shared meshes).
Exit status 0 if every mutation was caught. The run time is dominated by the
rebuilds: about one to two minutes per test program on two cores.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INTERNAL = "include/CGAL/Density_equalizing_maps/internal/"


class Mutation:
    def __init__(self, name, what, path, old, new, tests):
        self.name, self.what, self.path, self.old, self.new, self.tests = name, what, path, old, new, tests


# The tests listed for a mutation are the programs expected to catch it; their
# `<name>_shared` variants (label shared_data) run too when they exist.
MUTATIONS = [
    Mutation("edeq_radius_search_off",
             "EDEQ: Radii_search_flow::after_step returns before searching the radii",
             INTERNAL + "radii_search_flow.h",
             "    if(n < 2 || n % search_period != 0) return;",
             "    return;",
             ["test_ellipsoidal_density_equalizing", "test_edeq_shared"]),
    Mutation("lsdem_density_term_zero",
             "LSDEM: Landmark_flow::direction scales the density term by 0",
             INTERNAL + "landmark_flow.h",
             "    d *= alpha;",
             "    d *= 0 * alpha;",
             ["test_spherical_density_equalizing", "test_lsdem_shared"]),
    Mutation("chart_repair_skipped",
             "LSDEM: the two-chart LBS repair of a folding step is skipped (untangling and halving kept)",
             INTERNAL + "ellipsoid_domain.h",
             "          ok = m_repair.repair_in_chart(s, m_pole, stats.repairs) && m_repair.repair_in_chart(s, south, stats.repairs);",
             "          ok = true; (void)south;",
             ["test_spherical_density_equalizing", "test_lsdem_shared"]),
    Mutation("untangling_skipped",
             "sphere/ellipsoid domain: the local untangling of a folding step is skipped (only halving left)",
             INTERNAL + "ellipsoid_domain.h",
             "ok = untangle_on_sphere(s, m_F, m_vertex_faces);",
             "ok = false;",
             ["test_spherical_density_equalizing"]),
    Mutation("mobius_noop",
             "Moebius area correction returns its input",
             INTERNAL + "spherical_conformal.h",
             "  const Vector source_area = face_areas(X, F);\n  const Complex_vector z = north_chart(S);",
             "  return S;\n  const Vector source_area = face_areas(X, F);\n  const Complex_vector z = north_chart(S);",
             ["test_spherical_conformal"]),
    Mutation("tdem_repair_off",
             "TDEM: the periodic LBS repair of a folding step is disabled (only step halving left)",
             INTERNAL + "torus_domain.h",
             "if(!repair(y, flagged)) break;",
             "break;",
             ["test_toroidal"]),
    Mutation("fecm_no_conformal_correction",
             "FECM: the conformal correction psi' (LBS of the radial parameterization's Beltrami coefficient) is the identity",
             INTERNAL + "ellipsoidal_conformal.h",
             "    if(!linear_beltrami_solve(c.source, Fo, nu, fixed, c.source, *m_psi_solver, c.image, &m_open_assembler) ||\n"
             "       !c.image.allFinite())",
             "    if(true)",
             ["test_ellipsoidal_conformal"]),
    Mutation("feqcm_landmark_term_off",
             "FEQCM: the landmark term of the landmark-aligned harmonic map has weight 1e-12 lambda",
             INTERNAL + "ellipsoidal_conformal.h",
             "    diag[landmarks[k]] += lambda;\n    rhs.row(landmarks[k]) += lambda * qt.row(k);",
             "    diag[landmarks[k]] += 1e-12 * lambda;\n    rhs.row(landmarks[k]) += 1e-12 * lambda * qt.row(k);",
             ["test_ellipsoidal_conformal"]),
    Mutation("lbs_stiffness_sign",
             "LBS: sign flip of the off-diagonal coefficient of the Beltrami stiffness",
             INTERNAL + "beltrami.h",
             "    const double a2 = -2 * tau / s;",
             "    const double a2 = 2 * tau / s;",
             ["test_operators"]),
]


def run(cmd, cwd=None, log=None):
    with open(log, "a") if log else open(os.devnull, "w") as out:
        out.write("$ " + " ".join(cmd) + "\n")
        out.flush()
        return subprocess.call(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)


def copy_sources(src, dst):
    files = subprocess.check_output(["git", "ls-files", "-co", "--exclude-standard"], cwd=src, text=True).split("\n")
    for f in files:
        if not f or not os.path.isfile(os.path.join(src, f)):
            continue
        os.makedirs(os.path.dirname(os.path.join(dst, f)) or dst, exist_ok=True)
        shutil.copy2(os.path.join(src, f), os.path.join(dst, f))


def ctest_results(build, tests, log, with_shared=True):
    """name -> 'passed' / 'failed' / 'skipped' for the tests (and their _shared
    variants), and the first failed checks (the "FAILED: ..." lines)."""
    names = "|".join(re.escape(t) for t in tests)
    pattern = "^(%s)(_shared)?$" % names if with_shared else "^(%s)$" % names
    out = subprocess.run(["ctest", "--test-dir", build, "-R", pattern, "--output-on-failure"],
                         capture_output=True, text=True)
    ctest_results.failed_checks = [l.strip()[len("FAILED: "):] for l in (out.stdout + out.stderr).split("\n")
                                   if l.strip().startswith("FAILED: ")]
    with open(log, "a") as f:
        f.write(out.stdout + out.stderr)
    res = {}
    for m in re.finditer(r"Test\s+#\d+: (\S+) \.+[ *]*(Passed|\*\*\*Failed|Failed|\*\*\*Skipped|Not Run|\*\*\*Timeout|Exception)",
                         out.stdout):
        status = m.group(2).strip("*")
        res[m.group(1)] = {"Passed": "passed", "Failed": "failed", "Skipped": "skipped"}.get(status, "failed")
    for m in re.finditer(r"Test\s+#\d+: (\S+) \.+[^\n]*Skipped", out.stdout):
        res[m.group(1)] = "skipped"
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="/tmp/dem_mutation_check")
    ap.add_argument("--data", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "data")))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--baseline", action="store_true")
    ap.add_argument("--tests", nargs="*", help="run these test programs instead of each mutation's own")
    ap.add_argument("--generated-only", action="store_true",
                    help="leave out the test_*_shared programs (and the _shared runs): generated meshes only")
    args = ap.parse_args()
    chosen = [m for m in MUTATIONS if not args.only or m.name in args.only]
    if args.tests:
        for m in chosen:
            m.tests = args.tests
    if args.generated_only:
        for m in chosen:
            m.tests = [t for t in m.tests if not t.endswith("_shared")]
    if args.list:
        for m in MUTATIONS:
            print("%-30s %s [%s]" % (m.name, m.what, ", ".join(m.tests)))
        return 0

    src, build = os.path.join(args.work, "src"), os.path.join(args.work, "build")
    log = os.path.join(args.work, "mutation_check.log")
    if os.path.isdir(src):
        shutil.rmtree(src)
    os.makedirs(src)
    copy_sources(ROOT, src)
    open(log, "w").close()
    env_jobs = ["-j%d" % args.jobs]
    if run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DDEM_BUILD_BENCHMARKS=OFF",
            "-DDEM_SHARED_DATA_DIR=" + args.data], log=log) != 0:
        print("configure failed, see " + log)
        return 2
    os.environ.setdefault("OMP_NUM_THREADS", "1")

    def build_and_test(tests):
        # <target>/fast: the test programs only, not the dem tool they depend on.
        # A /fast build does not update the header dependencies it learns, so
        # after the first build a second mutated header would go unseen: the
        # programs' objects are deleted first (ccache recompiles an unchanged
        # source at no cost, a mutated one for real).
        for t in tests:
            obj_dir = os.path.join(build, "test", "Density_equalizing_maps", "CMakeFiles", t + ".dir")
            for root, _, files in os.walk(obj_dir):
                for name in files:
                    if name.endswith(".o"):
                        os.remove(os.path.join(root, name))
        targets = [t + "/fast" for t in tests]
        if run(["cmake", "--build", build] + env_jobs + ["--target"] + targets, log=log) != 0:
            return None
        return ctest_results(build, tests, log, not args.generated_only)

    rows, all_caught = [], True
    if args.baseline:
        tests = sorted({t for m in chosen for t in m.tests})
        t0 = time.time()
        res = build_and_test(tests)
        bad = [n for n, s in (res or {}).items() if s == "failed"]
        print("baseline (%.0f s): %s" % (time.time() - t0, "build failed" if res is None else
                                        ("failing: " + ", ".join(bad) if bad else "all pass")))
        if res is None or bad:
            return 2
    for m in chosen:
        path = os.path.join(src, m.path)
        original = open(path).read()
        if original.count(m.old) != 1:
            print("%s: the text to replace occurs %d times in %s" % (m.name, original.count(m.old), m.path))
            rows.append((m, "pattern not found", [], 0))
            all_caught = False
            continue
        open(path, "w").write(original.replace(m.old, m.new))
        t0 = time.time()
        try:
            res = build_and_test(m.tests)
        finally:
            open(path, "w").write(original)
        seconds = time.time() - t0
        if res is None:
            rows.append((m, "build failed", [], seconds))
            all_caught = False
            continue
        failed = sorted(n for n, s in res.items() if s == "failed")
        skipped = sorted(n for n, s in res.items() if s == "skipped")
        verdict = "caught" if failed else "NOT caught"
        all_caught = all_caught and bool(failed)
        checks = ctest_results.failed_checks
        rows.append((m, verdict, failed, seconds, checks))
        print("%-30s %-10s by %s%s (%.0f s)" % (m.name, verdict, ", ".join(failed) or "-",
                                                 (" ; skipped " + ", ".join(skipped)) if skipped else "", seconds))
        for c in checks[:4]:
            print("    FAILED: " + c)
        sys.stdout.flush()

    print("\n| mutation | breakage | verdict | failing tests | first failed checks | time |\n|---|---|---|---|---|---:|")
    for r in rows:
        checks = "; ".join(c.replace("|", "/") for c in (r[4] if len(r) > 4 else [])[:2])
        print("| `%s` | %s | %s | %s | %s | %.0f s |" % (r[0].name, r[0].what, r[1], ", ".join(r[2]) or "-",
                                                        checks or "-", r[3]))
    print("\nlog: " + log)
    return 0 if all_caught else 1


if __name__ == "__main__":
    sys.exit(main())
