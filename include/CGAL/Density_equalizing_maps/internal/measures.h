// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H

// The quantities of the papers' tables (ALGORITHMS.md section 11).

#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <cmath>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Sample mean and standard deviation (N - 1 normalization, as MATLAB).
struct Mean_sd { double mean = 0, sd = 0; };

inline Mean_sd mean_sd(const Vector& v)
{
  Mean_sd r;
  if(v.size() == 0) return r;
  r.mean = v.mean();
  if(v.size() > 1) r.sd = std::sqrt((v.array() - r.mean).square().sum() / double(v.size() - 1));
  return r;
}

/// sd / mean.
inline double relative_sd(const Vector& v) { const Mean_sd m = mean_sd(v); return m.sd / m.mean; }

/// Variance of v / mean(v) (N - 1 normalization).
inline double normalized_variance(const Vector& v) { const double r = relative_sd(v); return r * r; }

/// d_area(T) = log( (|f(T)| / sum |f|) / (|T| / sum |T|) ), flat triangle areas.
inline Vector log_area_ratio(const Vector& source_area, const Vector& image_area)
{
  const double ss = source_area.sum(), si = image_area.sum();
  Vector d(source_area.size());
  for(Eigen::Index k = 0; k < d.size(); ++k) d[k] = std::log((image_area[k] / si) / (source_area[k] / ss));
  return d;
}

/// Face density rho_F = population / area and vertex density rho_V = M rho_F.
struct Densities { Vector face, vertex; };

inline Densities densities(const Vector& population, const Vector& area, const Sparse_matrix& M)
{
  Densities d;
  d.face = population.cwiseQuotient(area);
  d.vertex = M * d.face;
  return d;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H
