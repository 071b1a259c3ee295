// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// dem: the command-line front end of the package (contract in DESIGN.md).
//
//   dem METHOD INPUT [options]
//
// Exit status: 0 done; 2 usage error; 3 invalid input (message on stderr);
// 4 the algorithm could not produce a fold-over-free map (the metrics are
// still written, the output mesh is not).
//
// The input is read as a polygon soup and validated on index arrays before a
// halfedge structure is built, so that non-manifold edges or open boundaries,
// which a Surface_mesh cannot even store, are reported as invalid input.
//
// A method is compiled in when its public header exists (__has_include), so
// the tool builds at every stage of the package; other methods answer "not
// available in this build" (exit 2).

#include "dem_support/dem_support.h"

#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#if __has_include(<CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>)
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#define DEM_HAS_SDEM 1
#endif
#if __has_include(<CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>) && !defined(DEM_WITHOUT_ELLIPSOIDAL)
#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#define DEM_HAS_ELLIPSOIDAL_CONFORMAL 1
#endif
#if __has_include(<CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>)
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#define DEM_HAS_EDEM 1
#endif
#if __has_include(<CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>)
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>
#define DEM_HAS_TDEM 1
#endif

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <unistd.h> // isatty

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace DI = CGAL::Density_equalizing_maps::internal;
namespace NP = CGAL::Density_equalizing_maps::parameters;
using namespace dem_cli;

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef Mesh::Face_index Face;
typedef Mesh::Property_map<Vertex, Point_3> Point_map;
typedef Mesh::Property_map<Face, double> Face_value_map;
typedef std::vector<std::pair<Vertex, Point_3>> Landmarks;

namespace {

/// Everything a method needs, read and validated.
struct Problem
{
  Mesh mesh;
  DI::Matrix X;
  DI::Index_matrix F;
  DI::Vector population;                    // per face (input area when --population area / absent)
  Face_value_map population_map;
  bool explicit_population = false;
  Landmarks landmarks;
  std::vector<std::pair<Vertex, Vertex>> cut_edges;
};

/// Prints iterations on stderr once a run has lasted more than a second.
class Progress
{
public:
  explicit Progress(bool quiet) : quiet_(quiet), start_(std::chrono::steady_clock::now()) {}
  ~Progress() { if(printed_ && tty_) std::cerr << std::endl; }
  bool operator()(std::size_t iteration, double error)
  {
    if(quiet_) return true;
    const double t = seconds_since(start_);
    if(t > 1.0 && t - last_ >= 1.0) {
      // one line per second; rewritten in place on a terminal
      std::fprintf(stderr, tty_ ? "\r  iteration %zu, error %.3e, %.1f s   " : "  iteration %zu, error %.3e, %.1f s\n",
                   iteration, error, t);
      std::fflush(stderr);
      last_ = t;
      printed_ = true;
    }
    return true; // never cancel
  }
  std::function<bool(std::size_t, double)> callback() { return [this](std::size_t i, double e) { return (*this)(i, e); }; }

private:
  bool quiet_;
  bool tty_ = isatty(2) != 0;
  bool printed_ = false;
  double last_ = 0;
  std::chrono::steady_clock::time_point start_;
};

/// Wall and CPU time of the mapping section.
struct Stopwatch
{
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double c0 = process_cpu_seconds();
  void stop(double& wall, double& cpu) const { wall = seconds_since(t0); cpu = process_cpu_seconds() - c0; }
};

/// Result of a method run: the image positions and the report.
struct Run
{
  DEM::Map_report report;
  DI::Matrix Y;        // output positions (rows = vertex indices)
  DI::Matrix Y0;       // the method's initial map when dem computed it (else empty)
  double seconds = 0;
  double cpu_seconds = 0; // CPU time (all threads) of the same section
  std::vector<std::string> notes;
};

DI::Matrix to_matrix(const Mesh& mesh, const Point_map& pm)
{
  DI::Matrix Y(mesh.number_of_vertices(), 3);
  for(Vertex v : mesh.vertices()) {
    const Point_3& p = pm[v];
    Y(v.idx(), 0) = p.x(); Y(v.idx(), 1) = p.y(); Y(v.idx(), 2) = p.z();
  }
  return Y;
}

Point_map fresh_point_map(Mesh& mesh, const std::string& name)
{
  return mesh.add_property_map<Vertex, Point_3>(name, Point_3(0, 0, 0)).first;
}

// ---------------------------------------------------------------------------
// Methods. Each one maps problem.mesh and fills Run; it throws
// DEM::Invalid_input on invalid input.

Run run_spherical_conformal(Problem& pb, const Options& opt)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_sphere");
  const Stopwatch watch;
  run.report = DEM::spherical_conformal_map(pb.mesh, out, NP::mobius_area_correction(opt.mobius));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}

