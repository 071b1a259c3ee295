// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ENGINE_PARAMETERS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ENGINE_PARAMETERS_H

// Named parameters of the density-equalizing methods, read in one place, and
// the translation of the engine's result into the public report.

#include <CGAL/Density_equalizing_maps/internal/density_engine.h>
#include <CGAL/Density_equalizing_maps/internal/input.h>

#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

template <class NamedParameters>
Engine_options engine_options_from_parameters(const NamedParameters& np, double default_time_step,
                                              double default_tolerance, std::size_t default_iterations)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Engine_options o;
  o.time_step = choose_parameter(get_parameter(np, internal_np::time_step), default_time_step);
  o.tolerance = choose_parameter(get_parameter(np, internal_np::stopping_tolerance), default_tolerance);
  o.max_iterations = static_cast<std::size_t>(
    choose_parameter(get_parameter(np, internal_np::number_of_iterations), default_iterations));
  if(!(o.time_step > 0) || !std::isfinite(o.time_step))
    throw Invalid_input("time_step must be positive (got " + std::to_string(o.time_step) + ")");
  if(!(o.tolerance > 0) || !std::isfinite(o.tolerance))
    throw Invalid_input("stopping_tolerance must be positive (got " + std::to_string(o.tolerance) + ")");
  if constexpr(!is_default_parameter<NamedParameters, internal_np::progress_callback_t>::value) {
    auto cb = get_parameter(np, internal_np::progress_callback);
    o.progress = [cb](std::size_t it, double err) { return static_cast<bool>(cb(it, err)); };
  }
  o.stage = stage_notifier_from_parameters(np);
  return o;
}

/// The truncation of inverted faces' Beltrami coefficients in the repair step.
template <class NamedParameters>
double truncation_from_parameters(const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const double truncation = choose_parameter(get_parameter(np, internal_np::truncation), 0.1);
  if(!(truncation > 0 && truncation < 1)) throw Invalid_input("truncation must lie in (0, 1)");
  return truncation;
}

inline void fill_report(const Engine_result& r, Map_report& report)
{
  report.termination = r.termination;
  report.iterations = r.iterations;
  report.initial_error = r.initial_error;
  report.final_error = r.final_error;
  report.repairs += r.steps.repairs; // after those of the start (a fallback repaired)
  report.step_halvings = r.steps.halvings;
  // after what the start said (e.g. which initial map was taken)
  if(!r.message.empty()) report.message += (report.message.empty() ? "" : "; ") + r.message;
}

/// Reads landmarks (vertex, target point) into indices and a target matrix.
/// Throws `Invalid_input` for a vertex out of range, a non-finite target, or
/// a vertex listed twice (two targets for one vertex contradict each other;
/// even equal ones would count twice in the landmark energy).
template <class TriangleMesh, class Landmarks, class NamedParameters>
void read_landmarks(const TriangleMesh& tm, const Landmarks& landmarks, const NamedParameters& np,
                    std::vector<Eigen::Index>& vertices, Matrix& targets)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const std::size_t nv = static_cast<std::size_t>(num_vertices(tm));
  vertices.clear();
  std::vector<char> listed(nv, 0);
  targets.resize(static_cast<Eigen::Index>(landmarks.size()), 3);
  Eigen::Index k = 0;
  for(const auto& lm : landmarks) {
    const std::size_t i = static_cast<std::size_t>(get(vim, lm.first));
    if(i >= nv)
      throw Invalid_input("landmark " + std::to_string(k) + ": vertex index " + std::to_string(i) +
                          " out of range (the mesh has " + std::to_string(nv) + " vertices)");
    if(listed[i])
      throw Invalid_input("landmark " + std::to_string(k) + ": vertex " + std::to_string(i) +
                          " is listed more than once");
    listed[i] = 1;
    vertices.push_back(static_cast<Eigen::Index>(i));
    targets(k, 0) = CGAL::to_double(lm.second.x());
    targets(k, 1) = CGAL::to_double(lm.second.y());
    targets(k, 2) = CGAL::to_double(lm.second.z());
    if(!targets.row(k).allFinite())
      throw Invalid_input("landmark " + std::to_string(k) + ": non-finite target");
    ++k;
  }
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ENGINE_PARAMETERS_H
