// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem ellipsoidal-conformal | ellipsoidal-quasiconformal | edem | edeq`.

#include "maps.h"

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace dem_cli {

namespace {

namespace NP = CGAL::Density_equalizing_maps::parameters;

Run run_ellipsoidal_conformal(Problem& pb, const Options& opt)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_ellipsoid");
  const Stopwatch watch;
  if(opt.radii)
    run.report = DEM::ellipsoidal_conformal_map(
        pb.mesh, out, NP::combine(NP::ellipsoid_radii(*opt.radii), NP::optimize_radii(opt.optimize_radii),
                                tool_parameters()));
  else
    run.report = DEM::ellipsoidal_conformal_map(
        pb.mesh, out, NP::combine(NP::optimize_radii(opt.optimize_radii), tool_parameters()));
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
      NP::combine(NP::ellipsoid_radii(radii), NP::landmark_weight(opt.lambda.value_or(1.)),
                  tool_parameters()));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}
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
      pb.mesh, init, NP::combine(NP::ellipsoid_radii(radii), NP::face_population_map(pb.population_map),
                                 tool_parameters()));
  if(!opt.quiet) std::cerr << "dem: " << start.message << std::endl;
  const auto common = NP::combine(NP::ellipsoid_radii(radii), NP::initial_map(init),
                                  NP::face_population_map(pb.population_map),
                                  NP::progress_callback(progress.callback()), tool_parameters(),
                                  NP::time_step(opt.time_step.value_or(method_defaults(opt.method).time_step)));
  if(!quasiconformal)
    run.report = DEM::ellipsoidal_density_equalizing_map(
        pb.mesh, out,
        NP::combine(common, NP::stopping_tolerance(opt.tolerance.value_or(method_defaults(opt.method).tolerance)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(method_defaults(opt.method).max_iterations))));
  else
    run.report = DEM::ellipsoidal_density_equalizing_quasiconformal_map(
        pb.mesh, out,
        NP::combine(common, NP::beltrami_weight(opt.alpha.value_or(5.)),
                    NP::stopping_tolerance(opt.tolerance.value_or(method_defaults(opt.method).tolerance)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(method_defaults(opt.method).max_iterations))));
  run.report.start = start.start; // the flow itself was handed the start as `initial_map`
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y0 = to_matrix(pb.mesh, init);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}

} // namespace

Run run_ellipsoidal_map(Problem& pb, const Options& opt)
{
  switch(opt.method) {
    case Method::ELLIPSOIDAL_CONFORMAL: return run_ellipsoidal_conformal(pb, opt);
    case Method::ELLIPSOIDAL_QUASICONFORMAL: return run_ellipsoidal_quasiconformal(pb, opt);
    default: return run_edem(pb, opt, opt.method == Method::EDEQ);
  }
}

} // namespace dem_cli
