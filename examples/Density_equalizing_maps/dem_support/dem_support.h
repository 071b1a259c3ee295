// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Support code of the `dem` command-line tool: command-line parsing, the
// polygon-soup to array conversion, and the metrics of the JSON contract
// (DESIGN.md), computed here and only here.

#ifndef DEM_SUPPORT_DEM_SUPPORT_H
#define DEM_SUPPORT_DEM_SUPPORT_H

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>
#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <sys/resource.h> // getrusage

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace dem_cli {

namespace DI = CGAL::Density_equalizing_maps::internal;

inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU time (user + system, all threads) of the process so far.
inline double process_cpu_seconds()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// ---------------------------------------------------------------------------
// Methods and options

enum class Method
{
  SPHERICAL_CONFORMAL, ELLIPSOIDAL_CONFORMAL, ELLIPSOIDAL_QUASICONFORMAL, SDEM, LSDEM, EDEM, EDEQ, TDEM,
  TOROIDAL_PARAMETERIZATION, NONE
};
enum class Domain { SPHERE, ELLIPSOID, TORUS };

struct Method_entry { Method method; const char* name; Domain domain; };

inline const std::vector<Method_entry>& method_table()
{
  static const std::vector<Method_entry> t = {
    {Method::SPHERICAL_CONFORMAL, "spherical-conformal", Domain::SPHERE},
    {Method::ELLIPSOIDAL_CONFORMAL, "ellipsoidal-conformal", Domain::ELLIPSOID},
    {Method::ELLIPSOIDAL_QUASICONFORMAL, "ellipsoidal-quasiconformal", Domain::ELLIPSOID},
    {Method::SDEM, "sdem", Domain::SPHERE},
    {Method::LSDEM, "lsdem", Domain::SPHERE},
    {Method::EDEM, "edem", Domain::ELLIPSOID},
    {Method::EDEQ, "edeq", Domain::ELLIPSOID},
    {Method::TDEM, "tdem", Domain::TORUS},
    {Method::TOROIDAL_PARAMETERIZATION, "toroidal-parameterization", Domain::TORUS}};
  return t;
}

inline const char* method_name(Method m)
{
  for(const Method_entry& e : method_table()) if(e.method == m) return e.name;
  return "?";
}

inline Domain domain_of(Method m)
{
  for(const Method_entry& e : method_table()) if(e.method == m) return e.domain;
  return Domain::SPHERE;
}

struct Options
{
  Method method = Method::NONE;
  std::string input;
  std::string population;  // file, "area" or empty (= area)
  std::string landmarks;
  std::string cut_edges;
  std::string output;
  std::string metrics;
  std::optional<std::array<double, 3>> radii;
  std::optional<std::array<double, 2>> torus;
  bool optimize_radii = false;
  bool mobius = false;
  bool quiet = false;
  std::optional<double> time_step, tolerance, alpha, beta, gamma, lambda;
  std::optional<std::size_t> max_iterations;
};

/// The build: which default sparse solver the library was compiled with.
inline std::string version_text()
{
#ifdef CGAL_DEM_USE_CHOLMOD
  return "dem (Density_equalizing_maps), sparse solver: CHOLMOD supernodal LLT";
#else
  return "dem (Density_equalizing_maps), sparse solver: Eigen SimplicialLDLT";
#endif
}

inline std::string usage_text()
{
  return
    "usage: dem METHOD INPUT [options]\n"
    "  METHOD   spherical-conformal | ellipsoidal-conformal | ellipsoidal-quasiconformal |\n"
    "           sdem | lsdem | edem | edeq | tdem | toroidal-parameterization\n"
    "  INPUT    a closed triangle mesh CGAL can read (OFF, OBJ, PLY, STL, ...)\n"
    "  --population FILE|area     one value per face (default: area = area-preserving)\n"
    "  --landmarks FILE           lines \"vertex_index x y z\" (0-based; '#' comments)\n"
    "  --radii A B C              target ellipsoid (ellipsoidal methods; initial radii for edeq)\n"
    "  --optimize-radii           ellipsoidal-conformal: optimize a,b,c\n"
    "  --torus R r                torus radii (tdem, toroidal-parameterization)\n"
    "  --cut-edges FILE           toroidal-parameterization: cut graph (vertex pairs), else automatic\n"
    "  --time-step DT  --tolerance EPS  --max-iterations N\n"
    "  --alpha A --beta B --gamma G  (lsdem; --alpha also for edeq)   --lambda L (ellipsoidal-quasiconformal)\n"
    "  --mobius                   spherical-conformal: apply the Moebius area correction\n"
    "  --output FILE              the mapped mesh (same connectivity, vertices on the domain)\n"
    "  --metrics FILE             JSON metrics; a one-line summary always goes to stdout\n"
    "  --quiet                    no progress messages on stderr\n"
    "  --help, --version          usage / the build's sparse solver\n"
    "exit status: 0 done, 2 usage error (or method not in this build), 3 invalid input or unwritable file,\n"
    "             4 no fold-over-free map (metrics written, output not written)\n";
}

enum class Parse_status { OK, HELP, VERSION, ERROR };

namespace internal {

inline bool to_number(const std::string& s, double& v)
{
  return CGAL::Density_equalizing_maps::IO::internal::parse_double(s, v) && std::isfinite(v);
}

} // namespace internal

/// Parses argv into `opt`. Reports unknown methods/options, missing values,
/// unreadable numbers and options that do not apply to the method.
inline Parse_status parse_command_line(int argc, char** argv, Options& opt, std::string& error)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  for(const std::string& a : args)
    if(a == "--help" || a == "-h") return Parse_status::HELP;
  for(const std::string& a : args)
    if(a == "--version") return Parse_status::VERSION;
  std::vector<std::string> positional;
  std::vector<std::string> seen;
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if(a.size() < 2 || a.compare(0, 2, "--") != 0) { positional.push_back(a); continue; }
    seen.push_back(a);
    auto value = [&](std::size_t count, std::vector<std::string>& out) -> bool {
      for(std::size_t c = 1; c <= count; ++c) {
        if(i + c >= args.size() || (args[i + c].compare(0, 2, "--") == 0 && args[i + c].size() > 2)) {
          error = "option " + a + " needs " + std::to_string(count) + (count == 1 ? " value" : " values");
          return false;
        }
        out.push_back(args[i + c]);
      }
      i += count;
      return true;
    };
    auto numbers = [&](std::size_t count, double* out) -> bool {
      std::vector<std::string> v;
      if(!value(count, v)) return false;
      for(std::size_t c = 0; c < count; ++c)
        if(!internal::to_number(v[c], out[c])) {
          error = "option " + a + ": \"" + v[c] + "\" is not a number";
          return false;
        }
      return true;
    };
    auto string_value = [&](std::string& out) -> bool {
      std::vector<std::string> v;
      if(!value(1, v)) return false;
      out = v[0];
      return true;
    };
    auto scalar = [&](std::optional<double>& out) -> bool {
      double d;
      if(!numbers(1, &d)) return false;
      out = d;
      return true;
    };
    bool ok = true;
    if(a == "--population") ok = string_value(opt.population);
    else if(a == "--landmarks") ok = string_value(opt.landmarks);
    else if(a == "--cut-edges") ok = string_value(opt.cut_edges);
    else if(a == "--output") ok = string_value(opt.output);
    else if(a == "--metrics") ok = string_value(opt.metrics);
    else if(a == "--radii") { std::array<double, 3> r; ok = numbers(3, r.data()); if(ok) opt.radii = r; }
    else if(a == "--torus") { std::array<double, 2> r; ok = numbers(2, r.data()); if(ok) opt.torus = r; }
    else if(a == "--optimize-radii") opt.optimize_radii = true;
    else if(a == "--mobius") opt.mobius = true;
    else if(a == "--quiet") opt.quiet = true;
    else if(a == "--time-step") ok = scalar(opt.time_step);
    else if(a == "--tolerance") ok = scalar(opt.tolerance);
    else if(a == "--alpha") ok = scalar(opt.alpha);
    else if(a == "--beta") ok = scalar(opt.beta);
    else if(a == "--gamma") ok = scalar(opt.gamma);
    else if(a == "--lambda") ok = scalar(opt.lambda);
    else if(a == "--max-iterations") {
      std::vector<std::string> v;
      ok = value(1, v);
      std::size_t n = 0;
      if(ok && !CGAL::Density_equalizing_maps::IO::internal::parse_index(v[0], n)) {
        error = "option --max-iterations: \"" + v[0] + "\" is not a non-negative integer";
        ok = false;
      }
      if(ok) opt.max_iterations = n;
    } else {
      error = "unknown option " + a;
      return Parse_status::ERROR;
    }
    if(!ok) return Parse_status::ERROR;
  }
  if(positional.empty()) { error = "missing METHOD"; return Parse_status::ERROR; }
  for(const Method_entry& e : method_table())
    if(positional[0] == e.name) opt.method = e.method;
  if(opt.method == Method::NONE) { error = "unknown method " + positional[0]; return Parse_status::ERROR; }
  if(positional.size() < 2) { error = "missing INPUT"; return Parse_status::ERROR; }
  if(positional.size() > 2) { error = "unexpected argument " + positional[2]; return Parse_status::ERROR; }
  opt.input = positional[1];

  // Options that do not apply to the method are errors rather than silently ignored.
  const Method m = opt.method;
  auto applies = [&](const std::string& o) {
    if(o == "--landmarks") return m == Method::LSDEM || m == Method::ELLIPSOIDAL_QUASICONFORMAL;
    if(o == "--radii")
      return m == Method::ELLIPSOIDAL_CONFORMAL || m == Method::ELLIPSOIDAL_QUASICONFORMAL || m == Method::EDEM ||
             m == Method::EDEQ;
    if(o == "--optimize-radii") return m == Method::ELLIPSOIDAL_CONFORMAL;
    if(o == "--torus") return m == Method::TDEM || m == Method::TOROIDAL_PARAMETERIZATION;
    if(o == "--cut-edges") return m == Method::TOROIDAL_PARAMETERIZATION;
    if(o == "--time-step" || o == "--tolerance" || o == "--max-iterations")
      return m == Method::SDEM || m == Method::LSDEM || m == Method::EDEM || m == Method::EDEQ || m == Method::TDEM ||
             m == Method::TOROIDAL_PARAMETERIZATION;
    if(o == "--alpha") return m == Method::LSDEM || m == Method::EDEQ;
    if(o == "--beta" || o == "--gamma") return m == Method::LSDEM;
    if(o == "--lambda") return m == Method::ELLIPSOIDAL_QUASICONFORMAL;
    if(o == "--mobius") return m == Method::SPHERICAL_CONFORMAL;
    return true; // --population (density metrics for every method), --output, --metrics, --quiet
  };
  for(const std::string& o : seen)
    if(!applies(o)) {
      error = "option " + o + " does not apply to method " + method_name(m);
      return Parse_status::ERROR;
    }
  if((m == Method::LSDEM || m == Method::ELLIPSOIDAL_QUASICONFORMAL) && opt.landmarks.empty()) {
    error = std::string("method ") + method_name(m) + " needs --landmarks FILE";
    return Parse_status::ERROR;
  }
  if((m == Method::EDEM || m == Method::EDEQ) && !opt.radii) {
    error = std::string("method ") + method_name(m) + " needs --radii A B C";
    return Parse_status::ERROR;
  }
  if((m == Method::TDEM || m == Method::TOROIDAL_PARAMETERIZATION) && !opt.torus) {
    error = std::string("method ") + method_name(m) + " needs --torus R r";
    return Parse_status::ERROR;
  }
  if(opt.max_iterations && *opt.max_iterations == 0) {
    error = "option --max-iterations: must be at least 1";
    return Parse_status::ERROR;
  }
  return Parse_status::OK;
}

