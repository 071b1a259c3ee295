// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The `dem` command-line contract (DESIGN.md): exit codes, messages on
// stderr, the output mesh (same connectivity, vertices on the domain) and the
// metrics JSON (every key present, parseable). Runs build/bin/dem (DEM_CLI)
// on small generated meshes written to a temporary folder.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Density_equalizing_maps/internal/openblas.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h> // stat, umask
#include <sys/wait.h> // WIFEXITED
#include <unistd.h>   // getpid

#include "dem_cli_runner.h" // Soup, the text-mesh writers, check()

typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point;
using namespace dem_cli_test;

namespace {

const Temporary_folder folder("dem_test_cli");
const fs::path& tmp_dir = folder.path;

// Geodesic icosphere (frequency-2^k Loop-style midpoint subdivision), outward oriented.
Soup icosphere(int subdivisions)
{
  const double t = (1 + std::sqrt(5.)) / 2;
  Soup s;
  s.V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  s.T = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
         {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  auto normalize = [](P3 p) { const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                              return P3{p[0] / n, p[1] / n, p[2] / n}; };
  for(P3& p : s.V) p = normalize(p);
  for(int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if(it != mid.end()) return it->second;
      s.V.push_back(normalize({(s.V[a][0] + s.V[b][0]) / 2, (s.V[a][1] + s.V[b][1]) / 2, (s.V[a][2] + s.V[b][2]) / 2}));
      return mid[key] = int(s.V.size()) - 1;
    };
    std::vector<Tri> T;
    for(const Tri& f : s.T) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      T.push_back({f[0], a, c}); T.push_back({f[1], b, a}); T.push_back({f[2], c, b}); T.push_back({a, b, c});
    }
    s.T = T;
  }
  // a non-round shape: stretch, so that the map is not the identity
  for(P3& p : s.V) { p[0] *= 1.6; p[2] *= 0.8; }
  return s;
}

Soup torus(double R, double r, int nu, int nv) { return torus_soup(R, r, nu, nv); }

std::string write_text(const std::string& name, const std::string& content) { return write_file(folder / name, content); }
std::string write_off(const std::string& name, const Soup& s) { return write_text(name, off_text(s)); }
std::string write_obj(const std::string& name, const Soup& s) { return write_text(name, obj_text(s)); }

std::string read_text(const fs::path& p) { return read_file(p.string()); }

/// Runs `dem ARGS`, capturing stdout and stderr.
Result dem(const std::string& args) { return run_dem(folder, args); }

bool expect(const Result& r, int code, const std::string& what, const std::string& message = "")
{
  bool ok = check(r.code == code, what + ": exit " + std::to_string(r.code) + ", expected " + std::to_string(code) +
                                      " (stderr: " + r.err + ")");
  if(!message.empty())
    ok = check(contains(r.err, message), what + ": stderr should mention \"" + message + "\", got: " + r.err) && ok;
  return ok;
}

const char* metric_keys[] = {"method", "vertices", "faces", "seconds", "iterations", "converged", "fold_overs",
                             "mean_abs_mu", "sd_abs_mu", "mean_abs_darea", "sd_abs_darea", "density_var_initial",
                             "density_var_final", "face_density_var_initial", "face_density_var_final",
                             "landmark_error", "radii"};

