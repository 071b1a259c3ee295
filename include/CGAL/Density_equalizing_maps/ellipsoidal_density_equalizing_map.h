// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_DENSITY_EQUALIZING_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_DENSITY_EQUALIZING_MAP_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/ellipsoid_domain.h>
#include <CGAL/Density_equalizing_maps/internal/elongated_starts.h>
#include <CGAL/Density_equalizing_maps/internal/engine_parameters.h>
#include <CGAL/Density_equalizing_maps/internal/radii_search_flow.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <boost/property_map/vector_property_map.hpp>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Relative distance tolerance under which an input surface counts as lying
/// on the target ellipsoid already.
constexpr double on_ellipsoid_tolerance = 1e-3;

/// The starting ellipsoidal map: the user's `initial_map` (projected radially
/// onto the ellipsoid; it must be bijective); else the input surface itself
/// when it already lies on the target ellipsoid (within
/// `on_ellipsoid_tolerance`) and is star-shaped about its center, as in the
/// experiments of paper 000 (a cartogram on an ellipsoid starts from the
/// ellipsoid, not from a conformal re-parameterization of it); else the better
/// of two bijective candidates: the ellipsoidal conformal map with the same
/// radii, and the Moebius-corrected spherical conformal map (population_mobius_start())
/// scaled by the radii (a linear image of a bijective spherical map, hence bijective). "Better" is
/// the one whose density (population / image area) is closer to uniform: on
/// strongly anisotropic ellipsoids the ellipsoidal conformal map has a large
/// area distortion and the flow from it is slow to equalize. An elongated
/// surface (see elongated_starts.h) also tries axial_start() scaled by the
/// radii, which does not crowd where both conformal maps do.
template <class TriangleMesh, class NamedParameters>
Matrix initial_ellipsoidal_map(const TriangleMesh& tm, const Mesh_arrays<TriangleMesh>& a,
                               const Eigen::Vector3d& radii, const Vector& population, const NamedParameters& np,
                               const Spd_solver& solver, std::string& note, Map_report& fallbacks)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Matrix x;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::initial_map_t>::value) {
    x = read_points(a, get_parameter(np, internal_np::initial_map));
    if(!x.allFinite()) throw Invalid_input("the initial map has non-finite coordinates");
    project_to_ellipsoid(x, radii);
    const std::size_t folds = count_inverted_faces_about_center(x, a.F);
    if(folds > 0)
      throw Invalid_input("the initial ellipsoidal map is not bijective: " + std::to_string(folds) +
                          " fold-overs (exact count)");
    fallbacks.start = "initial_map";
    return x;
  } else {
    if(max_ellipsoid_deviation(a.input_positions(), radii) <= on_ellipsoid_tolerance) {
      x = a.input_positions(); // the radii are in the input's units
      project_to_ellipsoid(x, radii);
      if(count_inverted_faces_about_center(x, a.F) == 0) {
        note = "the input lies on the ellipsoid: started from it. ";
        fallbacks.start = "input";
        return x;
      }
    }
    auto density_error = [&](const Matrix& y) { return vertex_density_spread(population, y, a.F); };
    const Flash_result flash = flash_spherical_map(a.X, a.F, solver);
    bool by_population = false;
    const Matrix scaled_sphere =
      Ellipsoid_domain::from_unit_sphere(population_mobius_start(a.X, a.F, flash.S, population, by_population), radii);
    typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point;
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    boost::vector_property_map<Point, decltype(vim)> fecm(a.vertices.size(), vim);
    const std::array<double, 3> r = {radii[0], radii[1], radii[2]};
    const Map_report conformal =
      ellipsoidal_conformal_map(tm, fecm, parameters::combine(np, parameters::ellipsoid_radii(r)));
    x = read_points(a, fecm);
    project_to_ellipsoid(x, radii);
    // both conformal candidates start from the same FLASH map: one fallback to report
    fallbacks.used_tutte_fallback = flash.tutte;
    fallbacks.add_fallback(flash.fallback.empty() ? "" : "initial map: " + flash.fallback);
    auto usable = [&](const Matrix& y) {
      return y.rows() > 0 && y.allFinite() && count_inverted_faces_about_center(y, a.F) == 0;
    };
    const double fecm_error = usable(x) ? density_error(x) : std::numeric_limits<double>::infinity();
    const double scaled_error = usable(scaled_sphere) ? density_error(scaled_sphere)
                                                      : std::numeric_limits<double>::infinity();
    // an elongated surface: the axial start along the axis of the largest radius, scaled by the radii
    const Principal_frame frame = principal_frame(a.X, &radii);
    if(frame.extent.maxCoeff() >= elongation_of_crowding * frame.extent.minCoeff()) {
      int axis = 0;
      radii.maxCoeff(&axis);
      const Matrix axial = axial_start(a.X, a.F, frame, axis, radii);
      if(axial.rows() > 0) {
        Matrix y = Ellipsoid_domain::from_unit_sphere(axial, radii);
        const double axial_error = usable(y) ? density_error(y) : std::numeric_limits<double>::infinity();
        if(axial_error < std::min(fecm_error, scaled_error)) {
          note = "started from the map along the principal axis (an elongated surface: closer to uniform density "
                 "than both conformal maps). ";
          fallbacks.start = "axial";
          return y;
        }
      }
    }
    if(fecm_error <= scaled_error && std::isfinite(fecm_error)) {
      fallbacks.repairs += conformal.repairs;
      fallbacks.start = "conformal";
      return x;
    }
    fallbacks.repairs += flash.repairs;
    fallbacks.start = by_population ? "scaled_sphere_population_moebius" : "scaled_sphere";
    note = "started from the scaled spherical conformal map (closer to uniform density than the ellipsoidal "
           "conformal map). ";
    return scaled_sphere;
  }
}