// ---------------------------------------------------------------------------
// Input arrays

/// Copies a polygon soup into arrays; throws Invalid_input on a non-triangle.
template <class Point, class Polygon>
void soup_to_arrays(const std::vector<Point>& points, const std::vector<Polygon>& polygons, DI::Matrix& X,
                    DI::Index_matrix& F)
{
  X.resize(Eigen::Index(points.size()), 3);
  for(std::size_t i = 0; i < points.size(); ++i) {
    X(Eigen::Index(i), 0) = CGAL::to_double(points[i].x());
    X(Eigen::Index(i), 1) = CGAL::to_double(points[i].y());
    X(Eigen::Index(i), 2) = CGAL::to_double(points[i].z());
  }
  F.resize(Eigen::Index(polygons.size()), 3);
  for(std::size_t k = 0; k < polygons.size(); ++k) {
    if(polygons[k].size() != 3)
      throw CGAL::Density_equalizing_maps::Invalid_input(
          "not a triangle mesh: face " + std::to_string(k) + " has " + std::to_string(polygons[k].size()) +
          " vertices");
    for(int c = 0; c < 3; ++c) {
      const std::size_t v = polygons[k][std::size_t(c)];
      if(v >= points.size())
        throw CGAL::Density_equalizing_maps::Invalid_input("face " + std::to_string(k) + " refers to vertex " +
                                                           std::to_string(v) + ", out of range");
      F(Eigen::Index(k), c) = int(v);
    }
  }
}

