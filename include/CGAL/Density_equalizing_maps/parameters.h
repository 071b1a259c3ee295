// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Named parameters of the package. CGAL 5.5 cannot chain new names after its
// own members, so new names come first in a chain, or packs are joined with
// `combine()` (see the user manual).
#ifndef CGAL_DENSITY_EQUALIZING_MAPS_PARAMETERS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Density_equalizing_maps {

namespace internal_np {
using namespace CGAL::internal_np;   // CGAL's tags + Lookup_named_param_def stay reachable as internal_np::X
enum time_step_t              { time_step };
enum stopping_tolerance_t     { stopping_tolerance };
enum ellipsoid_radii_t        { ellipsoid_radii };
enum face_population_t        { face_population };
enum vertex_density_t         { vertex_density };
enum initial_map_t            { initial_map };
enum mobius_area_correction_t { mobius_area_correction };
enum truncation_t             { truncation };
enum landmarks_t              { landmarks };
enum density_weight_t         { density_weight };
enum harmonic_weight_t        { harmonic_weight };
enum landmark_weight_t        { landmark_weight };
enum beltrami_weight_t        { beltrami_weight };
enum pole_vertices_t          { pole_vertices };
enum optimize_radii_t         { optimize_radii };
enum torus_radii_t            { torus_radii };
enum cut_edges_t              { cut_edges };
enum flat_torus_coordinates_t { flat_torus_coordinates };
enum flat_torus_offsets_t     { flat_torus_offsets };
enum progress_callback_t      { progress_callback };
enum stage_callback_t         { stage_callback };
enum sea_density_t            { sea_density };
enum overlap_subdivision_t    { overlap_subdivision };
enum relative_area_tolerance_t { relative_area_tolerance };
enum number_of_passes_t       { number_of_passes };
enum boundary_step_t          { boundary_step };
enum pass_callback_t          { pass_callback };
enum torus_lattice_t          { torus_lattice };
enum coarse_globe_vertices_t  { coarse_globe_vertices };
enum concurrency_tag_t        { concurrency_tag };
} // namespace internal_np

namespace parameters {
using namespace CGAL::parameters;    // built-in names, default_values(), choose_parameter, ...

#define CGAL_DEM_ADD_NAMED_PARAMETER(TAG_T, FUNC)                          \
  template <typename T>                                                    \
  CGAL::Named_function_parameters<T, internal_np::TAG_T> FUNC(const T& t)  \
  { return CGAL::Named_function_parameters<T, internal_np::TAG_T>(t); }

CGAL_DEM_ADD_NAMED_PARAMETER(time_step_t,          time_step)
CGAL_DEM_ADD_NAMED_PARAMETER(stopping_tolerance_t, stopping_tolerance)
CGAL_DEM_ADD_NAMED_PARAMETER(ellipsoid_radii_t,    ellipsoid_radii)
CGAL_DEM_ADD_NAMED_PARAMETER(face_population_t,    face_population_map)
CGAL_DEM_ADD_NAMED_PARAMETER(vertex_density_t,     vertex_density_map)
CGAL_DEM_ADD_NAMED_PARAMETER(initial_map_t,        initial_map)
CGAL_DEM_ADD_NAMED_PARAMETER(mobius_area_correction_t, mobius_area_correction)
CGAL_DEM_ADD_NAMED_PARAMETER(truncation_t,         truncation)
CGAL_DEM_ADD_NAMED_PARAMETER(landmarks_t,          landmarks)
CGAL_DEM_ADD_NAMED_PARAMETER(density_weight_t,     density_weight)
CGAL_DEM_ADD_NAMED_PARAMETER(harmonic_weight_t,    harmonic_weight)
CGAL_DEM_ADD_NAMED_PARAMETER(landmark_weight_t,    landmark_weight)
CGAL_DEM_ADD_NAMED_PARAMETER(beltrami_weight_t,    beltrami_weight)
CGAL_DEM_ADD_NAMED_PARAMETER(pole_vertices_t,      pole_vertices)
CGAL_DEM_ADD_NAMED_PARAMETER(optimize_radii_t,     optimize_radii)
CGAL_DEM_ADD_NAMED_PARAMETER(torus_radii_t,        torus_radii)
CGAL_DEM_ADD_NAMED_PARAMETER(cut_edges_t,          cut_edges)
CGAL_DEM_ADD_NAMED_PARAMETER(flat_torus_coordinates_t, flat_torus_coordinates)
CGAL_DEM_ADD_NAMED_PARAMETER(flat_torus_offsets_t,     flat_torus_offsets)
CGAL_DEM_ADD_NAMED_PARAMETER(progress_callback_t,  progress_callback)
CGAL_DEM_ADD_NAMED_PARAMETER(stage_callback_t,     stage_callback)
CGAL_DEM_ADD_NAMED_PARAMETER(sea_density_t,        sea_density)
CGAL_DEM_ADD_NAMED_PARAMETER(overlap_subdivision_t, overlap_subdivision)
CGAL_DEM_ADD_NAMED_PARAMETER(relative_area_tolerance_t, relative_area_tolerance)
CGAL_DEM_ADD_NAMED_PARAMETER(number_of_passes_t,   number_of_passes)
CGAL_DEM_ADD_NAMED_PARAMETER(boundary_step_t,      boundary_step)
CGAL_DEM_ADD_NAMED_PARAMETER(torus_lattice_t,      torus_lattice)
CGAL_DEM_ADD_NAMED_PARAMETER(pass_callback_t,      pass_callback)
CGAL_DEM_ADD_NAMED_PARAMETER(coarse_globe_vertices_t, coarse_globe_vertices)
CGAL_DEM_ADD_NAMED_PARAMETER(concurrency_tag_t,    concurrency_tag)
#undef CGAL_DEM_ADD_NAMED_PARAMETER

namespace internal {
// push the entries of `np2` (innermost first) on top of `np1`
template <typename NP1, typename T, typename Tag>
CGAL::Named_function_parameters<T, Tag, NP1>
append(const NP1& np1, const CGAL::Named_function_parameters<T, Tag, CGAL::internal_np::No_property>& np2)
{ return CGAL::Named_function_parameters<T, Tag, NP1>(np2.v, np1); }

template <typename NP1, typename T, typename Tag, typename Base>
auto append(const NP1& np1, const CGAL::Named_function_parameters<T, Tag, Base>& np2)
{
  auto inner = internal::append(np1, static_cast<const Base&>(np2));
  return CGAL::Named_function_parameters<T, Tag, decltype(inner)>(np2.v, inner);
}
} // namespace internal

// combine(np1, np2, ...): one CGAL pack with every entry; for a repeated name the later pack wins
template <typename NP>
NP combine(const NP& np) { return np; }

template <typename NP1, typename NP2, typename... NPs>
auto combine(const NP1& np1, const NP2& np2, const NPs&... nps)
{ return combine(internal::append(np1, np2), nps...); }

} // namespace parameters
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_PARAMETERS_H
