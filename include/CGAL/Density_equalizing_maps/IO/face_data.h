// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_FACE_DATA_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_FACE_DATA_H

/// \file face_data.h
/// The per-face quantities of a map that the writers attach to a mesh: the
/// population, the density ratio on the image, the log area ratio and the
/// Beltrami coefficient magnitude, all computed with the public measures
/// (measures.h), in the order of `faces(tm)`.

#include <CGAL/Density_equalizing_maps/IO/color_map.h>
#include <CGAL/Density_equalizing_maps/IO/triangle_soup.h>
#include <CGAL/Density_equalizing_maps/measures.h>

#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// Per-face quantities of a map `f` from an input mesh to its image, in the order of `faces(tm)`.
struct Face_data
{
  std::vector<double> population;     ///< `P_T` (the input face area by default)
  std::vector<double> density_ratio;  ///< `rho_T / mean(rho)`, `rho_T = P_T / |f(T)|`, arithmetic mean over the faces (1 everywhere for a perfect density-equalizing map; its variance is `density_variance().face`)
  std::vector<double> log_area_ratio; ///< `d_area(T)` as `log_area_ratios()`
  std::vector<double> abs_mu;         ///< `|mu|(T)` as `beltrami_coefficient_magnitudes()`

  /// The values `by` selects.
  /// \param by a quantity
  /// \returns its per-face values
  const std::vector<double>& values(Color_by by) const
  {
    switch(by) {
    case Color_by::log_area_ratio: return log_area_ratio;
    case Color_by::beltrami: return abs_mu;
    case Color_by::density: return density_ratio;
    default: return population;
    }
  }
};

/// \ingroup PkgDensityEqualizingMapsIO
/// The name of a `Color_by` as used in files and on the command line: `darea`, `mu`, `density`, `population`.
/// \param by a quantity
/// \returns its command-line name (`darea`, `mu`, `density` or `population`)
inline std::string color_by_name(Color_by by)
{
  switch(by) {
  case Color_by::log_area_ratio: return "darea";
  case Color_by::beltrami: return "mu";
  case Color_by::density: return "density";
  default: return "population";
  }
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Parses `darea`, `mu`, `density` or `population`.
/// \throws Invalid_input naming the accepted words otherwise
/// \param s the name
/// \returns the quantity of that name
inline Color_by color_by_from_name(const std::string& s)
{
  for(Color_by by : {Color_by::log_area_ratio, Color_by::beltrami, Color_by::density, Color_by::population})
    if(color_by_name(by) == s) return by;
  throw Invalid_input("unknown colour quantity \"" + s + "\" (expected darea, mu, density or population)");
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Computes the `Face_data` of the map from `tm` to the positions `mapped`.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to points
/// \param tm the input triangle mesh (non-degenerate faces)
/// \param mapped the image of every vertex
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{face_population_map}
///     \cgalParamDescription{the population of every face}
///     \cgalParamDefault{the area of the input face}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_density_map}
///     \cgalParamDescription{a density per input vertex, used when no `face_population_map` is given:
///       the population of a face is its input area times the mean density of its three corners
///       (the integral of the linear interpolant of the density)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{the input positions}
///     \cgalParamDefault{`get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \throws Invalid_input if a face is not a triangle
/// \returns the per-face values of the map
template <class TriangleMesh, class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
Face_data face_data(const TriangleMesh& tm, MappedPointMap mapped,
                    const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, tm));
  const Triangle_soup input = triangle_soup(tm, vpm);
  const Triangle_soup image = triangle_soup(tm, mapped);
  const std::vector<double> input_area = internal::face_areas(input), image_area = internal::face_areas(image);
  const std::size_t m = input.faces.size();

  Face_data d;
  d.population = input_area;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::face_population_t>::value) {
    auto pop = get_parameter(np, internal_np::face_population);
    std::size_t k = 0;
    for(auto f : faces(tm)) d.population[k++] = double(get(pop, f));
  } else if constexpr(!is_default_parameter<NamedParameters, internal_np::vertex_density_t>::value) {
    auto rho = get_parameter(np, internal_np::vertex_density);
    std::vector<double> at_vertex;
    for(auto v : vertices(tm)) at_vertex.push_back(double(get(rho, v)));
    for(std::size_t k = 0; k < m; ++k) {
      const auto& t = input.faces[k];
      d.population[k] = input_area[k] * (at_vertex[t[0]] + at_vertex[t[1]] + at_vertex[t[2]]) / 3;
    }
  }

  d.density_ratio.resize(m);
  for(std::size_t k = 0; k < m; ++k) d.density_ratio[k] = d.population[k] / image_area[k];
  const double mean = m > 0 ? std::accumulate(d.density_ratio.begin(), d.density_ratio.end(), 0.) / double(m) : 1.;
  for(double& r : d.density_ratio) r /= mean;

  auto darea = get(CGAL::dynamic_face_property_t<double>(), tm);
  auto mu = get(CGAL::dynamic_face_property_t<double>(), tm);
  log_area_ratios(tm, mapped, darea, parameters::vertex_point_map(vpm));
  beltrami_coefficient_magnitudes(tm, mapped, mu, parameters::vertex_point_map(vpm));
  for(auto f : faces(tm)) {
    d.log_area_ratio.push_back(get(darea, f));
    d.abs_mu.push_back(get(mu, f));
  }
  return d;
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_FACE_DATA_H