// ---------------------------------------------------------------------------
// Metrics (DESIGN.md contract). NaN = not applicable = JSON null.

struct Metrics
{
  static constexpr double NA = std::numeric_limits<double>::quiet_NaN();
  std::string method;
  std::size_t vertices = 0, faces = 0;
  double seconds = NA;
  double cpu_seconds = NA;       // CPU time of the mapping (summary line only, not a JSON key)
  double iterations = NA;        // NA for direct methods
  bool converged = false;
  std::size_t fold_overs = 0;
  double mean_abs_mu = NA, sd_abs_mu = NA, mean_abs_darea = NA, sd_abs_darea = NA;
  double density_var_initial = NA, density_var_final = NA;
  double face_density_var_initial = NA, face_density_var_final = NA;
  double landmark_error = NA;
  std::vector<double> radii;     // empty = null
  std::string termination;       // for the summary line
};

struct Metric_input
{
  const DI::Matrix* X = nullptr;        // input positions
  const DI::Index_matrix* F = nullptr;
  const DI::Matrix* Y = nullptr;        // output positions (3D: sphere, ellipsoid or torus image)
  const DI::Matrix* initial = nullptr;  // the map the method starts from (or the input mesh)
  const DI::Vector* population = nullptr;
  const std::vector<Eigen::Index>* landmark_index = nullptr;
  const DI::Matrix* landmark_targets = nullptr; // rows = targets as given to the method
  std::size_t radii_count = 3;          // 3 (ellipsoid) or 2 (torus)
};

