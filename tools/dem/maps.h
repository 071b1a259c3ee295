// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The nine maps of the package as `dem` runs them, one function per family
// (each compiled in its own file, so the heavy method headers are
// instantiated once). The applications (remesh, register, ...) call run_map().

#ifndef DEM_TOOL_MAPS_H
#define DEM_TOOL_MAPS_H

#include "metrics.h"
#include "problem.h"

namespace dem_cli {

/// spherical-conformal, sdem, lsdem.
Run run_spherical_map(Problem& pb, const Options& opt);
/// ellipsoidal-conformal, ellipsoidal-quasiconformal, edem, edeq.
Run run_ellipsoidal_map(Problem& pb, const Options& opt);
/// tdem, toroidal-parameterization.
Run run_toroidal_map(Problem& pb, const Options& opt);

/// Maps `pb` with `opt.method`; throws DEM::Invalid_input on invalid input.
inline Run run_map(Problem& pb, const Options& opt)
{
  switch(domain_of(opt.method)) {
    case Domain::SPHERE: return run_spherical_map(pb, opt);
    case Domain::ELLIPSOID: return run_ellipsoidal_map(pb, opt);
    case Domain::TORUS: return run_toroidal_map(pb, opt);
  }
  return Run();
}

/// The contract's metrics of a map run (map_command.cpp); applications add their keys.
Metrics map_metrics(const Problem& pb, const Options& opt, const Run& run);

} // namespace dem_cli

#endif // DEM_TOOL_MAPS_H