#ifdef DEM_HAS_SDEM
// The initial map of SDEM / LSDEM (FLASH + Moebius, the library's default) is
// computed here and handed over, so that the initial density variance is
// measured on the map the iteration actually starts from.
Run run_sdem(Problem& pb, const Options& opt, bool landmark_aligned)
{
  Run run;
  Point_map init = fresh_point_map(pb.mesh, "v:dem_initial");
  Point_map out = fresh_point_map(pb.mesh, "v:dem_sdem");
  Progress progress(opt.quiet);
  const Stopwatch watch;
  DEM::spherical_conformal_map(pb.mesh, init, NP::mobius_area_correction(true));
  const auto common = NP::combine(NP::initial_map(init), NP::progress_callback(progress.callback()),
                                  NP::face_population_map(pb.population_map));
  if(!landmark_aligned) {
    run.report = DEM::spherical_density_equalizing_map(
        pb.mesh, out,
        NP::combine(common, NP::time_step(opt.time_step.value_or(0.1)),
                    NP::stopping_tolerance(opt.tolerance.value_or(1e-3)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(200))));
  } else {
    run.report = DEM::landmark_aligned_spherical_density_equalizing_map(
        pb.mesh, pb.landmarks, out,
        NP::combine(common, NP::time_step(opt.time_step.value_or(0.01)),
                    NP::stopping_tolerance(opt.tolerance.value_or(1e-3)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(200)),
                    NP::density_weight(opt.alpha.value_or(1.)), NP::harmonic_weight(opt.beta.value_or(2.)),
                    NP::landmark_weight(opt.gamma.value_or(5.))));
  }
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y0 = to_matrix(pb.mesh, init);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}
#endif

#ifdef DEM_HAS_ELLIPSOIDAL_CONFORMAL
Run run_ellipsoidal_conformal(Problem& pb, const Options& opt)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_ellipsoid");
  const Stopwatch watch;
  if(opt.radii)
    run.report = DEM::ellipsoidal_conformal_map(
        pb.mesh, out, NP::combine(NP::ellipsoid_radii(*opt.radii), NP::optimize_radii(opt.optimize_radii)));
  else
    run.report = DEM::ellipsoidal_conformal_map(pb.mesh, out, NP::optimize_radii(opt.optimize_radii));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}

// Landmark targets given on the unit sphere (as in the shared *.landmarks.txt
// files, whose coordinates have 4 decimals, hence the tolerance 1e-4, the one
// LSDEM accepts) are normalized and mapped to the ellipsoid by
// (x, y, z) -> (a x, b y, c z). Targets already on the ellipsoid are kept.
Run run_ellipsoidal_quasiconformal(Problem& pb, const Options& opt)
{
  Run run;
  const std::array<double, 3> radii = opt.radii ? *opt.radii : DEM::bounding_box_ellipsoid_radii(pb.mesh);
  auto norm = [](const Point_3& p) { return std::sqrt(CGAL::to_double(p.x() * p.x() + p.y() * p.y() + p.z() * p.z())); };
  auto ellipsoid_level = [&](const Point_3& p) {
    const double x = p.x() / radii[0], y = p.y() / radii[1], z = p.z() / radii[2];
    return std::sqrt(x * x + y * y + z * z);
  };
  bool on_ellipsoid = true, on_unit_sphere = true;
  for(const auto& l : pb.landmarks) {
    on_ellipsoid = on_ellipsoid && std::abs(ellipsoid_level(l.second) - 1) <= 1e-6;
    on_unit_sphere = on_unit_sphere && std::abs(norm(l.second) - 1) <= 1e-4;
  }
  if(!on_ellipsoid && on_unit_sphere) {
    for(auto& l : pb.landmarks) {
      const double s = 1 / norm(l.second);
      l.second = Point_3(radii[0] * s * l.second.x(), radii[1] * s * l.second.y(), radii[2] * s * l.second.z());
    }
    char buf[240];
    std::snprintf(buf, sizeof buf, "the landmark targets lie on the unit sphere: mapped to the ellipsoid "
                  "(%.6g, %.6g, %.6g) by (x, y, z) -> (a x, b y, c z)", radii[0], radii[1], radii[2]);
    run.notes.push_back(buf);
  }
  Point_map out = fresh_point_map(pb.mesh, "v:dem_ellipsoid");
  const Stopwatch watch;
  run.report = DEM::ellipsoidal_quasiconformal_map(
      pb.mesh, pb.landmarks, out,
      NP::combine(NP::ellipsoid_radii(radii), NP::landmark_weight(opt.lambda.value_or(1.))));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}