/// Var(rho/mean rho) of the vertex density M rho_F and of the face density
/// rho_F = population / area, areas and M on the map Z.
inline std::pair<double, double> density_variances(const DI::Matrix& Z, const DI::Index_matrix& F,
                                                   const DI::Vector& population)
{
  const DI::Vector area = DI::face_areas(Z, F);
  const DI::Densities d = DI::densities(population, area, DI::face_to_vertex(area, F, Z.rows()));
  return {DI::normalized_variance(d.vertex), DI::normalized_variance(d.face)};
}

inline Metrics compute_metrics(const std::string& method, const CGAL::Density_equalizing_maps::Map_report& report,
                               double seconds, const Metric_input& in)
{
  using CGAL::Density_equalizing_maps::Termination;
  const DI::Matrix& X = *in.X;
  const DI::Index_matrix& F = *in.F;
  const DI::Matrix& Y = *in.Y;
  Metrics m;
  m.method = method;
  m.vertices = std::size_t(X.rows());
  m.faces = std::size_t(F.rows());
  m.seconds = seconds;
  if(report.termination != Termination::NOT_ITERATIVE) m.iterations = double(report.iterations);
  m.converged = report.converged();
  m.termination = CGAL::Density_equalizing_maps::to_string(report.termination);
  m.fold_overs = report.fold_overs;

  const DI::Mean_sd mu = DI::mean_sd(DI::beltrami_magnitude_3d(X, Y, F));
  m.mean_abs_mu = mu.mean;
  m.sd_abs_mu = mu.sd;
  const DI::Vector darea = DI::log_area_ratio(DI::face_areas(X, F), DI::face_areas(Y, F)).cwiseAbs();
  const DI::Mean_sd da = DI::mean_sd(darea);
  m.mean_abs_darea = da.mean;
  m.sd_abs_darea = da.sd;

  const auto initial = density_variances(in.initial ? *in.initial : X, F, *in.population);
  const auto final = density_variances(Y, F, *in.population);
  m.density_var_initial = initial.first;
  m.face_density_var_initial = initial.second;
  m.density_var_final = final.first;
  m.face_density_var_final = final.second;

  if(in.landmark_index && !in.landmark_index->empty()) {
    double s = 0;
    for(std::size_t k = 0; k < in.landmark_index->size(); ++k)
      s += (Y.row((*in.landmark_index)[k]) - in.landmark_targets->row(Eigen::Index(k))).norm();
    m.landmark_error = s / double(in.landmark_index->size());
  }
  for(std::size_t c = 0; c < std::min(in.radii_count, report.radii.size()); ++c) m.radii.push_back(report.radii[c]);
  return m;
}

