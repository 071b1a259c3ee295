// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "cli.h"
#include "commands.h"

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>
#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/version.h>

#include <sys/resource.h> // getrusage

#include <cmath>
#include <iostream>
#include <sstream>

namespace dem_cli {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double process_cpu_seconds()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// The package version (version.h), the build's default sparse solver and,
/// under OpenBLAS, the kernels it runs (internal/openblas.h).
std::string version_text()
{
#ifdef CGAL_DEM_USE_CHOLMOD
  const char* solver = "CHOLMOD supernodal LLT";
#else
  const char* solver = "Eigen SimplicialLDLT";
#endif
  const std::string kernels = CGAL::Density_equalizing_maps::internal::openblas_core_name();
  return std::string("dem (Density_equalizing_maps) ") + CGAL_DEM_VERSION_STR + ", sparse solver: " + solver +
         (kernels.empty() ? std::string() : ", OpenBLAS kernels: " + kernels);
}

std::string usage_text()
{
  std::string text =
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
    "  --output-format F          freesurfer | gifti | ply | vtk | vtp | obj | off | stl | ts (default: by extension)\n"
    "  --color-by Q               darea | mu | density | population: colours of .ply/.vtk/.vtp (default darea)\n"
    "  --output-input-colored FILE  the input surface coloured by the same quantity (.ply, .vtk, .vtp)\n"
    "  --vertex-population FILE   one positive value per vertex (FreeSurfer curv, GIfTI data array or text);\n"
    "                             face population = face area x mean of its corners' values\n"
    "  --output-scale S           multiply the written positions by S (FreeSurfer spheres: 100)\n"
    "  --quiet                    no progress messages on stderr\n"
    "  --threads N                at most N threads, for every subcommand: the parallel loops, OpenBLAS and\n"
    "                             CHOLMOD's OpenMP regions (default: every core; 1: single-threaded). The\n"
    "                             loops give the same bits on any number; OpenBLAS's threads add in another\n"
    "                             order than one thread (OPENBLAS_NUM_THREADS=1: every run as --threads 1)\n"
    "  --repair                   repair a polygon soup first (merge duplicated vertices, remove\n"
    "                             duplicated and degenerate faces, orient consistently, keep the\n"
    "                             largest component) and print what changed; off by default\n"
    "  --help, --version          usage (dem METHOD --help: that method's options, defaults, examples) / version\n"
    "input formats: .off .obj .ply .stl .ts, FreeSurfer triangle surfaces (lh.white, ...), GIfTI .surf.gii\n"
    "output formats (--output, by extension): .ply with per-face population, density_ratio, log_area_ratio,\n"
    "  abs_mu and colours; .vtk/.vtp with the same cell data; .obj with texture coordinates; .gii;\n"
    "  FreeSurfer (no extension, lh.* / rh.*, or --output-format freesurfer); .off .stl .ts (positions)\n"
    "environment: OPENBLAS_CORETYPE names OpenBLAS's kernels; unset, dem sets it and starts again when\n"
    "  OpenBLAS does not know this CPU and fell back to kernels without AVX (e.g. 0.3.21 on recent Xeons)\n"
    "exit status: 0 done; 2 usage error (also: unsupported output format, an output that is an input);\n"
    "             3 invalid input (also: an output directory that is missing or not writable);\n"
    "             4 the method failed: fold-overs left, stalled, or a numerical failure (says which;\n"
    "               metrics written, mesh output not written)\n"
    "files: outputs are checked before the computation and written atomically (temporary file +\n"
    "       rename); on exit 3 or 4 an --output (and on exit 3 a --metrics) file left by an earlier\n"
    "       run is deleted, so that no stale result looks current. Inputs are never overwritten.\n";
  if(!applications().empty()) {
    text += "applications (dem NAME --help for their options):\n";
    for(const Application& a : applications()) text += std::string("  ") + a.synopsis + "\n";
  }
  return text;
}

Method_defaults method_defaults(Method m)
{
  switch(m) {
  case Method::SDEM: return {0.1, 1e-3, 200};
  case Method::LSDEM: return {0.01, 1e-3, 200};
  case Method::EDEM: return {0.1, 1e-3, 300};
  case Method::EDEQ: return {0.1, 1e-5, 300};
  case Method::TDEM: case Method::TOROIDAL_PARAMETERIZATION: return {0.1, 1e-2, 1000};
  default: return {};
  }
}

std::string method_help_text(Method m)
{
  const Method_defaults d = method_defaults(m);
  const std::string name = method_name(m);
  std::ostringstream o;
  o << "usage: dem " << name << " INPUT [options]\n";
  switch(m) {
  case Method::SPHERICAL_CONFORMAL: o << "  conformal map onto the unit sphere (genus 0)\n"
                                       "  --mobius                 apply the Moebius area correction (default off)\n"; break;
  case Method::ELLIPSOIDAL_CONFORMAL: o << "  conformal map onto an ellipsoid (genus 0)\n"
                                         "  --radii A B C            the ellipsoid (default: from the mesh's principal axes)\n"
                                         "  --optimize-radii         optimize a, b, c (default off)\n"; break;
  case Method::ELLIPSOIDAL_QUASICONFORMAL: o << "  landmark-matching quasi-conformal map onto an ellipsoid\n"
                                              "  --landmarks FILE         required: lines \"vertex x y z\"\n"
                                              "  --radii A B C            the ellipsoid\n"
                                              "  --lambda L               landmark weight (default 1)\n"; break;
  case Method::SDEM: o << "  spherical density-equalizing map\n"; break;
  case Method::LSDEM: o << "  landmark-aligned spherical density-equalizing map\n"
                         "  --landmarks FILE         required: lines \"vertex x y z\"\n"
                         "  --alpha A --beta B --gamma G  density, harmonic, landmark weights (default 1, 2, 5)\n"; break;
  case Method::EDEM: o << "  ellipsoidal density-equalizing map\n  --radii A B C            required: the ellipsoid\n"; break;
  case Method::EDEQ: o << "  ellipsoidal density-equalizing quasi-conformal map\n"
                        "  --radii A B C            required: the initial ellipsoid\n"
                        "  --alpha A                Beltrami weight (default 5)\n"; break;
  case Method::TDEM: o << "  toroidal density-equalizing map of a mesh lying on the torus\n"
                        "  --torus R r              required: the radii, R > r > 0\n"; break;
  case Method::TOROIDAL_PARAMETERIZATION: o << "  density-equalizing map of any genus-one mesh onto the torus\n"
                                             "  --torus R r              required: the radii, R > r > 0\n"
                                             "  --cut-edges FILE         cut graph (vertex pairs; default automatic)\n"; break;
  default: break;
  }
  if(d.tolerance > 0)
    o << "  --time-step DT            default " << d.time_step << "\n"
      << "  --tolerance EPS           stop when the density error is below EPS (default " << d.tolerance << ")\n"
      << "  --max-iterations N        default " << d.max_iterations << "\n";
  o << "  --population FILE|area    one value per face (default area)\n"
       "  --vertex-population FILE  one value per vertex: face population = area x mean of its corners\n"
       "  --output FILE  --output-format F  --color-by darea|mu|density|population (default darea)\n"
       "  --output-input-colored FILE  --output-scale S  --metrics FILE  --quiet\n"
       "read: .off .obj .ply .stl .ts, FreeSurfer triangle surfaces, .gii\n"
       "written: .ply .vtk .vtp (face data + colours), .obj (texture coordinates), .gii, FreeSurfer, .off .stl .ts\n"
       "examples:\n";
  const std::string extra = m == Method::TDEM || m == Method::TOROIDAL_PARAMETERIZATION ? " --torus 3 1"
                            : m == Method::EDEM || m == Method::EDEQ ? " --radii 2 1 1"
                            : m == Method::LSDEM || m == Method::ELLIPSOIDAL_QUASICONFORMAL ? " --landmarks landmarks.txt"
                            : "";
  const std::string mesh = m == Method::TDEM || m == Method::TOROIDAL_PARAMETERIZATION ? "torus.off" : "bumpy.off";
  o << "  dem " << name << " " << mesh << extra << " --output out.ply --color-by darea --output-input-colored in.ply\n";
  if(domain_of(m) == Domain::TORUS)
    o << "  dem " << name << " " << mesh << extra << " --population pop.txt --output out.obj --metrics m.json\n";
  else
    o << "  dem " << name << " lh.white" << extra << " --output lh.sphere.gii --vertex-population lh.thickness --quiet\n";
  return o.str();
}

namespace internal {

inline bool to_number(const std::string& s, double& v)
{
  return CGAL::Density_equalizing_maps::IO::internal::parse_double(s, v) && std::isfinite(v);
}

} // namespace internal

bool take_threads_option(std::vector<std::string>& args, unsigned& threads)
{
  for(std::size_t i = 0; i < args.size(); ++i) {
    if(args[i] != "--threads") continue;
    std::size_t n = 0;
    if(i + 1 >= args.size() || !CGAL::Density_equalizing_maps::IO::internal::parse_index(args[i + 1], n) || n == 0 ||
       n > 4096) {
      std::cerr << "dem: option --threads needs a number of threads from 1 to 4096"
                << (i + 1 < args.size() ? ", not \"" + args[i + 1] + "\"" : std::string()) << std::endl;
      return false;
    }
    threads = unsigned(n);
    args.erase(args.begin() + std::ptrdiff_t(i), args.begin() + std::ptrdiff_t(i) + 2);
    --i;
  }
  return true;
}

Parse_status parse_command_line(const std::vector<std::string>& args, Options& opt, std::string& error)
{
  for(const std::string& a : args)
    if(a == "--help" || a == "-h") {
      if(!args.empty())
        for(const Method_entry& e : method_table())
          if(args[0] == e.name) {
            opt.method = e.method;
            opt.method_help = true;
          }
      return Parse_status::HELP;
    }
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
    else if(a == "--output-format") ok = string_value(opt.output_format);
    else if(a == "--color-by") ok = string_value(opt.color_by);
    else if(a == "--output-input-colored") ok = string_value(opt.output_input_colored);
    else if(a == "--vertex-population") ok = string_value(opt.vertex_population);
    else if(a == "--output-scale") {
      ok = scalar(opt.output_scale);
      if(ok && !(*opt.output_scale > 0)) { error = "option --output-scale: must be positive"; ok = false; }
    }
    else if(a == "--radii") { std::array<double, 3> r; ok = numbers(3, r.data()); if(ok) opt.radii = r; }
    else if(a == "--torus") { std::array<double, 2> r; ok = numbers(2, r.data()); if(ok) opt.torus = r; }
    else if(a == "--optimize-radii") opt.optimize_radii = true;
    else if(a == "--mobius") opt.mobius = true;
    else if(a == "--quiet") opt.quiet = true;
    else if(a == "--repair") opt.repair = true;
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
  if(!opt.vertex_population.empty() && !opt.population.empty()) {
    error = "--population and --vertex-population are exclusive (one population per run)";
    return Parse_status::ERROR;
  }
  if(opt.color_by != "darea" && opt.color_by != "mu" && opt.color_by != "density" && opt.color_by != "population") {
    error = "option --color-by: \"" + opt.color_by + "\" is not one of darea, mu, density, population";
    return Parse_status::ERROR;
  }
  if(opt.max_iterations && *opt.max_iterations == 0) {
    error = "option --max-iterations: must be at least 1";
    return Parse_status::ERROR;
  }
  return Parse_status::OK;
}

} // namespace dem_cli