/// Parses the metrics file and checks every key of the contract; returns the tree.
boost::property_tree::ptree check_metrics(const std::string& file, const std::string& method, std::size_t nv,
                                          std::size_t nf)
{
  boost::property_tree::ptree pt;
  try {
    boost::property_tree::read_json(file, pt);
  } catch(const std::exception& e) {
    check(false, "metrics " + file + " is not valid JSON: " + e.what());
    return pt;
  }
  for(const char* k : metric_keys) check(pt.count(k) == 1, std::string("metrics key ") + k + " missing");
  check(pt.get<std::string>("method", "") == method, "metrics method");
  check(pt.get<std::size_t>("vertices", 0) == nv, "metrics vertices");
  check(pt.get<std::size_t>("faces", 0) == nf, "metrics faces");
  check(pt.get<std::size_t>("fold_overs", 1) == 0, "metrics fold_overs == 0");
  check(pt.get<double>("seconds", -1) >= 0, "metrics seconds");
  const double mu = pt.get<double>("mean_abs_mu", -1);
  check(mu >= 0 && mu < 1, "metrics mean_abs_mu in [0,1)");
  check(pt.get<double>("mean_abs_darea", -1) >= 0, "metrics mean_abs_darea");
  check(pt.get<double>("density_var_final", -1) >= 0, "metrics density_var_final");
  return pt;
}

/// The output has the input's faces, in order, and its vertices on the domain.
void check_output(const std::string& file, const Soup& in, double (*domain_residual)(const Point&),
                  const std::string& what)
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if(!check(CGAL::IO::read_polygon_soup(file, points, polygons), what + ": output readable")) return;
  check(points.size() == in.V.size(), what + ": same number of vertices");
  bool same = polygons.size() == in.T.size();
  for(std::size_t k = 0; same && k < polygons.size(); ++k)
    same = polygons[k].size() == 3 && int(polygons[k][0]) == in.T[k][0] && int(polygons[k][1]) == in.T[k][1] &&
           int(polygons[k][2]) == in.T[k][2];
  check(same, what + ": same connectivity");
  double worst = 0;
  for(const Point& p : points) worst = std::max(worst, domain_residual(p));
  check(worst < 1e-9, what + ": vertices on the domain (worst residual " + std::to_string(worst) + ")");
}

double torus_3_1_residual(const Point& p)
{
  const double x = CGAL::to_double(p.x()), y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
  const double d = std::sqrt(x * x + y * y) - 3;
  return std::abs(std::sqrt(d * d + z * z) - 1);
}

double ellipsoid_2_1_1_residual(const Point& p)
{
  const double x = CGAL::to_double(p.x()) / 2, y = CGAL::to_double(p.y()), z = CGAL::to_double(p.z());
  return std::abs(std::sqrt(x * x + y * y + z * z) - 1);
}

double unit_sphere_residual(const Point& p) { return std::abs(std::sqrt(CGAL::to_double(p.x() * p.x() + p.y() * p.y() + p.z() * p.z())) - 1); }

} // namespace

