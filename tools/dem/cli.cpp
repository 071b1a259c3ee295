// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "cli.h"
#include "commands.h"

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>

#include <sys/resource.h> // getrusage

#include <cmath>

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

/// The build: which default sparse solver the library was compiled with.
std::string version_text()
{
#ifdef CGAL_DEM_USE_CHOLMOD
  return "dem (Density_equalizing_maps), sparse solver: CHOLMOD supernodal LLT";
#else
  return "dem (Density_equalizing_maps), sparse solver: Eigen SimplicialLDLT";
#endif
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
    "  --quiet                    no progress messages on stderr\n"
    "  --help, --version          usage / the build's sparse solver\n"
    "exit status: 0 done, 2 usage error, 3 invalid input or unwritable file,\n"
    "             4 no fold-over-free map (metrics written, output not written)\n";
  if(!applications().empty()) {
    text += "applications (dem NAME --help for their options):\n";
    for(const Application& a : applications()) text += std::string("  ") + a.synopsis + "\n";
  }
  return text;
}


namespace internal {

inline bool to_number(const std::string& s, double& v)
{
  return CGAL::Density_equalizing_maps::IO::internal::parse_double(s, v) && std::isfinite(v);
}

} // namespace internal

Parse_status parse_command_line(const std::vector<std::string>& args, Options& opt, std::string& error)
{
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

} // namespace dem_cli
