// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What every subcommand of `dem` shares: the mesh type, a problem read and
// validated from files, the result of a map run, progress and timing, and the
// writing of an output mesh.

#ifndef DEM_TOOL_PROBLEM_H
#define DEM_TOOL_PROBLEM_H

#include "cli.h"
#include "dem_stages.h"

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace dem_cli {

namespace DEM = CGAL::Density_equalizing_maps;
namespace DI = CGAL::Density_equalizing_maps::internal;

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef Mesh::Face_index Face;
typedef Mesh::Property_map<Vertex, Point_3> Point_map;
typedef Mesh::Property_map<Face, double> Face_value_map;
typedef std::vector<std::pair<Vertex, Point_3>> Landmarks;

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
  /// --repair: what it changed ("" without --repair), and whether it changed anything
  std::string repairs;
  bool repaired = false;
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

/// The stage reporter of the running command, if any: Progress forwards the
/// iterations to it (stage name, error against tolerance, estimate).
void set_stage_progress(Stage_progress* s);
Stage_progress* stage_progress();

/// The library's stage names (named parameter `stage_callback`), shown by the
/// stage reporter as parts of the running stage.
std::function<void(const std::string&)> stage_callback();

/// The named parameters every map run by dem takes: the stage names for the
/// progress display, and parallel loops (their number of threads is set once
/// for the process, by --threads in main.cpp).
inline auto tool_parameters()
{
  return DEM::parameters::combine(DEM::parameters::stage_callback(stage_callback()),
                                  DEM::parameters::concurrency_tag(CGAL::Parallel_if_available_tag()));
}

/// Prints iterations on stderr once a run has lasted more than a second
/// (through the stage reporter when one is set).
class Progress
{
public:
  explicit Progress(bool quiet);
  ~Progress();
  bool operator()(std::size_t iteration, double error);
  std::function<bool(std::size_t, double)> callback() { return [this](std::size_t i, double e) { return (*this)(i, e); }; }

private:
  bool quiet_;
  bool tty_;
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

DI::Matrix to_matrix(const Mesh& mesh, const Point_map& pm);
Point_map fresh_point_map(Mesh& mesh, const std::string& name);

/// Reads and validates the mesh of `opt.input` for `opt.method`'s domain
/// (throws DEM::Invalid_input, exit 3).
void read_mesh(const Options& opt, Problem& pb);

/// Reads the population, landmark and cut-edge files of `opt`.
void read_sidecars(const Options& opt, Problem& pb);

/// Landmark targets as rows, with their vertex indices.
DI::Matrix landmark_targets(const Landmarks& l, std::vector<Eigen::Index>& index);

/// Writes a triangle mesh (positions Y, faces F) in the format of the file's
/// extension, atomically (a temporary file in the same folder, then renamed).
bool write_output(const std::string& file, const DI::Matrix& Y, const DI::Index_matrix& F);

} // namespace dem_cli

#endif // DEM_TOOL_PROBLEM_H
