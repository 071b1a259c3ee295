// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The metrics of the `dem` JSON contract (DESIGN.md), computed here and only
// here, and the one-line summary every subcommand prints.

#ifndef DEM_TOOL_METRICS_H
#define DEM_TOOL_METRICS_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace dem_cli {

namespace DI = CGAL::Density_equalizing_maps::internal;

/// NaN = not applicable = JSON null.
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
  std::string fallback;          // Map_report::fallback; empty = null
  std::string start;             // Map_report::start; empty = null
  std::size_t repairs = 0;       // Map_report::repairs
  std::string termination;       // for the summary line
  /// Keys a subcommand adds to the contract's (remesh, register, cartogram, ...):
  /// name and JSON value text, written after the contract's keys in this order.
  std::vector<std::pair<std::string, std::string>> extra;
  void add(const std::string& key, double value);
  void add_json(const std::string& key, const std::string& json_value) { extra.emplace_back(key, json_value); }
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
std::pair<double, double> density_variances(const DI::Matrix& Z, const DI::Index_matrix& F,
                                            const DI::Vector& population);

Metrics compute_metrics(const std::string& method, const CGAL::Density_equalizing_maps::Map_report& report,
                        double seconds, const Metric_input& in);

std::string json_number(double v);
std::string json_string(const std::string& s);
std::string metrics_json(const Metrics& m);
bool write_metrics_json(const std::string& file, const Metrics& m);
std::string summary_line(const Metrics& m);

} // namespace dem_cli

#endif // DEM_TOOL_METRICS_H
