// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_CONFORMAL_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_CONFORMAL_MAP_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/ellipsoidal_conformal.h>
#include <CGAL/Density_equalizing_maps/internal/input.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <array>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

namespace internal {

/// Index of a vertex descriptor given by the user, checked against the mesh.
template <class TriangleMesh, class NamedParameters, class VertexDescriptor>
Eigen::Index checked_vertex_index(const TriangleMesh& tm, const NamedParameters& np,
                                  const Mesh_arrays<TriangleMesh>& a, const VertexDescriptor& v, const std::string& what)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const auto raw = get(vim, v);
  const long long i = static_cast<long long>(raw);
  if(i < 0 || i >= static_cast<long long>(a.vertices.size()) || !(a.vertices[static_cast<std::size_t>(i)] == v))
    throw Invalid_input(what + " is not a vertex of the mesh (index " + std::to_string(i) + " out of range 0.." +
                        std::to_string(a.vertices.size() - 1) + ")");
  return static_cast<Eigen::Index>(i);
}

/// Radii (given or bounding-box) and pole vertices (given or automatic) from the named parameters.
template <class TriangleMesh, class NamedParameters>
void ellipsoid_setup_from_parameters(const TriangleMesh& tm, const NamedParameters& np,
                                     const Mesh_arrays<TriangleMesh>& a, Eigen::Vector3d& radii,
                                     std::array<Eigen::Index, 3>& poles, bool* poles_given = nullptr)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Principal_frame frame;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::ellipsoid_radii_t>::value) {
    const auto& r = get_parameter(np, internal_np::ellipsoid_radii);
    radii = Eigen::Vector3d(double(r[0]), double(r[1]), double(r[2]));
    check_radii(radii);
    frame = principal_frame(a.X, &radii);
  } else {
    frame = principal_frame(a.X);
    radii = frame.extent / frame.extent.mean();
    check_radii(radii, "the default ellipsoid radii (bounding box of the mesh in its principal frame)");
  }
  if constexpr(!is_default_parameter<NamedParameters, internal_np::pole_vertices_t>::value) {
    const auto& pv = get_parameter(np, internal_np::pole_vertices);
    const char* names[3] = {"pole vertex 'top'", "pole vertex 'bottom'", "pole vertex 'right'"};
    for(int k = 0; k < 3; ++k) poles[k] = checked_vertex_index(tm, np, a, pv[k], names[k]);
    if(poles[0] == poles[1] || poles[0] == poles[2] || poles[1] == poles[2])
      throw Invalid_input("the three pole vertices (top, bottom, right) must be distinct (got indices " +
                          std::to_string(poles[0]) + ", " + std::to_string(poles[1]) + ", " +
                          std::to_string(poles[2]) + ")");
    if(poles_given) *poles_given = true;
  } else {
    poles = default_pole_vertices(a.X, frame);
    if(poles_given) *poles_given = false;
  }
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Returns the bounding-box ellipsoid radii (a, b, c) of a mesh (paper 003, Sec. 4.4.1).
///
/// The mesh is centred and its principal axes (PCA of the vertex positions)
/// are taken as coordinate axes; the sides of the bounding box in that frame,
/// divided by their mean, are the radii, so that (a + b + c) / 3 = 1. The
/// longest principal axis becomes the ellipsoid's z axis, the middle one its x
/// axis and the shortest its y axis, hence c >= a >= b. The mesh itself is not
/// modified. These are the default radii of `ellipsoidal_conformal_map()` and
/// `ellipsoidal_quasiconformal_map()`; passing them explicitly as
/// `ellipsoid_radii` gives the same map (the automatic poles match the
/// principal axes to the radii by size in both cases).
///
/// \param tm a closed genus-0 triangle mesh
/// \param np `vertex_point_map`, `vertex_index_map` as for `spherical_conformal_map()`
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre `tm` is not flat: its bounding box has a positive extent along each axis (checked)
/// \throws Invalid_input if the mesh is invalid, flat or so thin that its radii differ by more than a factor 1e6
/// \returns the radii (a, b, c), of mean 1
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::array<double, 3> bounding_box_ellipsoid_radii(const TriangleMesh& tm,
                                                   const NamedParameters& np = parameters::default_values())
{
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  const Eigen::Vector3d r = internal::bounding_box_radii(a.X);
  internal::check_radii(r, "the bounding-box radii of the mesh (in its principal frame)");
  return {r[0], r[1], r[2]};
}

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Computes a bijective conformal map of a genus-0 closed triangle mesh
/// onto the ellipsoid x²/a² + y²/b² + z²/c² = 1 (FECM, Choi 2024, paper 003 Sec. 4).
///
/// Steps: a FLASH spherical conformal map; the north stereographic chart; the
/// Möbius transformation sending the face at the *top* pole vertex to infinity,
/// the face at the *bottom* pole vertex to 0 and the *right* vertex onto the
/// positive real axis; the balancing factor k that gives both polar triangles
/// equal perimeters (paper eq. 29); then the quasi-conformal map ψ whose Beltrami coefficient
/// is that of the inverse ellipsoidal stereographic projection
/// \f$(P^N_{abc})^{-1}\f$, computed with the Linear Beltrami Solver on the
/// chart punctured at the north face. The output is
/// \f$f = (P^N_{abc})^{-1} \circ \psi^{-1}\f$ of the chart, which is conformal.
/// ψ⁻¹ is evaluated by point location in the triangulation of ψ's image with
/// barycentric interpolation of the chart, so every output point lies on the
/// ellipsoid up to rounding (the authors' code interpolates 3D points instead,
/// which leaves them slightly inside).
///
/// <b>Normalization of ψ</b> (the paper does not specify the boundary condition of ψ):
/// near the north pole ψ must behave like an anisotropic stretch (by a : b), not like
/// the identity. ψ is computed as ψ' ∘ A with the closed-form map
/// \f$A = P^N \circ \rho \circ (P^N_{abc})^{-1}\f$, ρ the radial projection of the ellipsoid
/// onto the unit sphere, so that \f$(P^N_{abc})^{-1} \circ A^{-1}\f$ is the radial
/// parameterization of the ellipsoid, conformal at both poles; ψ' (its Beltrami coefficient,
/// which vanishes at both poles) is the identity on the outer vertices up to the translation
/// that makes ψ'(0) = 0. So the bottom pole face goes to the south pole and the top one to the
/// north pole, as the Möbius step intends. Pinning ψ itself to the identity, as a direct
/// reading of the paper suggests, moves the south pole far away: an ellipsoid-shaped mesh
/// mapped onto its own radii then got mean |d_area| 1.35 instead of 0.011.
///
/// <b>Dilation</b> (deviation from the paper, on by default, `mobius_area_correction(false)`
/// restores the paper's map): the balancing factor k only equalizes the two polar
/// triangles and can leave a large area distortion (mean |d_area| 0.82 instead of 0.42
/// on maxplanck with the bounding-box radii). Since \f$\Phi = (P^N_{abc})^{-1} \circ \psi^{-1}\f$ is conformal, so is
/// \f$\Phi(t\,p)\f$ for any t > 0 (a Möbius map that keeps both poles and the right
/// vertex's direction); t is chosen by Brent's search on log t minimizing the
/// area distortion energy below. Each trial only relocates the dilated chart points in
/// ψ's triangulation (no new linear solve).
///
/// <b>Frame.</b> The output lies on the canonical ellipsoid centred at the origin
/// with axes along x, y, z; it is not expressed in the input's frame. The input
/// mesh is never modified: its centred principal frame (PCA of the vertex
/// positions) is used only to choose the default radii and the default poles.
/// The principal axes are matched by size to the ellipsoid axes (longest
/// principal axis to the axis of the largest radius, ...; with the default radii
/// the longest goes to z, the middle one to x). An axis-aligned input whose
/// extents are ordered like the radii thus keeps its orientation (up to the
/// translation to the origin).
///
/// <b>Radii optimization</b> (`optimize_radii(true)`, paper 003 Sec. 4.4.2): starting
/// from the given or bounding-box radii, minimizes the area distortion energy
/// \f$E = \frac{1}{|F|}\sum_T d_T^2\f$ (d_T the log area ratio with both areas
/// normalized by their exact sums; the paper approximates the ellipsoid area
/// by Thomsen's formula instead). E is scale invariant, so the radii are
/// parameterized by (log(a/c), log(b/c)) and scaled to (a + b + c) / 3 = 1. The
/// paper descends a gradient computed with the chart points ψ⁻¹(p) frozen; that model
/// ignores how the conformal correction moves points when the radii change and
/// pointed the wrong way on the shared meshes, so a Nelder–Mead simplex (at most 12
/// evaluations) minimizes the exact energy instead, each evaluation recomputing ψ and
/// the dilation for the trial radii. Steps up to the chart are computed once. The
/// report gives the energies before and after
/// (`initial_error`, `final_error`) and the number of simplex iterations.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam VertexPointOutMap a model of `WritablePropertyMap` with the vertex
///         descriptor as key and a 3D point type constructible from three doubles as value
///
/// \param tm the input mesh: closed, manifold, connected, genus 0, no degenerate face
/// \param ellipsoid_map receives the image of each vertex on the ellipsoid
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
///   \cgalParamNBegin{ellipsoid_radii}
///     \cgalParamDescription{the radii (a, b, c) of the target ellipsoid, all positive, each in [1e-100, 1e100],
///       the largest at most 1e6 times the smallest (independent of the scale of the mesh: the map is computed
///       in the ellipsoid's units)}
///     \cgalParamType{`std::array<double, 3>`}
///     \cgalParamDefault{`bounding_box_ellipsoid_radii(tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{optimize_radii}
///     \cgalParamDescription{optimize the radii for minimal area distortion, starting from `ellipsoid_radii`;
///                           the radii found are scaled to mean 1}
///     \cgalParamType{bool}
///     \cgalParamDefault{`false`}
///   \cgalParamNEnd
///   \cgalParamNBegin{mobius_area_correction}
///     \cgalParamDescription{choose the dilation t of the pole-normalized chart that minimizes the area
///                           distortion (the map stays conformal); `false` keeps the paper's balancing factor k}
///     \cgalParamType{bool}
///     \cgalParamDefault{`true`}
///   \cgalParamNEnd
///   \cgalParamNBegin{pole_vertices}
///     \cgalParamDescription{three distinct vertices (top, bottom, right): top goes near (0,0,c), bottom near
///                           (0,0,-c) and right onto the half-plane y = 0, x > 0}
///     \cgalParamType{`std::array<vertex_descriptor, 3>`}
///     \cgalParamDefault{in the centred principal frame matched to the radii: the vertices of largest and
///                       smallest coordinate along the ellipsoid's z axis and of largest coordinate along its x axis}
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
/// \pre the radii given with `ellipsoid_radii`, if any, are positive and finite, and the pole
///      vertices, if given, are distinct vertices of `tm` (checked)
/// \returns a `Map_report` with `radii` = the radii used (or found), `fold_overs` = the exact count of
/// faces not positively oriented about the ellipsoid's centre; with `optimize_radii`, `iterations`,
/// `initial_error` and `final_error` (area distortion energies)
/// \throws Invalid_input if the mesh is not a valid genus-0 closed surface, the radii are not positive,
/// finite and in the supported range: each in [1e-100, 1e100], the largest at most 1e6 times the smallest,
/// or the pole vertices are not three distinct vertices of the mesh; nothing is written then.
/// \throws Algorithm_failure if the spherical conformal map or the ellipsoidal chart could not be computed
/// (linear solver failure, non-finite result); nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report ellipsoidal_conformal_map(const TriangleMesh& tm, VertexPointOutMap ellipsoid_map,
                                     const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  Eigen::Vector3d radii;
  std::array<Eigen::Index, 3> poles;
  internal::ellipsoid_setup_from_parameters(tm, np, a, radii, poles);
  const bool optimize = choose_parameter(get_parameter(np, internal_np::optimize_radii), false);
  const auto solver = internal::solver_from_parameters(np);

  const bool dilate = choose_parameter(get_parameter(np, internal_np::mobius_area_correction), true);
  const internal::Stage_notifier stage = internal::stage_notifier_from_parameters(np);

  internal::begin_stage(stage, "spherical conformal map and ellipsoidal charts");
  const internal::Ellipsoidal_mapper mapper(a.X, a.F, poles, *solver);
  Map_report report;
  report.used_tutte_fallback = mapper.chart().tutte;
  report.add_fallback(mapper.chart().fallback);
  report.repairs = mapper.chart().repairs;
  internal::Matrix f;
  internal::begin_stage(stage, optimize ? "radii optimization" : "ellipsoidal conformal map");
  if(optimize) {
    internal::Radii_optimization opt = internal::optimize_ellipsoid_radii(mapper, radii, dilate);
    radii = opt.best.radii;
    f = std::move(opt.best.f);
    report.termination = Termination::CONVERGED;
    report.iterations = opt.iterations;
    report.initial_error = opt.initial_energy;
    report.final_error = opt.best.energy;
    std::ostringstream msg;
    msg << "area distortion energy " << opt.initial_energy << " -> " << opt.best.energy << " ("
        << opt.evaluations << " evaluations)";
    report.message = msg.str();
  } else {
    f = internal::evaluate_ellipsoidal_conformal(mapper, radii, internal::face_areas(a.X, a.F), dilate).f;
  }
  internal::begin_stage(stage, "fold check and repair");
  report.fold_overs = internal::repair_folded_ellipsoidal_map(mapper.flash(), a.F, radii, *solver, f, report);
  report.radii = {radii[0], radii[1], radii[2]};
  if(report.fold_overs > 0)
    report.message += (report.message.empty() ? "" : "; ") + internal::crowding_note(a.X, a.F, f);
  internal::write_points(a, f, ellipsoid_map);
  return report;
}

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Returns the radii that `ellipsoidal_conformal_map()` finds with `optimize_radii(true)`
/// (same named parameters; the radii have mean 1).
/// \param tm a closed genus-0 triangle mesh
/// \param np the named parameters of `ellipsoidal_conformal_map()`
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 0 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \returns the optimized radii (a, b, c)
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::array<double, 3> optimal_ellipsoid_radii(const TriangleMesh& tm,
                                              const NamedParameters& np = parameters::default_values())
{
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  Eigen::Vector3d radii;
  std::array<Eigen::Index, 3> poles;
  internal::ellipsoid_setup_from_parameters(tm, np, a, radii, poles);
  const auto solver = internal::solver_from_parameters(np);
  const bool dilate = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, internal_np::mobius_area_correction), true);
  const internal::Ellipsoidal_mapper mapper(a.X, a.F, poles, *solver);
  const Eigen::Vector3d r = internal::optimize_ellipsoid_radii(mapper, radii, dilate).best.radii;
  return {r[0], r[1], r[2]};
}

