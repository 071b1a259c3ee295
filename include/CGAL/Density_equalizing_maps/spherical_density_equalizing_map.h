// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_DENSITY_EQUALIZING_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_DENSITY_EQUALIZING_MAP_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/ellipsoid_domain.h>
#include <CGAL/Density_equalizing_maps/internal/elongated_starts.h>
#include <CGAL/Density_equalizing_maps/internal/engine_parameters.h>
#include <CGAL/Density_equalizing_maps/internal/landmark_flow.h>
#include <CGAL/Density_equalizing_maps/internal/spherical_conformal.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <limits>
#include <sstream>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// The starting sphere: the user's `initial_map` (checked: finite, no point at
/// the center, bijective; `Invalid_input` otherwise), else the spherical
/// conformal map with the Moebius correction of paper 001, towards the
/// population when that is closer to uniform density (population_mobius_start()),
/// which is bijective
/// in exact arithmetic: if its exact fold-over count is not 0 the computation
/// failed (`Algorithm_failure`), the input is not at fault. Given the
/// `population` (SDEM), an elongated surface also tries axial_start() and
/// ellipsoidal_start() and starts from whichever map has
/// the image density closer to uniform (mean_abs_log_density()); the report's
/// message says when the ellipsoidal start was taken.
template <class TriangleMesh, class NamedParameters>
Matrix initial_spherical_map(const Mesh_arrays<TriangleMesh>& a, const NamedParameters& np, const Spd_solver& solver,
                             Map_report& report, const Vector* population = nullptr)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Matrix S;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::initial_map_t>::value) {
    S = read_points(a, get_parameter(np, internal_np::initial_map));
    validate_spherical_points(S, "the initial map");
    normalize_rows(S);
    const std::size_t folds = count_inverted_faces_about_center(S, a.F);
    report.start = "initial_map";
    if(folds > 0)
      throw Invalid_input("the initial map is not bijective: " + std::to_string(folds) + " fold-overs (exact count)");
  } else {
    const Stage_notifier stage = stage_notifier_from_parameters(np);
    const Flash_result flash = flash_spherical_map(a.X, a.F, solver, stage);
    report.used_tutte_fallback = flash.tutte;
    report.add_fallback(flash.fallback.empty() ? "" : "initial map: " + flash.fallback);
    report.repairs += flash.repairs;
    begin_stage(stage, "Moebius area correction");
    bool by_population = false;
    S = population ? population_mobius_start(a.X, a.F, flash.S, *population, by_population)
                   : mobius_area_correction(a.X, a.F, flash.S);
    report.start = by_population ? "conformal_population_moebius" : "conformal";
    const std::size_t folds = count_inverted_faces_about_center(S, a.F);
    const Principal_frame frame = principal_frame(a.X);
    if(population && frame.extent.maxCoeff() >= elongation_of_crowding * frame.extent.minCoeff()) {
      begin_stage(stage, "starting maps of an elongated surface");
      const double conformal = folds > 0 ? std::numeric_limits<double>::infinity()
                                         : mean_abs_log_density(*population, face_areas(S, a.F));
      double best = conformal;
      auto consider = [&](Matrix candidate, const char* start, const char* name) {
        if(candidate.rows() == 0) return;
        const double spread = mean_abs_log_density(*population, face_areas(candidate, a.F));
        if(!(spread < best)) return;
        std::ostringstream note;
        note << "initial map: " << name << " (mean |log density| " << spread << ", against ";
        if(folds > 0) note << "a Moebius-corrected conformal map with " << folds << " fold-overs)";
        else note << conformal << " for the Moebius-corrected conformal map)";
        report.message = note.str();
        best = spread;
        report.start = start;
        S = std::move(candidate);
      };
      consider(axial_start(a.X, a.F, frame), "axial", "along the principal axis, latitudes by area");
      consider(ellipsoidal_start(a.X, a.F, frame, flash, solver), "ellipsoidal",
               "the conformal map onto the bounding-box ellipsoid scaled onto the sphere");
      if(best < conformal) return S;
    }
    if(folds > 0)
      throw Algorithm_failure("the computed initial spherical map (conformal map with Moebius area correction) is "
                              "not bijective: " + std::to_string(folds) + " fold-overs (exact count); " +
                              crowding_note(a.X, a.F, S));
  }
  return S;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsSphere
