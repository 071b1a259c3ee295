// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The command line of the `dem` tool: the methods it knows, the options of
// the map subcommands (`dem METHOD INPUT [options]`, DESIGN.md) and their
// parsing. No CGAL header is needed here: every subcommand file includes it.

#ifndef DEM_TOOL_CLI_H
#define DEM_TOOL_CLI_H

#include <array>
#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace dem_cli {

double seconds_since(std::chrono::steady_clock::time_point t0);

/// CPU time (user + system, all threads) of the process so far.
double process_cpu_seconds();

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
  bool repair = false; // --repair: PMP soup repair before validation (soup_repair.h)
  std::optional<double> time_step, tolerance, alpha, beta, gamma, lambda;
  std::optional<std::size_t> max_iterations;
  // formats (dem_formats.h)
  std::string output_format;        // --output-format: overrides the extension of --output
  std::string color_by = "darea";   // --color-by darea|mu|density|population
  std::string output_input_colored; // --output-input-colored FILE (.ply/.vtk/.vtp)
  std::string vertex_population;    // --vertex-population FILE (curv, .gii or text; one value per vertex)
  std::optional<double> output_scale; // --output-scale S: multiply the written positions (FreeSurfer spheres: 100)
  bool method_help = false;         // `dem METHOD --help`
};

/// The defaults of a method's iterative options (0 = not iterative / not used).
struct Method_defaults
{
  double time_step = 0, tolerance = 0;
  std::size_t max_iterations = 0;
};
Method_defaults method_defaults(Method m);

/// `dem METHOD --help`: the method's options with their defaults, the formats and two examples.
std::string method_help_text(Method m);

/// `dem --version`: the package and the build's default sparse solver.
std::string version_text();

/// `dem --help`.
std::string usage_text();

/// Takes `--threads N` out of the arguments of any subcommand (N from 1 to
/// 4096) into `threads`; 0 when absent. Says what is wrong on stderr and
/// returns false for a missing or bad number (exit status 2).
bool take_threads_option(std::vector<std::string>& args, unsigned& threads);

enum class Parse_status { OK, HELP, VERSION, ERROR };

/// Parses the arguments of a map subcommand (`METHOD INPUT [options]`, without
/// the program name) into `opt`. Reports unknown methods/options, missing
/// values, unreadable numbers and options that do not apply to the method.
Parse_status parse_command_line(const std::vector<std::string>& args, Options& opt, std::string& error);

} // namespace dem_cli

#endif // DEM_TOOL_CLI_H