int main()
{

  const Soup sphere = icosphere(3); // 642 vertices, 1280 faces
  const std::string sphere_off = write_off("sphere.off", sphere);
  const std::string sphere_obj = write_obj("sphere.obj", sphere);
  const std::string metrics = (tmp_dir / "metrics.json").string();
  const std::string output = (tmp_dir / "out.off").string();

  // --- dem --version names OpenBLAS's kernels. On a CPU with AVX2 and FMA they
  // are never ones without AVX: dem starts again with this CPU's kernels when
  // OpenBLAS fell back for a model it does not know (internal/openblas.h),
  // unless OPENBLAS_CORETYPE was set by the caller.
  {
    Result r = dem("--version");
    expect(r, 0, "dem --version");
    const std::string key = "OpenBLAS kernels: ";
    const std::size_t at = r.out.find(key);
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
    __builtin_cpu_init();
    if(at != std::string::npos && !std::getenv("OPENBLAS_CORETYPE") && __builtin_cpu_supports("avx2") &&
       __builtin_cpu_supports("fma")) {
      std::string kernels = r.out.substr(at + key.size());
      kernels = kernels.substr(0, kernels.find_first_of(" \n"));
      check(!CGAL::Density_equalizing_maps::internal::openblas_core_without_avx(kernels),
            "dem runs OpenBLAS's kernels of this CPU, not " + kernels);
    }
#endif
  }

  // --- a valid run: output, metrics, summary line
  {
    Result r = dem("spherical-conformal \"" + sphere_off + "\" --output \"" + output + "\" --metrics \"" + metrics + "\"");
    if(expect(r, 0, "spherical-conformal on an icosphere")) {
      check(!r.out.empty() && contains(r.out, "spherical-conformal"), "one-line summary on stdout");
      check_metrics(metrics, "spherical-conformal", sphere.V.size(), sphere.T.size());
      check_output(output, sphere, unit_sphere_residual, "spherical-conformal output");
      // written through a temporary file, yet with the permissions of any new
      // file (0666 less the umask), not the temporary's owner-only 0600
      const mode_t mask = ::umask(0);
      ::umask(mask);
      struct stat st;
      check(::stat(output.c_str(), &st) == 0 && (st.st_mode & 0777) == (0666 & ~mask),
            "the output has the permissions of a new file (0666 less the umask)");
      check(::stat(metrics.c_str(), &st) == 0 && (st.st_mode & 0777) == (0666 & ~mask),
            "the metrics file has the permissions of a new file (0666 less the umask)");
    }
    fs::remove(output);
    fs::remove(metrics);
    r = dem("spherical-conformal \"" + sphere_obj + "\" --mobius --output \"" + output + "\"");
    if(expect(r, 0, "spherical-conformal --mobius on an OBJ file"))
      check_output(output, sphere, unit_sphere_residual, "OBJ input, --mobius output");
  }

  // --- invalid meshes: exit 3 with a message naming the problem
  {
    const Soup triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
    expect(dem("spherical-conformal \"" + write_off("triangle.off", triangle) + "\""), 3, "single triangle");

    Soup open = icosphere(1);
    open.T.pop_back();
    expect(dem("spherical-conformal \"" + write_off("open.off", open) + "\""), 3, "icosphere with a hole",
           "boundary");

    // three triangles on the edge (0,1)
    const Soup fin{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
    expect(dem("spherical-conformal \"" + write_off("fin.off", fin) + "\""), 3, "non-manifold edge", "non-manifold");

    const Soup ring = torus(3, 1, 16, 8);
    expect(dem("spherical-conformal \"" + write_off("torus.off", ring) + "\""), 3, "genus-1 mesh for a sphere method",
           "genus");

    expect(dem("spherical-conformal \"" + (tmp_dir / "missing.off").string() + "\""), 3, "missing file");
    expect(dem("spherical-conformal \"" + write_text("garbage.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n") + "\""), 3,
           "unreadable file");
  }

  // --- usage errors: exit 2
  {
    expect(dem("conformal-thing \"" + sphere_off + "\""), 2, "unknown method", "unknown method");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --frobnicate"), 2, "unknown option", "unknown option");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --output"), 2, "missing option value", "needs");
    expect(dem("sdem \"" + sphere_off + "\" --time-step abc"), 2, "unreadable number", "not a number");
    expect(dem("spherical-conformal"), 2, "missing INPUT", "INPUT");
    expect(dem("sdem \"" + sphere_off + "\" --max-iterations 1.5"), 2, "non-integer iteration count");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --threads 0"), 2, "zero threads", "--threads");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --threads"), 2, "--threads without a number", "--threads");
  }

  // --- --threads: the map is the same, to the last printed digit, on one thread and on two
  {
    const std::string one = (tmp_dir / "one_thread.off").string(), two = (tmp_dir / "two_threads.off").string();
    const Soup fine = icosphere(5); // 20,480 faces: several blocks of the parallel loops
    const std::string fine_off = write_off("fine_sphere.off", fine);
    // --threads 1 also holds OpenBLAS to one thread, whose factorizations
    // differ in the last bits from its multithreaded ones: both runs get one
    // BLAS thread here, so that the comparison is that of the loops.
    const std::string one_blas_thread = "env OPENBLAS_NUM_THREADS=1";
    auto sdem = [&](const std::string& threads, const std::string& output) {
      return run_dem(folder, "sdem \"" + fine_off + "\" --quiet --threads " + threads + " --output \"" + output + "\"",
                     120, one_blas_thread);
    };
    if(expect(sdem("1", one), 0, "sdem --threads 1") && expect(sdem("2", two), 0, "sdem --threads 2"))
      check(read_text(one) == read_text(two), "sdem --threads 1 and --threads 2 write the same file");

    // --threads 1 runs on one thread, the sparse factorizations included,
    // whatever the environment says of the BLAS and OpenMP: the mapping's CPU
    // time (all threads; the summary line's "(Y s CPU)") is not above its
    // wall time. OpenBLAS and CHOLMOD's OpenMP regions used to run their own
    // threads (benchmark/RESULTS.md, "The single-threaded mode").
    const Result r = run_dem(folder, "sdem \"" + fine_off + "\" --quiet --threads 1", 120,
                             "env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT");
    std::smatch m;
    const std::regex times("([0-9.]+) s \\(([0-9.]+) s CPU\\)");
    if(expect(r, 0, "sdem --threads 1 without thread variables") &&
       check(std::regex_search(r.out, m, times), "sdem prints its wall and CPU time (" + r.out + ")")) {
      const double wall = std::stod(m[1]), cpu = std::stod(m[2]);
      check(cpu <= 1.02 * wall + 0.01, "sdem --threads 1: CPU time " + m[2].str() + " s within its wall time " +
                                         m[1].str() + " s (one thread)");
    }
  }

  // --- sidecar files: exit 3, the message names the line
  {
    std::string lines;
    for(std::size_t k = 0; k < sphere.T.size(); ++k) lines += (k == 2 ? "1.0 oops\n" : "1.0\n");
    Result r = dem("spherical-conformal \"" + sphere_off + "\" --population \"" + write_text("bad.pop", lines) + "\"");
    expect(r, 3, "malformed population line", "line 3");

    std::string short_pop;
    for(std::size_t k = 0; k + 1 < sphere.T.size(); ++k) short_pop += "2.5\n";
    expect(dem("spherical-conformal \"" + sphere_off + "\" --population \"" + write_text("short.pop", short_pop) + "\""),
           3, "population of the wrong length", std::to_string(sphere.T.size() - 1) + " values");

    std::string negative = "# comment line\n\n";
    for(std::size_t k = 0; k < sphere.T.size(); ++k) negative += (k == 5 ? "-1\n" : "1\n");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --population \"" + write_text("neg.pop", negative) + "\""),
           3, "non-positive population", "line 8");

    std::string good;
    for(std::size_t k = 0; k < sphere.T.size(); ++k) good += (k % 7 == 0 ? "3\n" : "1 # weight\n");
    expect(dem("spherical-conformal \"" + sphere_off + "\" --population \"" + write_text("good.pop", good) + "\""), 0,
           "valid population with comments");

    const std::string bad_landmarks = write_text("bad.lm", "# v x y z\n0 1 0 0\n99999 0 1 0\n");
    r = dem("lsdem \"" + sphere_off + "\" --landmarks \"" + bad_landmarks + "\"");
    expect(r, 3, "landmark index out of range", "out of range");
    const std::string malformed_landmarks = write_text("malformed.lm", "0 1 0 0\n5 0 1\n");
    r = dem("lsdem \"" + sphere_off + "\" --landmarks \"" + malformed_landmarks + "\"");
    expect(r, 3, "malformed landmark line", "line 2");
  }

  // --- a density-equalizing run with a prescribed population
  {
    std::string pop;
    for(std::size_t k = 0; k < sphere.T.size(); ++k) pop += (sphere.V[sphere.T[k][0]][2] > 0.3 ? "4\n" : "1\n");
    const std::string pop_file = write_text("cap.pop", pop);
    Result r = dem("sdem \"" + sphere_off + "\" --population \"" + pop_file + "\" --max-iterations 30 --output \"" +
                   output + "\" --metrics \"" + metrics + "\"");
    if(expect(r, 0, "sdem on an icosphere")) {
      auto pt = check_metrics(metrics, "sdem", sphere.V.size(), sphere.T.size());
      check(pt.get<double>("density_var_final", 1e9) < pt.get<double>("density_var_initial", 0),
            "sdem lowers the density variance");
      check(pt.get<std::string>("iterations", "null") != "null", "sdem reports iterations");
      check_output(output, sphere, unit_sphere_residual, "sdem output");
    }
  }

  // --- ellipsoid and torus methods
  {
    Result r = dem("ellipsoidal-conformal \"" + sphere_off + "\" --radii 2 1 1 --output \"" + output + "\" --metrics \"" +
                   metrics + "\"");
    if(expect(r, 0, "ellipsoidal-conformal on an icosphere")) {
      auto pt = check_metrics(metrics, "ellipsoidal-conformal", sphere.V.size(), sphere.T.size());
      check(pt.get_child_optional("radii") && pt.get_child("radii").size() == 3, "ellipsoidal-conformal radii");
      check_output(output, sphere, ellipsoid_2_1_1_residual, "ellipsoidal-conformal output");
    }
    expect(dem("edem \"" + sphere_off + "\""), 2, "edem without --radii", "--radii");

    // Exit 4: landmarks asking for a mirror image (orientation reversing) with
    // a large weight leave fold-overs (no orientation-preserving map can meet
    // them). The metrics are written, the output is not.
    std::string mirror;
    for(std::size_t i = 0; i < sphere.V.size(); i += 3) {
      const P3& p = sphere.V[i];
      const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      mirror += std::to_string(i) + " " + std::to_string(-p[0] / n) + " " + std::to_string(p[1] / n) + " " +
                std::to_string(p[2] / n) + "\n";
    }
    const std::string mirror_file = write_text("mirror.lm", mirror);
    fs::remove(output);
    fs::remove(metrics);
    r = dem("ellipsoidal-quasiconformal \"" + sphere_off + "\" --landmarks \"" + mirror_file +
            "\" --radii 1 1 1 --lambda 100 --output \"" + output + "\" --metrics \"" + metrics + "\"");
    if(expect(r, 4, "mirrored landmarks: no fold-over-free map", "fold-over")) {
      check(!fs::exists(output), "exit 4: no output written");
      check(fs::exists(metrics), "exit 4: metrics written");
      check(contains(r.err, "fold-over"), "exit 4: stderr explains: " + r.err);
      boost::property_tree::ptree pt;
      try { boost::property_tree::read_json(metrics, pt); } catch(...) { check(false, "exit 4: metrics parse"); }
      // either the folded map itself, or the fold-free fallback that gave up the
      // landmarks (named in the `fallback` key): the metrics say which
      const std::string fallback = pt.get<std::string>("fallback", "");
      check(pt.get<std::size_t>("fold_overs", 0) > 0 || (!fallback.empty() && fallback != "null"),
            "exit 4: metrics report the fold-overs or the fallback");
    }

    const Soup ring = torus(3, 1, 24, 12);
    const std::string ring_off = write_off("ring.off", ring);
    expect(dem("tdem \"" + ring_off + "\""), 2, "tdem without --torus", "--torus");
    r = dem("tdem \"" + ring_off + "\" --torus 3 1 --output \"" + output + "\" --metrics \"" + metrics + "\"");
    if(expect(r, 0, "tdem on a torus")) {
      check_metrics(metrics, "tdem", ring.V.size(), ring.T.size());
      check_output(output, ring, torus_3_1_residual, "tdem output");
    }
    expect(dem("tdem \"" + sphere_off + "\" --torus 3 1"), 3, "genus-0 mesh for a torus method", "genus");
    expect(dem("tdem \"" + ring_off + "\" --torus 1 3"), 3, "R < r", "R > r");
  }

  if(failures()) { std::cerr << failures() << " failure(s)\n"; return 1; }
  std::cout << "test_cli: all checks passed\n";
  return 0;
}