template <class TriangleMesh, class NamedParameters>
Eigen::Vector3d ellipsoid_radii_from_parameters(const Mesh_arrays<TriangleMesh>& a, const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Eigen::Vector3d radii;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::ellipsoid_radii_t>::value) {
    const auto& r = get_parameter(np, internal_np::ellipsoid_radii);
    radii = Eigen::Vector3d(double(r[0]), double(r[1]), double(r[2]));
  } else {
    radii = bounding_box_radii(a.X);
  }
  check_radii(radii);
  return radii;
}

/// EDEM and EDEQ: the same start, domain and engine; they differ by the flow
/// (plain density equalization, or with the radius search) and its stopping
/// tolerance. `make_flow(F, population, x, options, diffusion_solver)` builds it.
template <class TriangleMesh, class VertexPointOutMap, class NamedParameters, class MakeFlow>
Map_report ellipsoidal_density_equalization(const TriangleMesh& tm, VertexPointOutMap ellipsoid_map,
                                            const NamedParameters& np, double default_tolerance,
                                            const MakeFlow& make_flow)
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = closed_surface_arrays(tm, np, 2);
  const Eigen::Vector3d radii = ellipsoid_radii_from_parameters(a, np);
  const Vector population = population_from_parameters(a, np);
  const Engine_options options = engine_options_from_parameters(np, 0.1, default_tolerance, 300);
  const double truncation = truncation_from_parameters(np);
  const auto solver = solver_from_parameters(np);
  const auto diffusion_solver = diffusion_solver_from_parameters(np);

  std::string note;
  Map_report report;
  begin_stage(options.stage, "initial map (spherical and ellipsoidal conformal maps)");
  Matrix x = initial_ellipsoidal_map(tm, a, radii, population, np, *solver, note, report);
  Ellipsoid_domain ellipsoid(a.F, x, radii, truncation, *solver);
  auto flow = make_flow(a.F, population, x, options, *diffusion_solver);
  const Engine_result r = run_density_equalization(ellipsoid, flow, x, population, options, *diffusion_solver);

  fill_report(r, report);
  report.message = note + report.message;
  report.fold_overs = ellipsoid.fold_overs(x);
  const Eigen::Vector3d& found = ellipsoid.radii();
  report.radii = {found[0], found[1], found[2]};
  write_points(a, x, ellipsoid_map);
  return report;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Computes the map onto the ellipsoid from which `ellipsoidal_density_equalizing_map()` and