#endif

#if defined(DEM_HAS_EDEM) && defined(DEM_HAS_ELLIPSOIDAL_CONFORMAL)
// EDEM and EDEQ start from the library's default starting map with the
// (initial) radii; it is computed here and handed over, so that the initial
// density variance is measured on the map the iteration starts from.
Run run_edem(Problem& pb, const Options& opt, bool quasiconformal)
{
  Run run;
  Point_map init = fresh_point_map(pb.mesh, "v:dem_initial");
  Point_map out = fresh_point_map(pb.mesh, "v:dem_edem");
  Progress progress(opt.quiet);
  const std::array<double, 3> radii = *opt.radii;
  const Stopwatch watch;
  const DEM::Map_report start = DEM::ellipsoidal_density_equalizing_initial_map(
      pb.mesh, init, NP::combine(NP::ellipsoid_radii(radii), NP::face_population_map(pb.population_map)));
  if(!opt.quiet) std::cerr << "dem: " << start.message << std::endl;
  const auto common = NP::combine(NP::ellipsoid_radii(radii), NP::initial_map(init),
                                  NP::face_population_map(pb.population_map),
                                  NP::progress_callback(progress.callback()),
                                  NP::time_step(opt.time_step.value_or(0.1)));
  if(!quasiconformal)
    run.report = DEM::ellipsoidal_density_equalizing_map(
        pb.mesh, out,
        NP::combine(common, NP::stopping_tolerance(opt.tolerance.value_or(1e-3)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(300))));
  else
    run.report = DEM::ellipsoidal_density_equalizing_quasiconformal_map(
        pb.mesh, out,
        NP::combine(common, NP::beltrami_weight(opt.alpha.value_or(5.)),
                    NP::stopping_tolerance(opt.tolerance.value_or(1e-5)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(300))));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y0 = to_matrix(pb.mesh, init);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}
#endif

#ifdef DEM_HAS_TDEM
Run run_toroidal(Problem& pb, const Options& opt, bool parameterization)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_torus");
  Progress progress(opt.quiet);
  const auto common = NP::combine(
      NP::torus_radii(*opt.torus), NP::face_population_map(pb.population_map),
      NP::progress_callback(progress.callback()), NP::time_step(opt.time_step.value_or(0.1)),
      NP::stopping_tolerance(opt.tolerance.value_or(1e-2)),
      CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(1000)));
  const Stopwatch watch;
  if(!parameterization)
    run.report = DEM::toroidal_density_equalizing_map(pb.mesh, out, common);
  else if(!pb.cut_edges.empty())
    run.report = DEM::toroidal_parameterization(pb.mesh, out, NP::combine(NP::cut_edges(pb.cut_edges), common));
  else
    run.report = DEM::toroidal_parameterization(pb.mesh, out, common);
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}
#endif