/// \brief Computes the spherical density-equalizing map (SDEM) of a genus-0 closed mesh.
///
/// Starting from a bijective spherical map, the vertices flow on the unit sphere
/// with the velocity \f$ -\nabla\rho/\rho \f$ of a density \f$ \rho \f$ that
/// diffuses (Lyu, Lui, Choi 2024): regions of high population grow, regions of
/// low population shrink, until the density (population / image area) is uniform.
/// With the default population (the face areas of the input) the result is an
/// area-preserving parameterization. Every step is checked for fold-overs with
/// exact predicates; the faces of a folding step are untangled locally and the
/// step is halved if that fails; if no fold-over-free step can be found
/// `Map_report::termination` is `Termination::STALLED`. A run that does not
/// converge (stalled or at the iteration limit) returns the most uniform of its
/// maps (lowest sd/mean of the re-coupled density, the initial map included)
/// and says in `Map_report::message` when that is not the last one.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam VertexPointOutMap a writable vertex property map with 3D points as values
///
/// \param tm the input mesh: closed, manifold, connected, genus 0, no degenerate face
/// \param sphere_map receives the image of each vertex on the unit sphere
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{face_population_map}
///     \cgalParamDescription{a readable face property map with the positive population of each face}
///     \cgalParamDefault{the face areas of the input (area-preserving map)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_density_map}
///     \cgalParamDescription{alternatively, a positive density per vertex; the population of a face is its area times the mean density of its corners}
///     \cgalParamDefault{unused}
///   \cgalParamNEnd
///   \cgalParamNBegin{initial_map}
///     \cgalParamDescription{a readable vertex property map with a bijective starting map onto the sphere}
///     \cgalParamDefault{`spherical_conformal_map()` with Moebius area correction, or, when that brings the density
///       closer to uniform, followed by the Moebius transformation that minimizes the mean |log density| (its
///       dilation limited so that no face turns over)}
///   \cgalParamNEnd
///   \cgalParamNBegin{time_step}
///     \cgalParamDescription{the step \f$\delta t\f$ of diffusion and advection}
///     \cgalParamType{double}
///     \cgalParamDefault{0.1}
///   \cgalParamNEnd
///   \cgalParamNBegin{stopping_tolerance}
///     \cgalParamDescription{stop when sd/mean of the diffused vertex density is below it}
///     \cgalParamType{double}
///     \cgalParamDefault{1e-3}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_iterations}
///     \cgalParamDescription{maximum number of iterations}
///     \cgalParamType{unsigned int}
///     \cgalParamDefault{200}
///   \cgalParamNEnd
///   \cgalParamNBegin{truncation}
///     \cgalParamDescription{the Beltrami coefficient of an inverted face is set to modulus 1 - truncation before the LBS repair of a folding step (used by `landmark_aligned_spherical_density_equalizing_map()` only: the other flows untangle a folding step locally)}
///     \cgalParamType{double}
///     \cgalParamDefault{0.1}
///   \cgalParamNEnd
///   \cgalParamNBegin{progress_callback}
///     \cgalParamDescription{a callable `bool(std::size_t iteration, double error)` called once per iteration; returning `false` stops with the last bijective map (`Termination::CANCELLED`)}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map, vertex_index_map}
///     \cgalParamDescription{as for `spherical_conformal_map()`}
///   \cgalParamNEnd
///   \cgalParamNBegin{stage_callback}
///     \cgalParamDescription{a callable `void(const std::string& stage)` called as each stage starts (validation,
///       harmonic map, south-chart LBS correction, Moebius area correction, the iterations, ...), so that a
///       progress display can name a long direct stage}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver}
///     \cgalParamDescription{a model of `SparseLinearAlgebraWithFactorTraits_d` for the SPD systems}
///     \cgalParamDefault{`Default_sparse_solver_traits` for the initial map and the Beltrami repairs (LSDEM); the
///       diffusion steps, one per iteration on a slowly moving mesh, use conjugate gradients warm-started from
///       the previous iterations and preconditioned by a factorization of an earlier diffusion matrix (Jacobi
///       below 4000 vertices), refactored only when it stops being effective. If given, this solver is used
///       for every system.}
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
/// \pre the population (`face_population_map`) or density (`vertex_density_map`), when given, is
///      positive and finite on every face or vertex (checked)
/// \pre `initial_map`, when given, is a fold-over-free map of `tm` onto the unit sphere (checked)
/// \returns a `Map_report` (iterations, termination, final sd/mean, fold-overs = 0 unless stalled from the start)
/// \throws Invalid_input on an invalid mesh, population or parameter (including an `initial_map` that is not
///   finite, sends a vertex to the center or is not bijective); nothing is written then.
/// \throws Algorithm_failure if the computed starting map is not bijective or a linear solve of it failed;
///   nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report spherical_density_equalizing_map(const TriangleMesh& tm, VertexPointOutMap sphere_map,
                                            const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const internal::Engine_options options = internal::engine_options_from_parameters(np, 0.1, 1e-3, 200);
  const double truncation = internal::truncation_from_parameters(np);
  const auto solver = internal::solver_from_parameters(np);
  const auto diffusion_solver = internal::diffusion_solver_from_parameters(np);

  Map_report report;
  internal::Matrix x = internal::initial_spherical_map(a, np, *solver, report, &population);
  internal::Ellipsoid_domain sphere(a.F, x, Eigen::Vector3d::Ones(), truncation, *solver);
  internal::Density_flow flow;
  const internal::Engine_result r = internal::run_density_equalization(sphere, flow, x, population, options, *diffusion_solver);

  internal::fill_report(r, report);
  report.fold_overs = sphere.fold_overs(x);
  internal::write_points(a, x, sphere_map);
  return report;
}