/// `ellipsoidal_density_equalizing_quasiconformal_map()` start when no `initial_map` is given.
///
/// The input surface itself if it already lies on the ellipsoid (relative
/// distance at most 1e-3) with every face positively oriented about the
/// center; otherwise `ellipsoidal_conformal_map()` with the same radii, or the
/// Moebius-corrected spherical conformal map scaled by the radii when its
/// density is closer to uniform. Callers who want to measure or show the
/// starting map compute it here and pass it on as `initial_map`.
///
/// \param tm the input mesh (closed, genus 0)
/// \param initial_map receives the starting map (bijective, on the ellipsoid)
/// \param np `ellipsoid_radii`, `face_population_map` or `vertex_density_map`, `vertex_point_map`,
///   `vertex_index_map`, `sparse_linear_solver`, as for `ellipsoidal_density_equalizing_map()`
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre the population (`face_population_map`) or density (`vertex_density_map`), when given, is
///      positive and finite on every face or vertex (checked)
/// \pre the radii, if given, are positive and finite (checked)
/// \returns a `Map_report` whose `message` says which map was chosen, with the radii and the exact fold-over
///   count (0)
/// \throws Invalid_input on an invalid mesh, population or radii; nothing is written then.
/// \throws Algorithm_failure if the spherical or ellipsoidal conformal map could not be computed; nothing is
///   written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report ellipsoidal_density_equalizing_initial_map(const TriangleMesh& tm, VertexPointOutMap initial_map,
                                                      const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  const Eigen::Vector3d radii = internal::ellipsoid_radii_from_parameters(a, np);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const auto solver = internal::solver_from_parameters(np);
  Map_report report;
  const internal::Matrix x =
    internal::initial_ellipsoidal_map(tm, a, radii, population, np, *solver, report.message, report);
  if(report.message.empty()) report.message = "started from the ellipsoidal conformal map. ";
  report.termination = Termination::CONVERGED;
  report.fold_overs = internal::count_inverted_faces_about_center(x, a.F);
  report.radii = {radii[0], radii[1], radii[2]};
  internal::write_points(a, x, initial_map);
  return report;
}

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Computes the ellipsoidal density-equalizing map (EDEM) of a genus-0 closed mesh.
///
/// The density-equalizing flow of `spherical_density_equalizing_map()` run on
/// the ellipsoid \f$ x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 \f$ (Lyu, Lui, Choi 2026):
/// velocities are projected on the ellipsoid's tangent planes, vertices are
/// kept on it by radial projection, and fold-overs are repaired on the unit
/// sphere through \f$ h(x,y,z) = (x/a, y/b, z/c) \f$, a linear map that neither
/// creates nor removes fold-overs. The default population (input face areas)
/// gives an area-preserving ellipsoidal parameterization.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam VertexPointOutMap a writable vertex property map with 3D points as values
/// \param tm the input mesh (closed, genus 0)
/// \param ellipsoid_map receives the image of each vertex on the ellipsoid
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{ellipsoid_radii}
///     \cgalParamDescription{the radii (a, b, c), all positive, in the range of `ellipsoidal_conformal_map()`}
///     \cgalParamType{`std::array<double, 3>`}
///     \cgalParamDefault{the bounding-box radii of the input, normalized to mean 1}
///   \cgalParamNEnd
///   \cgalParamNBegin{initial_map}
///     \cgalParamDescription{a bijective starting map (projected radially onto the ellipsoid)}
///     \cgalParamDefault{the input surface itself if it already lies on the ellipsoid (relative distance
///       at most 1e-3) and every face is seen positively oriented from the center; otherwise
///       `ellipsoidal_conformal_map()` with the same radii, or the Moebius-corrected spherical conformal map
///       scaled by the radii if its density is closer to uniform (the report's message says which)}
///   \cgalParamNEnd
///   \cgalParamNBegin{face_population_map, vertex_density_map, time_step, truncation, progress_callback,
///     stage_callback, vertex_point_map, vertex_index_map, sparse_linear_solver}
///     \cgalParamDescription{as for `spherical_density_equalizing_map()`}
///   \cgalParamNEnd
///   \cgalParamNBegin{stopping_tolerance}
///     \cgalParamDescription{stop when sd/mean of the diffused vertex density is below it}
///     \cgalParamDefault{1e-3}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_iterations}
///     \cgalParamDescription{maximum number of iterations}
///     \cgalParamDefault{300}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre the population (`face_population_map`) or density (`vertex_density_map`), when given, is
///      positive and finite on every face or vertex (checked)
/// \pre the radii, if given, are positive and finite (checked)
/// \returns a `Map_report` with the radii used
/// \throws Invalid_input on an invalid mesh, population, radii or parameter, or an `initial_map` that is not
///   finite or not bijective; nothing is written then.
/// \throws Algorithm_failure if the default starting map could not be computed (see
///   `ellipsoidal_density_equalizing_initial_map()`); nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report ellipsoidal_density_equalizing_map(const TriangleMesh& tm, VertexPointOutMap ellipsoid_map,
                                              const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  return internal::ellipsoidal_density_equalization(
    tm, ellipsoid_map, np, 1e-3,
    [](const internal::Index_matrix&, const internal::Vector&, const internal::Matrix&, const internal::Engine_options&,
       const internal::Spd_solver&) { return internal::Density_flow(); });
}

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Computes the ellipsoidal density-equalizing quasi-conformal map (EDEQ) with optimized radii.
///
/// Minimizes \f$ E = E_{density} + \alpha E_{BC} \f$ by alternating the EDEM
/// step with a search over the radii: every 5 iterations the 9 radii
/// \f$ (a, b \pm \delta, c \pm \delta) \f$ (and mixed) with \f$ \delta = 0.1\cdot0.9^m \f$ are tried
/// and the one of least energy is kept (a is fixed: the scale is free). Stops
/// when the relative change of E is below the tolerance. The radii found are
/// in `Map_report::radii`.
///
/// \param tm the input mesh (closed, genus 0)
/// \param ellipsoid_map receives the map onto the final ellipsoid
/// \param np as `ellipsoidal_density_equalizing_map()` (`ellipsoid_radii` are the initial radii), plus:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{beltrami_weight}
///     \cgalParamDescription{the weight \f$\alpha\f$ of the Beltrami term}
///     \cgalParamType{double}
///     \cgalParamDefault{5}
///   \cgalParamNEnd
///   \cgalParamNBegin{stopping_tolerance}
///     \cgalParamDescription{stop when the relative change of the energy is below it}
///     \cgalParamDefault{1e-5}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre the population (`face_population_map`) or density (`vertex_density_map`), when given, is
///      positive and finite on every face or vertex (checked)
/// \pre the initial radii, if given, are positive and finite, and `beltrami_weight` is non-negative
///      (checked)
/// \returns a `Map_report` with the final radii and the exact fold-over count of the output
/// \throws Invalid_input, Algorithm_failure as `ellipsoidal_density_equalizing_map()`
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report ellipsoidal_density_equalizing_quasiconformal_map(const TriangleMesh& tm, VertexPointOutMap ellipsoid_map,
                                                             const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const double alpha = choose_parameter(get_parameter(np, internal_np::beltrami_weight), 5.);
  if(!(alpha >= 0) || !std::isfinite(alpha)) throw Invalid_input("beltrami_weight must be non-negative");
  return internal::ellipsoidal_density_equalization(
    tm, ellipsoid_map, np, 1e-5,
    [alpha](const internal::Index_matrix& F, const internal::Vector& population, const internal::Matrix& x,
            const internal::Engine_options& options, const internal::Spd_solver& diffusion_solver) {
      internal::Radii_search_flow flow(F, population, x, alpha, options.time_step, diffusion_solver);
      flow.start(x);
      return flow;
    });
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_DENSITY_EQUALIZING_MAP_H