Run run_method(Problem& pb, const Options& opt)
{
  switch(opt.method) {
    case Method::SPHERICAL_CONFORMAL: return run_spherical_conformal(pb, opt);
#ifdef DEM_HAS_SDEM
    case Method::SDEM: return run_sdem(pb, opt, false);
    case Method::LSDEM: return run_sdem(pb, opt, true);
#endif
#ifdef DEM_HAS_ELLIPSOIDAL_CONFORMAL
    case Method::ELLIPSOIDAL_CONFORMAL: return run_ellipsoidal_conformal(pb, opt);
    case Method::ELLIPSOIDAL_QUASICONFORMAL: return run_ellipsoidal_quasiconformal(pb, opt);
#endif
#if defined(DEM_HAS_EDEM) && defined(DEM_HAS_ELLIPSOIDAL_CONFORMAL)
    case Method::EDEM: return run_edem(pb, opt, false);
    case Method::EDEQ: return run_edem(pb, opt, true);
#endif
#ifdef DEM_HAS_TDEM
    case Method::TDEM: return run_toroidal(pb, opt, false);
    case Method::TOROIDAL_PARAMETERIZATION: return run_toroidal(pb, opt, true);
#endif
    default: break;
  }
  throw std::logic_error("method not wired"); // unreachable: checked by method_available()
}

bool method_available(Method m)
{
  switch(m) {
    case Method::SPHERICAL_CONFORMAL: return true;
#ifdef DEM_HAS_SDEM
    case Method::SDEM: case Method::LSDEM: return true;
#endif
#ifdef DEM_HAS_ELLIPSOIDAL_CONFORMAL
    case Method::ELLIPSOIDAL_CONFORMAL: case Method::ELLIPSOIDAL_QUASICONFORMAL: return true;
#endif
#if defined(DEM_HAS_EDEM) && defined(DEM_HAS_ELLIPSOIDAL_CONFORMAL)
    case Method::EDEM: case Method::EDEQ: return true;
#endif
#ifdef DEM_HAS_TDEM
    case Method::TDEM: case Method::TOROIDAL_PARAMETERIZATION: return true;
#endif
    default: return false;
  }
}

// ---------------------------------------------------------------------------
// Input.

/// Reads and validates the mesh (exit 3 on failure, through Invalid_input).
void read_mesh(const Options& opt, Problem& pb)
{
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  {
    std::ifstream probe(opt.input);
    if(!probe) throw DEM::Invalid_input("cannot open " + opt.input);
  }
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(opt.input, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception& e) {
    throw DEM::Invalid_input("cannot read " + opt.input + ": " + e.what());
  }
  if(!ok || polygons.empty())
    throw DEM::Invalid_input("cannot read a mesh from " + opt.input +
                             " (unknown format, syntax error or no face)");
  soup_to_arrays(points, polygons, pb.X, pb.F);
  DI::validate_closed_surface(pb.X, pb.F, domain_of(opt.method) == Domain::TORUS ? 0 : 2,
                              domain_of(opt.method) == Domain::TORUS ? 7 : 4);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, pb.mesh);
  if(pb.mesh.number_of_vertices() != std::size_t(pb.X.rows()) ||
     pb.mesh.number_of_faces() != std::size_t(pb.F.rows()))
    throw DEM::Invalid_input("the mesh could not be built from " + opt.input);
}

void read_sidecars(const Options& opt, Problem& pb)
{
  const std::size_t nv = std::size_t(pb.X.rows()), nf = std::size_t(pb.F.rows());
  if(!opt.population.empty() && opt.population != "area") {
    const std::vector<double> p = DEM::IO::read_face_values(opt.population, nf);
    pb.population = Eigen::Map<const DI::Vector>(p.data(), Eigen::Index(p.size()));
    pb.explicit_population = true;
  } else {
    pb.population = DI::face_areas(pb.X, pb.F);
  }
  pb.population_map = pb.mesh.add_property_map<Face, double>("f:dem_population", 0.).first;
  for(Face f : pb.mesh.faces()) pb.population_map[f] = pb.population[f.idx()];

  if(!opt.landmarks.empty())
    for(const DEM::IO::Indexed_landmark& l : DEM::IO::read_landmarks(opt.landmarks, nv))
      pb.landmarks.emplace_back(Vertex(Mesh::size_type(l.vertex)), Point_3(l.target[0], l.target[1], l.target[2]));
  if(!opt.cut_edges.empty())
    for(const auto& e : DEM::IO::read_vertex_pairs(opt.cut_edges, nv))
      pb.cut_edges.emplace_back(Vertex(Mesh::size_type(e.first)), Vertex(Mesh::size_type(e.second)));
}