/// \ingroup PkgDensityEqualizingMapsSphere
/// \brief Computes the landmark-aligned spherical density-equalizing map (LSDEM).
///
/// Minimizes \f$ \alpha E_{density} + \beta E_{harmonic} + \gamma E_{landmark} \f$
/// over maps onto the unit sphere: the SDEM flow, plus Laplacian smoothing of the
/// map and a pull of each landmark vertex towards its target. Before each step
/// the sphere is rotated by the rotation that best aligns the landmarks with
/// their targets, computed in closed form (Kabsch) where the paper uses gradient
/// descent over Euler angles: it is the global minimizer of the same term.
/// Stops when the largest vertex update (sum of absolute coordinate changes)
/// falls below the tolerance. A folding step is first rebuilt with the Linear
/// Beltrami Solver in two stereographic charts, then untangled and halved as in
/// `spherical_density_equalizing_map()` (without the chart repair the untangling
/// undoes the landmark pull: the landmark error grows with `landmark_weight`).
///
/// \tparam Landmarks a range of `std::pair<vertex_descriptor, Point_3>`; targets must lie on the unit
///         sphere (within 1e-4; they are then normalized)
///
/// \param tm the input mesh (genus 0, closed)
/// \param landmarks the landmark vertices and their targets
/// \param sphere_map receives the map
/// \param np as `spherical_density_equalizing_map()`, plus:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{density_weight}
///     \cgalParamDescription{\f$\alpha\f$}
///     \cgalParamType{double}
///     \cgalParamDefault{1}
///   \cgalParamNEnd
///   \cgalParamNBegin{harmonic_weight}
///     \cgalParamDescription{\f$\beta\f$}
///     \cgalParamType{double}
///     \cgalParamDefault{2}
///   \cgalParamNEnd
///   \cgalParamNBegin{landmark_weight}
///     \cgalParamDescription{\f$\gamma\f$}
///     \cgalParamType{double}
///     \cgalParamDefault{5}
///   \cgalParamNEnd
///   \cgalParamNBegin{time_step}
///     \cgalParamDescription{step size}
///     \cgalParamType{double}
///     \cgalParamDefault{0.01}
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
/// \pre `landmarks` is not empty, names vertices of `tm`, and every target is a point of
///      the unit sphere (checked)
/// \pre the weights `density_weight`, `harmonic_weight` and `landmark_weight` are non-negative
///      (checked)
/// \returns a `Map_report` with `landmark_error` = mean distance between mapped landmarks and targets
/// \throws Invalid_input on an invalid mesh, population or parameter, an empty landmark set, a landmark vertex
///   out of range or listed more than once, a target off the unit sphere or non-finite; nothing is written then.
/// \throws Algorithm_failure if the harmonic-energy system cannot be factored or the computed starting map is
///   not bijective; nothing is written then.
template <class TriangleMesh, class Landmarks, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report landmark_aligned_spherical_density_equalizing_map(const TriangleMesh& tm, const Landmarks& landmarks,
                                                             VertexPointOutMap sphere_map,
                                                             const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const internal::Engine_options options = internal::engine_options_from_parameters(np, 0.01, 1e-3, 200);
  const double truncation = internal::truncation_from_parameters(np);

  internal::Landmark_flow flow;
  internal::read_landmarks(tm, landmarks, np, flow.vertices, flow.targets);
  if(flow.vertices.empty()) throw Invalid_input("no landmarks given");
  for(Eigen::Index k = 0; k < flow.targets.rows(); ++k) {
    const double r = flow.targets.row(k).norm();
    if(std::abs(r - 1) > 1e-4)
      throw Invalid_input("landmark " + std::to_string(k) + ": target is not on the unit sphere (norm " +
                          std::to_string(r) + ")");
    flow.targets.row(k) /= r;
  }
  flow.alpha = choose_parameter(get_parameter(np, internal_np::density_weight), 1.);
  flow.beta = choose_parameter(get_parameter(np, internal_np::harmonic_weight), 2.);
  flow.gamma = choose_parameter(get_parameter(np, internal_np::landmark_weight), 5.);
  if(!(flow.alpha >= 0 && flow.beta >= 0 && flow.gamma >= 0))
    throw Invalid_input("the weights alpha, beta, gamma must be non-negative");

  const auto solver = internal::solver_from_parameters(np);
  const auto diffusion_solver = internal::diffusion_solver_from_parameters(np);
  if(!flow.prepare(a.X, a.F, options.time_step, *solver))
    throw Algorithm_failure("the harmonic-energy system of the input mesh could not be factored");
  Map_report report;
  internal::Matrix x = internal::initial_spherical_map(a, np, *solver, report);
  internal::Ellipsoid_domain sphere(a.F, x, Eigen::Vector3d::Ones(), truncation, *solver, true);
  const internal::Engine_result r = internal::run_density_equalization(sphere, flow, x, population, options, *diffusion_solver);

  internal::fill_report(r, report);
  report.fold_overs = sphere.fold_overs(x);
  report.landmark_error = flow.mean_landmark_error(x);
  internal::write_points(a, x, sphere_map);
  return report;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_SPHERICAL_DENSITY_EQUALIZING_MAP_H
