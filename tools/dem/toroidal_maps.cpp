// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem tdem | toroidal-parameterization`.

#include "maps.h"

#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include <CGAL/Simple_cartesian.h>

#include <array>

namespace dem_cli {

namespace {

namespace NP = CGAL::Density_equalizing_maps::parameters;

Run run_toroidal(Problem& pb, const Options& opt, bool parameterization)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_torus");
  Progress progress(opt.quiet);
  // the flat-torus layout, kept on the mesh for the texture coordinates of an OBJ output
  auto flat = pb.mesh.add_property_map<Vertex, CGAL::Simple_cartesian<double>::Point_2>("v:dem_flat").first;
  auto offsets = pb.mesh.add_property_map<Mesh::Halfedge_index, std::array<int, 2> >("h:dem_offset").first;
  const auto common = NP::combine(
      NP::flat_torus_coordinates(flat), NP::flat_torus_offsets(offsets),
      NP::torus_radii(*opt.torus), NP::face_population_map(pb.population_map),
      NP::progress_callback(progress.callback()), tool_parameters(),
      NP::time_step(opt.time_step.value_or(method_defaults(opt.method).time_step)),
      NP::stopping_tolerance(opt.tolerance.value_or(method_defaults(opt.method).tolerance)),
      CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(method_defaults(opt.method).max_iterations)));
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

} // namespace

Run run_toroidal_map(Problem& pb, const Options& opt)
{
  return run_toroidal(pb, opt, opt.method == Method::TOROIDAL_PARAMETERIZATION);
}

} // namespace dem_cli