DI::Matrix landmark_targets(const Landmarks& l, std::vector<Eigen::Index>& index)
{
  DI::Matrix Q(l.size(), 3);
  index.resize(l.size());
  for(std::size_t k = 0; k < l.size(); ++k) {
    index[k] = Eigen::Index(l[k].first.idx());
    Q(k, 0) = l[k].second.x(); Q(k, 1) = l[k].second.y(); Q(k, 2) = l[k].second.z();
  }
  return Q;
}

bool write_output(const std::string& file, const DI::Matrix& Y, const DI::Index_matrix& F)
{
  std::vector<Point_3> points;
  points.reserve(std::size_t(Y.rows()));
  for(Eigen::Index i = 0; i < Y.rows(); ++i) points.emplace_back(Y(i, 0), Y(i, 1), Y(i, 2));
  std::vector<std::array<std::size_t, 3>> triangles(std::size_t(F.rows()));
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) triangles[k][c] = std::size_t(F(k, c));
  return CGAL::IO::write_polygon_soup(file, points, triangles, CGAL::parameters::stream_precision(17));
}

} // namespace

int main(int argc, char** argv)
{
  Options opt;
  if(argc < 2) { std::cerr << usage_text(); return 2; }
  {
    std::string error;
    const Parse_status s = parse_command_line(argc, argv, opt, error);
    if(s == Parse_status::HELP) { std::cout << usage_text(); return 0; }
    if(s == Parse_status::VERSION) { std::cout << version_text() << std::endl; return 0; }
    if(s == Parse_status::ERROR) {
      std::cerr << "dem: " << error << "\n(dem --help prints the usage)\n";
      return 2;
    }
  }
  if(!method_available(opt.method)) {
    std::cerr << "dem: method " << method_name(opt.method) << " is not available in this build\n";
    return 2;
  }

  Problem pb;
  Run run;
  try {
    read_mesh(opt, pb);
    read_sidecars(opt, pb);
    run = run_method(pb, opt);
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: invalid input: " << e.what() << "\n";
    return 3;
  } catch(const std::bad_alloc&) {
    std::cerr << "dem: out of memory\n";
    return 4;
  } catch(const std::exception& e) {
    std::cerr << "dem: " << method_name(opt.method) << " failed: " << e.what() << "\n";
    return 4;
  }
  for(const std::string& n : run.notes) std::cerr << "dem: " << n << "\n";

  Metric_input mi;
  mi.X = &pb.X; mi.F = &pb.F; mi.Y = &run.Y;
  mi.initial = run.Y0.size() ? &run.Y0 : &pb.X;
  mi.population = &pb.population;
  mi.radii_count = domain_of(opt.method) == Domain::TORUS ? 2 : 3;
  std::vector<Eigen::Index> landmark_index;
  DI::Matrix targets;
  if(!pb.landmarks.empty()) {
    targets = landmark_targets(pb.landmarks, landmark_index);
    mi.landmark_index = &landmark_index;
    mi.landmark_targets = &targets;
  }
  Metrics m = compute_metrics(method_name(opt.method), run.report, run.seconds, mi);
  m.cpu_seconds = run.cpu_seconds;

  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return 3;
  }
  std::cout << summary_line(m) << std::endl;

  const bool failed = run.report.fold_overs > 0 || run.report.termination == DEM::Termination::STALLED;
  if(failed) {
    std::cerr << "dem: " << method_name(opt.method) << " could not produce a fold-over-free map ("
              << run.report.fold_overs << " fold-over(s), " << DEM::to_string(run.report.termination) << ")"
              << (run.report.message.empty() ? "" : ": " + run.report.message) << "; "
              << (opt.output.empty() ? "" : "nothing written to " + opt.output + ", ")
              << (opt.metrics.empty() ? "no metrics requested" : "metrics written to " + opt.metrics) << "\n";
    return 4;
  }
  if(!opt.output.empty() && !write_output(opt.output, run.Y, pb.F)) {
    std::cerr << "dem: cannot write " << opt.output << "\n";
    return 3;
  }
  return 0;
}
