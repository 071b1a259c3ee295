// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_COLOR_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_COLOR_MAP_H

/// \file color_map.h
/// The perceptually uniform sequential colour map "viridis" (van der Walt and
/// Smith, the default of matplotlib since 2.0) and the value ranges used to
/// colour the per-face quantities of a map. The table below holds viridis at
/// the nine parameters t = k/8 (published anchor values, rounded to 8 bits);
/// between anchors the colour is interpolated linearly in sRGB, which stays
/// within one or two 8-bit steps of the full 256-entry table.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// An 8-bit sRGB colour.
using Rgb = std::array<unsigned char, 3>;

/// \ingroup PkgDensityEqualizingMapsIO
/// The viridis colour of `t` in [0, 1] (clamped; NaN gives the colour of 0):
/// dark purple at 0, teal at 0.5, yellow at 1.
/// \param t the position in the colour map, clamped to [0, 1]
/// \returns the viridis colour at `t`
inline Rgb viridis(double t)
{
  static const double anchors[9][3] = {
    {68, 1, 84},    {71, 45, 123},  {59, 82, 139}, {44, 114, 142}, {33, 145, 140},
    {40, 174, 128}, {94, 201, 98},  {173, 220, 48}, {253, 231, 37}};
  if(!(t > 0)) t = 0; // also catches NaN
  if(t > 1) t = 1;
  const double s = 8 * t;
  const int k = std::min(7, int(s));
  const double w = s - k;
  Rgb c;
  for(int i = 0; i < 3; ++i)
    c[i] = static_cast<unsigned char>(std::lround((1 - w) * anchors[k][i] + w * anchors[k + 1][i]));
  return c;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// The quantity a mesh is coloured by.
enum class Color_by
{
  log_area_ratio, ///< `d_area`, range symmetric about 0: [-max|d_area|, +max|d_area|] (0 = area kept, teal)
  beltrami,       ///< `|mu|`, fixed range [0, 1] (0 = conformal)
  density,        ///< density ratio rho/mean(rho), log scale symmetric about 1: [1/q, q], q = max(ratio, 1/ratio)
  population      ///< population, log scale over [min, max] of the values
};

/// \ingroup PkgDensityEqualizingMapsIO
/// An affine (or logarithmic) map from values to the colour parameter t in [0, 1].
struct Color_range
{
  double low = 0, high = 1;
  bool logarithmic = false;

  /// t of a value: (v - low) / (high - low), on log(v) when logarithmic; 0.5 when the range is empty.
  /// \param v a value of the quantity
  /// \returns its position in [0, 1] in the colour map
  double parameter(double v) const
  {
    double a = low, b = high;
    if(logarithmic) {
      if(!(v > 0)) return 0;
      v = std::log(v);
      a = std::log(a);
      b = std::log(b);
    }
    if(!(b > a)) return 0.5;
    return (v - a) / (b - a);
  }
};

/// \ingroup PkgDensityEqualizingMapsIO
/// The documented range of `Color_by` for these values (non-finite values ignored).
/// \param by the quantity the values are
/// \param values the per-face values
/// \returns the documented colour range of that quantity for these values
inline Color_range color_range(Color_by by, const std::vector<double>& values)
{
  double max_abs = 0, lo = std::numeric_limits<double>::infinity(), hi = 0, max_log = 0;
  for(double v : values) {
    if(!std::isfinite(v)) continue;
    max_abs = std::max(max_abs, std::abs(v));
    if(v > 0) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      max_log = std::max(max_log, std::abs(std::log(v)));
    }
  }
  Color_range r;
  switch(by) {
  case Color_by::log_area_ratio: r.low = -max_abs; r.high = max_abs; break;
  case Color_by::beltrami: r.low = 0; r.high = 1; break;
  case Color_by::density:
    r.logarithmic = true;
    r.low = std::exp(-max_log);
    r.high = std::exp(max_log);
    break;
  case Color_by::population:
    r.logarithmic = true;
    r.low = std::isfinite(lo) ? lo : 1;
    r.high = std::isfinite(lo) ? hi : 1;
    break;
  }
  return r;
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_COLOR_MAP_H