/// \ingroup PkgDensityEqualizingMapsEllipsoid
/// \brief Computes a landmark-aligned bijective quasi-conformal map of a genus-0
/// closed triangle mesh onto the ellipsoid x²/a² + y²/b² + z²/c² = 1 (FEQCM,
/// paper 003 Sec. 5).
///
/// After the steps of `ellipsoidal_conformal_map()` up to ψ, the landmark targets
/// are brought to the plane by ψ ∘ \f$P^N_{abc}\f$, the chart is aligned to them by
/// the least-squares similarity z ↦ s z (closed form), and the landmark-aligned
/// harmonic map minimizing \f$\int|\nabla\Phi|^2 + \lambda\sum_k|\Phi(p_k) - \tilde q_k|^2\f$
/// is computed with the north face pinned. If Φ folds, its Beltrami coefficient
/// is smoothed and truncated and the map rebuilt by the Linear Beltrami Solver
/// until it is fold-free (FLASH-style loop, at most 500 passes). The smoothing
/// fades over the passes as in the authors' code, but faster: its penalty
/// increment triples every pass instead of staying 0.5, so at large λ the loop
/// takes about a third of the passes (see benchmark/RESULTS.md); the loop also
/// runs, without the smoothing, while the composed map below still inverts a
/// face on the ellipsoid (thin faces that ψ⁻¹ and the lift turn over). The output is
/// \f$(P^N_{abc})^{-1} \circ \psi^{-1} \circ \Phi\f$. A larger `landmark_weight`
/// brings the landmarks closer to their targets at the price of more
/// conformal distortion. Frame, radii and dilation as for `ellipsoidal_conformal_map()`
/// (the radii are not optimized here). Without `pole_vertices`, the poles are chosen
/// so that the conformal map is oriented like the targets: an ellipsoidal conformal
/// map with the default poles is computed, the best rotation (Kabsch) taking its
/// landmark images to the targets (both pulled back to the unit sphere) is found, and
/// the poles are the vertices whose rotated images are highest, lowest and furthest
/// along +x. Landmark targets given in an arbitrary frame (e.g. on a sphere
/// parameterization) then need no large rotation by Φ.
///
/// \tparam LandmarkRange a range of pairs (vertex descriptor, point with `x()`, `y()`, `z()`),
///         e.g. `std::vector<std::pair<vertex_descriptor, Point_3>>`
///
/// \param tm the input mesh (genus 0, closed)
/// \param landmarks the landmark vertices and their targets on the ellipsoid: each target must satisfy
///        |x²/a² + y²/b² + z²/c² − 1| ≤ 1e-3 (targets read with a few decimals pass; they are used after
///        radial projection onto the ellipsoid, and the landmark error is measured to the given points);
///        a vertex may appear once
/// \param ellipsoid_map receives the image of each vertex
/// \param np optional named parameters: those of `ellipsoidal_conformal_map()` except `optimize_radii`, and
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{landmark_weight}
///     \cgalParamDescription{the weight λ > 0 of the landmark mismatch}
///     \cgalParamType{double}
///     \cgalParamDefault{1}
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
/// \pre `landmarks` is not empty, names distinct vertices of `tm`, and every target lies on the
///      ellipsoid of the radii used (checked)
/// \pre `landmark_weight` is positive and finite (checked)
/// \returns a `Map_report` with `landmark_error` = the mean distance between mapped landmarks and their
/// targets, `radii`, `iterations` = passes of the bijectivity loop, `termination` = `MAXIMUM_ITERATIONS`
/// if the loop did not remove every planar fold, `landmarks_given_up` when the fold-free output had to
/// drop the landmark constraints (a failure of the method), and `fold_overs` = the exact count on the output
/// \throws Invalid_input for an invalid mesh, radii or pole vertices, an empty landmark set, a landmark
/// vertex not in the mesh or listed twice, a target not on the ellipsoid, or a non-positive weight
/// \throws Algorithm_failure as `ellipsoidal_conformal_map()`
template <class TriangleMesh, class LandmarkRange, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report ellipsoidal_quasiconformal_map(const TriangleMesh& tm, const LandmarkRange& landmarks,
                                          VertexPointOutMap ellipsoid_map,
                                          const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const auto a = internal::closed_surface_arrays(tm, np, 2);
  Eigen::Vector3d radii;
  std::array<Eigen::Index, 3> poles;
  bool poles_given = false;
  internal::ellipsoid_setup_from_parameters(tm, np, a, radii, poles, &poles_given);
  const double lambda = choose_parameter(get_parameter(np, internal_np::landmark_weight), 1.);
  if(!std::isfinite(lambda) || !(lambda > 0))
    throw Invalid_input("the landmark weight must be positive and finite (got " + std::to_string(lambda) + ")");

  std::vector<Eigen::Index> idx;
  std::vector<Eigen::Vector3d> q;
  std::set<Eigen::Index> seen;
  for(const auto& lm : landmarks) {
    const std::string name = "landmark " + std::to_string(idx.size());
    const Eigen::Index i = internal::checked_vertex_index(tm, np, a, lm.first, name);
    if(!seen.insert(i).second)
      throw Invalid_input(name + ": vertex " + std::to_string(i) + " is listed more than once");
    const Eigen::Vector3d t(CGAL::to_double(lm.second.x()), CGAL::to_double(lm.second.y()),
                            CGAL::to_double(lm.second.z()));
    const double level = t.cwiseQuotient(radii).squaredNorm();
    if(!t.allFinite() || !(std::abs(level - 1) <= 1e-3)) {
      std::ostringstream msg;
      msg << name << " (vertex " << i << "): target (" << t.x() << ", " << t.y() << ", " << t.z()
          << ") is not on the ellipsoid with radii (" << radii[0] << ", " << radii[1] << ", " << radii[2]
          << "): x^2/a^2 + y^2/b^2 + z^2/c^2 = " << level;
      throw Invalid_input(msg.str());
    }
    idx.push_back(i);
    q.push_back(t);
  }
  if(idx.empty()) throw Invalid_input("no landmarks: the quasi-conformal map needs at least one landmark");
  internal::Matrix targets(static_cast<Eigen::Index>(q.size()), 3);
  for(std::size_t k = 0; k < q.size(); ++k) targets.row(static_cast<Eigen::Index>(k)) = q[k].transpose();

  const auto solver = internal::solver_from_parameters(np);
  const bool dilate = choose_parameter(get_parameter(np, internal_np::mobius_area_correction), true);
  const internal::Stage_notifier stage = internal::stage_notifier_from_parameters(np);
  const internal::Flash_result flash = internal::flash_spherical_map(a.X, a.F, *solver, stage);
  internal::begin_stage(stage, "ellipsoidal charts and landmark-matching quasi-conformal map");
  if(!poles_given) { // orient the conformal map like the targets before pulling the landmarks
    const internal::Ellipsoidal_mapper first(a.X, a.F, poles, *solver, flash);
    const internal::Matrix f0 =
      internal::evaluate_ellipsoidal_conformal(first, radii, internal::face_areas(a.X, a.F), dilate).f;
    poles = internal::landmark_aligned_pole_vertices(f0, radii, idx, targets);
  }
  const internal::Ellipsoidal_mapper mapper(a.X, a.F, poles, *solver, flash);
  internal::Conformal_correction psi;
  double t = 1;
  if(dilate) t = internal::evaluate_ellipsoidal_conformal(mapper, radii, internal::face_areas(a.X, a.F), true, 0, 3, &psi).dilation;
  else psi = mapper.conformal_correction(radii);
  internal::Quasiconformal_result res = internal::ellipsoidal_quasiconformal(mapper, psi, t, idx, targets, lambda);

  Map_report report;
  report.used_tutte_fallback = mapper.chart().tutte;
  report.add_fallback(mapper.chart().fallback);
  report.repairs = mapper.chart().repairs;
  internal::begin_stage(stage, "fold check and repair");
  report.fold_overs = internal::repair_folded_ellipsoidal_map(mapper.flash(), a.F, radii, *solver, res.f, report);
  report.radii = {radii[0], radii[1], radii[2]};
  report.iterations = res.passes;
  report.termination = res.planar_bijective ? Termination::CONVERGED : Termination::MAXIMUM_ITERATIONS;
  if(!res.planar_bijective) report.message = "the bijectivity loop did not remove every fold of the planar map";
  // the loop left folds, and the repair replaced the map by the fold-free
  // spherical start, which knows nothing of the landmarks
  report.landmarks_given_up = !res.planar_bijective && !report.fallback.empty();
  double err = 0;
  for(std::size_t k = 0; k < idx.size(); ++k) err += (internal::row_vector3(res.f, idx[k]) - q[k]).norm();
  report.landmark_error = err / double(idx.size());
  internal::write_points(a, res.f, ellipsoid_map);
  return report;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_ELLIPSOIDAL_CONFORMAL_MAP_H
