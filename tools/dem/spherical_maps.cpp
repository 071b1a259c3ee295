// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem spherical-conformal | sdem | lsdem`.

#include "maps.h"

#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

namespace dem_cli {

namespace {

namespace NP = CGAL::Density_equalizing_maps::parameters;

Run run_spherical_conformal(Problem& pb, const Options& opt)
{
  Run run;
  Point_map out = fresh_point_map(pb.mesh, "v:dem_sphere");
  const Stopwatch watch;
  run.report = DEM::spherical_conformal_map(
      pb.mesh, out, NP::combine(NP::mobius_area_correction(opt.mobius), tool_parameters()));
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}

// The initial map of SDEM / LSDEM (the library's default: for SDEM the start
// chosen by its density, see Map_report::start; for LSDEM FLASH + Moebius area
// correction) is computed here and handed over, so that the initial density
// variance is measured on the map the iteration actually starts from.
Run run_sdem(Problem& pb, const Options& opt, bool landmark_aligned)
{
  Run run;
  Point_map init = fresh_point_map(pb.mesh, "v:dem_initial");
  Point_map out = fresh_point_map(pb.mesh, "v:dem_sdem");
  Progress progress(opt.quiet);
  const Stopwatch watch;
  DEM::Map_report start;
  start.start = "conformal";
  if(landmark_aligned)
    DEM::spherical_conformal_map(pb.mesh, init,
                                 NP::combine(NP::mobius_area_correction(true), tool_parameters()));
  else // zero iterations: SDEM's own start
    start = DEM::spherical_density_equalizing_map(
      pb.mesh, init, NP::combine(NP::face_population_map(pb.population_map), tool_parameters(),
                                 CGAL::parameters::number_of_iterations(0)));
  const auto common = NP::combine(NP::initial_map(init), NP::progress_callback(progress.callback()), tool_parameters(),
                                  NP::face_population_map(pb.population_map));
  if(!landmark_aligned) {
    run.report = DEM::spherical_density_equalizing_map(
        pb.mesh, out,
        NP::combine(common, NP::time_step(opt.time_step.value_or(method_defaults(Method::SDEM).time_step)),
                    NP::stopping_tolerance(opt.tolerance.value_or(method_defaults(Method::SDEM).tolerance)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(method_defaults(Method::SDEM).max_iterations))));
  } else {
    run.report = DEM::landmark_aligned_spherical_density_equalizing_map(
        pb.mesh, pb.landmarks, out,
        NP::combine(common, NP::time_step(opt.time_step.value_or(method_defaults(Method::LSDEM).time_step)),
                    NP::stopping_tolerance(opt.tolerance.value_or(method_defaults(Method::LSDEM).tolerance)),
                    CGAL::parameters::number_of_iterations(opt.max_iterations.value_or(method_defaults(Method::LSDEM).max_iterations)),
                    NP::density_weight(opt.alpha.value_or(1.)), NP::harmonic_weight(opt.beta.value_or(2.)),
                    NP::landmark_weight(opt.gamma.value_or(5.))));
  }
  run.report.start = start.start; // the flow itself was handed the start as `initial_map`
  watch.stop(run.seconds, run.cpu_seconds);
  run.Y0 = to_matrix(pb.mesh, init);
  run.Y = to_matrix(pb.mesh, out);
  return run;
}

} // namespace

Run run_spherical_map(Problem& pb, const Options& opt)
{
  if(opt.method == Method::SPHERICAL_CONFORMAL) return run_spherical_conformal(pb, opt);
  return run_sdem(pb, opt, opt.method == Method::LSDEM);
}

} // namespace dem_cli
