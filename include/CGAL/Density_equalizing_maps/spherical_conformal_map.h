// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_CONFORMAL_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_CONFORMAL_MAP_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/input.h>
#include <CGAL/Density_equalizing_maps/internal/spherical_conformal.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsSphere
/// \brief Computes a bijective conformal map of a genus-0 closed triangle mesh onto the unit sphere.
///
/// The map is computed as in FLASH (Choi, Lam, Lui 2015): a harmonic map of
/// the mesh punctured at its most regular face onto the plane, inverse
/// stereographic projection, then a quasi-conformal correction with the Linear
/// Beltrami Solver in the opposite stereographic chart. A Tutte embedding
/// replaces the harmonic map if the latter fails. Optionally a Moebius
/// transformation minimizing the mean absolute log area ratio is applied
/// (the map stays conformal).
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam VertexPointOutMap a model of `WritablePropertyMap` with the vertex
///         descriptor as key and a 3D point type constructible from three doubles as value
///
/// \param tm the input mesh: closed, manifold, connected, genus 0, no degenerate face
/// \param sphere_map receives the image of each vertex on the unit sphere
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{the input positions}
///     \cgalParamDefault{`get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map}
///     \cgalParamDescription{a map from vertices to indices 0..n-1}
///     \cgalParamDefault{an internal or dynamically filled map}
///   \cgalParamNEnd
///   \cgalParamNBegin{mobius_area_correction}
///     \cgalParamDescription{apply the Moebius area correction}
///     \cgalParamType{bool}
///     \cgalParamDefault{`false`}
///   \cgalParamNEnd
///   \cgalParamNBegin{stage_callback}
///     \cgalParamDescription{a callable `void(const std::string& stage)` called as each stage starts (validation,
///       harmonic map, south-chart LBS correction, Moebius area correction, the iterations, ...), so that a
///       progress display can name a long direct stage}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver}
///     \cgalParamDescription{a model of `SparseLinearAlgebraWithFactorTraits_d` for the SPD systems}
///     \cgalParamDefault{`Default_sparse_solver_traits`}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \returns a `Map_report` whose `fold_overs` is the exact count of inverted faces
/// \throws Invalid_input if the mesh is not a valid genus-0 closed surface; nothing is written then.
/// \throws Algorithm_failure if neither the harmonic map nor the Tutte embedding could be computed (linear
///   solver failure or non-finite result); nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report spherical_conformal_map(const TriangleMesh& tm, VertexPointOutMap sphere_map,
                                   const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  const auto solver = internal::solver_from_parameters(np);
  const internal::Stage_notifier stage = internal::stage_notifier_from_parameters(np);
  internal::Flash_result flash = internal::flash_spherical_map(a.X, a.F, *solver, stage);
  internal::Matrix S = flash.S;
  if(choose_parameter(get_parameter(np, internal_np::mobius_area_correction), false)) {
    internal::begin_stage(stage, "Moebius area correction");
    S = internal::mobius_area_correction(a.X, a.F, S);
  }
  internal::begin_stage(stage, "exact fold-over count");
  Map_report report;
  report.used_tutte_fallback = flash.tutte;
  report.add_fallback(flash.fallback);
  report.repairs = flash.repairs;
  report.fold_overs = internal::count_inverted_faces_about_center(S, a.F);
  if(report.fold_overs > 0) report.message = internal::crowding_note(a.X, a.F, S);
  internal::write_points(a, S, sphere_map);
  return report;
}

/// \ingroup PkgDensityEqualizingMapsSphere
/// \brief Applies to a spherical conformal map the Moebius transformation that
/// minimizes the mean absolute log area ratio between input faces and their images.
///
/// \param tm the input mesh (genus 0, closed)
/// \param sphere_map the spherical map to correct (readable vertex point map)
/// \param corrected_map receives the corrected map (may be the same map as `sphere_map`)
/// \param np `vertex_point_map`, `vertex_index_map` as for `spherical_conformal_map()`
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre `sphere_map` is a bijective map onto the sphere centred at the origin (points off the unit sphere
///   are projected radially onto it), as the output of `spherical_conformal_map()` is
/// \returns a `Map_report` with the fold-over count of the output
/// \throws Invalid_input if the mesh is not a valid genus-0 closed surface, or `sphere_map` has a
///   non-finite point, a point at the center, or an inverted face (exact count, after the radial
///   projection); nothing is written then.
template <class TriangleMesh, class VertexPointMap, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report mobius_area_correction(const TriangleMesh& tm, VertexPointMap sphere_map, VertexPointOutMap corrected_map,
                                  const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  internal::Matrix S = internal::read_points(a, sphere_map);
  internal::validate_spherical_points(S, "the spherical map");
  internal::normalize_rows(S);
  const std::size_t folds = internal::count_inverted_faces_about_center(S, a.F);
  if(folds > 0)
    throw Invalid_input("the spherical map is not bijective: " + std::to_string(folds) + " fold-overs (exact count)");
  internal::begin_stage(internal::stage_notifier_from_parameters(np), "Moebius area correction");
  const internal::Matrix Q = internal::mobius_area_correction(a.X, a.F, S);
  Map_report report;
  report.fold_overs = internal::count_inverted_faces_about_center(Q, a.F);
  internal::write_points(a, Q, corrected_map);
  return report;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_CONFORMAL_MAP_H