inline std::string json_number(double v)
{
  if(!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::string json_string(const std::string& s)
{
  std::string r = "\"";
  for(char c : s) {
    if(c == '"' || c == '\\') { r += '\\'; r += c; }
    else if(static_cast<unsigned char>(c) < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); r += b; }
    else r += c;
  }
  return r + "\"";
}

inline std::string metrics_json(const Metrics& m)
{
  std::ostringstream o;
  o << "{\n"
    << "  \"method\": " << json_string(m.method) << ",\n"
    << "  \"vertices\": " << m.vertices << ",\n"
    << "  \"faces\": " << m.faces << ",\n"
    << "  \"seconds\": " << json_number(m.seconds) << ",\n"
    << "  \"iterations\": " << json_number(m.iterations) << ",\n"
    << "  \"converged\": " << (m.converged ? "true" : "false") << ",\n"
    << "  \"fold_overs\": " << m.fold_overs << ",\n"
    << "  \"mean_abs_mu\": " << json_number(m.mean_abs_mu) << ",\n"
    << "  \"sd_abs_mu\": " << json_number(m.sd_abs_mu) << ",\n"
    << "  \"mean_abs_darea\": " << json_number(m.mean_abs_darea) << ",\n"
    << "  \"sd_abs_darea\": " << json_number(m.sd_abs_darea) << ",\n"
    << "  \"density_var_initial\": " << json_number(m.density_var_initial) << ",\n"
    << "  \"density_var_final\": " << json_number(m.density_var_final) << ",\n"
    << "  \"face_density_var_initial\": " << json_number(m.face_density_var_initial) << ",\n"
    << "  \"face_density_var_final\": " << json_number(m.face_density_var_final) << ",\n"
    << "  \"landmark_error\": " << json_number(m.landmark_error) << ",\n"
    << "  \"radii\": ";
  if(m.radii.empty()) o << "null";
  else {
    o << "[";
    for(std::size_t c = 0; c < m.radii.size(); ++c) o << (c ? ", " : "") << json_number(m.radii[c]);
    o << "]";
  }
  o << "\n}\n";
  return o.str();
}

inline bool write_metrics_json(const std::string& file, const Metrics& m)
{
  std::ofstream out(file);
  if(!out) return false;
  out << metrics_json(m);
  return bool(out);
}

inline std::string summary_line(const Metrics& m)
{
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s: %zu vertices, %zu faces, %.3f s (%.3f s CPU), %s%s, fold-overs %zu, mean|mu| %.4g, mean|darea| %.4g, "
                "density var %.4g -> %.4g",
                m.method.c_str(), m.vertices, m.faces, m.seconds, m.cpu_seconds,
                std::isfinite(m.iterations) ? (std::to_string(std::size_t(m.iterations)) + " iterations, ").c_str() : "",
                m.termination.c_str(), m.fold_overs, m.mean_abs_mu, m.mean_abs_darea, m.density_var_initial,
                m.density_var_final);
  std::string s = buf;
  if(std::isfinite(m.landmark_error)) s += ", landmark error " + json_number(m.landmark_error).substr(0, 10);
  if(!m.radii.empty()) {
    s += ", radii";
    for(double r : m.radii) { std::snprintf(buf, sizeof buf, " %.5g", r); s += buf; }
  }
  return s;
}

} // namespace dem_cli

#endif // DEM_SUPPORT_DEM_SUPPORT_H
