// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_SURFACE_REGISTRATION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_SURFACE_REGISTRATION_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/point_transfer.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/internal/landmark_warp.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/property_map/property_map.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsRegistration
/// The domain through which `register_surfaces()` builds the correspondence.
enum class Registration_domain
{
  SPHERE,   ///< landmark-aligned spherical density-equalizing maps (LSDEM, paper 001 §5.1)
  ELLIPSOID ///< landmark-aligned ellipsoidal quasi-conformal maps (FEQCM, paper 003 §5)
};

namespace internal_np {
enum registration_domain_t       { registration_domain };
enum target_face_population_t    { target_face_population };
enum target_location_map_t       { target_location_map };
} // namespace internal_np

namespace parameters {
/// \ingroup PkgDensityEqualizingMapsRegistration
/// Named parameter of `register_surfaces()`: the `Registration_domain`.
/// \param d the domain
/// \returns the named parameter
inline CGAL::Named_function_parameters<Registration_domain, internal_np::registration_domain_t>
registration_domain(Registration_domain d)
{ return CGAL::Named_function_parameters<Registration_domain, internal_np::registration_domain_t>(d); }

/// \ingroup PkgDensityEqualizingMapsRegistration
/// Named parameter of `register_surfaces()`: the population of the target's faces.
/// \param m a readable face property map of the target
/// \returns the named parameter
template <typename T>
CGAL::Named_function_parameters<T, internal_np::target_face_population_t> target_face_population_map(const T& m)
{ return CGAL::Named_function_parameters<T, internal_np::target_face_population_t>(m); }

/// \ingroup PkgDensityEqualizingMapsRegistration
/// Named parameter of `register_surfaces()`: receives, per source vertex, the target face and
/// barycentric coordinates of its corresponding point.
/// \param m a writable vertex property map of the source
/// \returns the named parameter
template <typename T>
CGAL::Named_function_parameters<T, internal_np::target_location_map_t> target_location_map(const T& m)
{ return CGAL::Named_function_parameters<T, internal_np::target_location_map_t>(m); }
} // namespace parameters

/// \ingroup PkgDensityEqualizingMapsRegistration
/// The landmark correction of one map of `register_surfaces()` (sphere route): a smooth warp of
/// the sphere that carries the map's landmark images onto the common landmark positions.
struct Landmark_correction
{
  /// the largest distance, on the unit sphere, between a landmark's image and its common position
  /// before the correction
  double error_before = 0;
  /// the same after the correction (0 up to rounding if `exact`)
  double error_after = 0;
  /// `true` if every landmark reached its common position; `false` if the warp would have folded the
  /// map, in which case the map was moved only as far as it stays fold-free (possibly not at all)
  bool exact = false;
};

/// \ingroup PkgDensityEqualizingMapsRegistration
/// What `register_surfaces()` computed.
struct Registration_report
{
  Registration_domain domain = Registration_domain::SPHERE; ///< the route taken
  Map_report source_map; ///< the map of the source onto the domain (`fold_overs`: exact count, 0)
  Map_report target_map; ///< the map of the target onto the domain (`fold_overs`: exact count, 0)
  /// the common position of each landmark pair on the domain, in the order of the pairs
  std::vector<std::array<double, 3> > landmark_positions;
  /// the radii of the ellipsoid (ellipsoid route), empty on the sphere
  std::vector<double> radii;
  /// sphere route: the correction of the source's and the target's conformal starting maps (landmarks
  /// moved onto the common positions before LSDEM), then of their LSDEM maps (the landmarks that LSDEM
  /// left off their positions moved back onto them); not applied on the ellipsoid route (all `exact` false)
  Landmark_correction source_start_correction, target_start_correction, source_correction, target_correction;
  /// mean and largest distance between a registered source landmark and its target landmark
  double landmark_error_mean = 0, landmark_error_max = 0;
  /// the length of the diagonal of the target's bounding box (divide the errors by it for relative values)
  double target_diagonal = 0;
  /// mean over the source faces of \f$ |\mu| \f$ and \f$ |d_{area}| \f$ of the registration map
  /// (source surface to registered points, see `map_distortion()`)
  double mean_abs_mu = 0, mean_abs_darea = 0;
  /// the image of every source / target vertex on the domain (in the order of the vertex index maps)
  std::vector<std::array<double, 3> > source_domain_points, target_domain_points;
  /// \returns `true`: a report is only returned for two fold-free maps
  bool is_bijective() const { return source_map.fold_overs == 0 && target_map.fold_overs == 0; }
};

namespace internal {

/// The pairs as vertex indices, checked: at least 3, every vertex in its mesh, no
/// vertex of either side in two pairs (a correspondence is one-to-one).
template <class SourceMesh, class TargetMesh, class LandmarkPairs, class NamedParameters>
void landmark_pair_indices(const SourceMesh& source, const TargetMesh& target, const LandmarkPairs& pairs,
                           const NamedParameters& np, const Mesh_arrays<SourceMesh>& as,
                           const Mesh_arrays<TargetMesh>& at, std::vector<Eigen::Index>& is,
                           std::vector<Eigen::Index>& it)
{
  std::map<Eigen::Index, std::size_t> seen_s, seen_t;
  for(const auto& p : pairs) {
    const std::size_t k = is.size();
    const std::string name = "landmark pair " + std::to_string(k);
    const Eigen::Index i = checked_vertex_index(source, np, as, p.first, name + ": the source vertex");
    const Eigen::Index j = checked_vertex_index(target, parameters::default_values(), at, p.second,
                                                name + ": the target vertex");
    const auto ds = seen_s.find(i), dt = seen_t.find(j);
    if(ds != seen_s.end() && dt != seen_t.end() && ds->second == dt->second)
      throw Invalid_input(name + " (" + std::to_string(i) + ", " + std::to_string(j) + ") duplicates pair " +
                          std::to_string(ds->second));
    if(ds != seen_s.end())
      throw Invalid_input(name + ": source vertex " + std::to_string(i) + " is already in pair " +
                          std::to_string(ds->second) + " (each vertex may be in one pair)");
    if(dt != seen_t.end())
      throw Invalid_input(name + ": target vertex " + std::to_string(j) + " is already in pair " +
                          std::to_string(dt->second) + " (each vertex may be in one pair)");
    seen_s.emplace(i, k);
    seen_t.emplace(j, k);
    is.push_back(i);
    it.push_back(j);
  }
  if(is.size() < 3)
    throw Invalid_input("registration needs at least 3 landmark pairs (got " + std::to_string(is.size()) + ")");
}

/// Genus of a triangle mesh from its Euler characteristic, for the messages that
/// compare two surfaces (closedness and manifoldness are validated afterwards).
template <class TriangleMesh>
long euler_characteristic_of(const Mesh_arrays<TriangleMesh>& a)
{
  return long(a.X.rows()) - long(3 * a.F.rows()) / 2 + long(a.F.rows());
}

inline void check_registrable_topology(long euler_source, long euler_target)
{
  const auto genus = [](long chi) { return std::to_string((2 - chi) / 2); };
  if(euler_source != euler_target)
    throw Invalid_input("genus mismatch: the source surface has genus " + genus(euler_source) +
                        " and the target surface genus " + genus(euler_target) +
                        "; registration needs two surfaces of genus 0");
  if(euler_source != 2)
    throw Invalid_input("both surfaces have genus " + genus(euler_source) +
                        "; registration through the sphere or the ellipsoid needs genus 0");
}

/// The Moebius area correction of a registration's starting map, searched on a sample of
/// about 4000 faces only. `mobius_area_correction()` then polishes the sample's optimum on
/// all faces, 12-18 % of the CPU time of a 25,000-face registration; here the starting map
/// only needs the Moebius freedom fixed the same way for both surfaces (the landmark
/// correction and LSDEM move it afterwards), and skipping the polish changed the mean
/// registration error by less than 0.01 % of the diagonal (benchmark/RESULTS.md, issue 18,
/// second section). Never worse than no correction on all faces; the dilation is kept
/// fold-free as in every Moebius correction (`internal::mobius_correction()`, whose first
/// stage this is).
inline Matrix sampled_mobius_area_correction(const Matrix& X, const Index_matrix& F, const Matrix& S)
{
  return mobius_correction(face_areas(X, F), F, S, nullptr, nullptr, Mobius_search::sample_only);
}

/// The area-corrected spherical conformal map (the LSDEM starting map), checked fold-free.
inline Matrix registration_start_on_sphere(const Matrix& X, const Index_matrix& F, const Spd_solver& solver,
                                           const char* which)
{
  const Flash_result flash = flash_spherical_map(X, F, solver);
  const Matrix S = sampled_mobius_area_correction(X, F, flash.S);
  const std::size_t folds = count_inverted_faces_about_center(S, F);
  if(folds > 0)
    throw Algorithm_failure(std::string("the conformal map of the ") + which + " surface is not bijective: " +
                            std::to_string(folds) + " fold-overs (exact count)");
  return S;
}

/// Common landmark positions on the unit sphere: `a` (source images) rotated by the
/// rotation R that best aligns them with `b` (target images), averaged with `b`, normalized.
inline Matrix common_landmark_directions(const Matrix& a, const Matrix& b, Eigen::Matrix3d& R)
{
  R = optimal_rotation(a, b);
  Matrix c(a.rows(), 3);
  for(Eigen::Index k = 0; k < a.rows(); ++k) {
    const Eigen::Vector3d m = R * row3(a, k) + row3(b, k);
    if(!(m.norm() > 1e-12))
      throw Algorithm_failure("landmark pair " + std::to_string(k) +
                              " lands at antipodal points of the two aligned conformal maps: no common position");
    c.row(k) = m.normalized().transpose();
  }
  return c;
}

inline Matrix rows_of(const Matrix& Y, const std::vector<Eigen::Index>& idx)
{
  Matrix out(Eigen::Index(idx.size()), 3);
  for(std::size_t k = 0; k < idx.size(); ++k) out.row(Eigen::Index(k)) = Y.row(idx[k]);
  return out;
}

typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Registration_point;

template <class TriangleMesh>
std::vector<std::pair<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, Registration_point> >
landmarks_at(const Mesh_arrays<TriangleMesh>& a, const std::vector<Eigen::Index>& idx, const Matrix& positions)
{
  std::vector<std::pair<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, Registration_point> > l;
  for(std::size_t k = 0; k < idx.size(); ++k) {
    const Eigen::Index r = Eigen::Index(k);
    l.emplace_back(a.vertices[std::size_t(idx[k])],
                   Registration_point(positions(r, 0), positions(r, 1), positions(r, 2)));
  }
  return l;
}

/// A vertex property map over the rows of a matrix of points (one per vertex index).
template <class TriangleMesh>
struct Row_point_maps
{
  std::vector<Registration_point> points;
  explicit Row_point_maps(const Matrix& Y)
  {
    points.reserve(std::size_t(Y.rows()));
    for(Eigen::Index i = 0; i < Y.rows(); ++i) points.emplace_back(Y(i, 0), Y(i, 1), Y(i, 2));
  }
  Row_point_maps(std::size_t n) : points(n) {}
  template <class VertexIndexMap>
  auto map(VertexIndexMap vim) { return boost::make_iterator_property_map(points.begin(), vim); }
  Matrix matrix() const
  {
    Matrix Y(Eigen::Index(points.size()), 3);
    for(std::size_t i = 0; i < points.size(); ++i)
      Y.row(Eigen::Index(i)) << points[i].x(), points[i].y(), points[i].z();
    return Y;
  }
};

/// The target's named parameters: the shared scalars, plus its own population if given.
template <class NamedParameters, class Base>
auto target_map_parameters(const NamedParameters& np, const Base& base)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::target_face_population_t>::value)
    return parameters::combine(base, parameters::face_population_map(get_parameter(np, internal_np::target_face_population)));
  else
    return base;
}

/// Moves the landmarks of the spherical map Y onto their common positions by a smooth,
/// fold-free warp of the sphere (`warp_landmarks_onto_targets()`).
inline Landmark_correction correct_landmarks(Matrix& Y, const Index_matrix& F, const std::vector<Eigen::Index>& l,
                                             const Matrix& common)
{
  const Landmark_warp_result w = warp_landmarks_onto_targets(Y, F, l, common);
  Landmark_correction c;
  c.error_before = w.error_before;
  c.error_after = w.error_after;
  c.exact = w.exact;
  return c;
}

template <class Map_report_type>
void refuse_folded(const Map_report_type& r, const char* which)
{
  if(r.fold_overs > 0)
    throw Algorithm_failure(std::string("the map of the ") + which + " surface has " + std::to_string(r.fold_overs) +
                            " fold-overs (exact count): no bijective correspondence can be built on it");
  // a fold-free map that dropped the landmarks would pair unrelated points
  if(r.landmarks_given_up)
    throw Algorithm_failure(std::string("the map of the ") + which +
                            " surface is fold-free only because it gave up the landmarks (" + r.fallback +
                            "): its landmarks do not meet their common positions");
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsRegistration
/// \brief Registers two genus-0 closed surfaces from corresponding landmarks: a dense,
/// bijective correspondence that sends each source landmark to (near) its target landmark.
///
/// Each surface is mapped onto a common domain so that corresponding landmarks land at
/// the same points; the correspondence is the source's map followed by the inverse of the
/// target's (paper 001 §5.1 on the sphere, paper 003 §5 on the ellipsoid), evaluated with
/// `Point_transfer`: every source vertex's image is located, with exact predicates, in the
/// target's mapped faces. Both maps are checked fold-free with exact predicates, so the
/// composition is a bijection between the surfaces (piecewise linear on the domain).
///
/// **Common landmark positions.** The landmarks need one target position per pair on the
/// domain, the same for both maps. They are taken from the conformal maps of the two
/// surfaces, which already put corresponding features near each other up to a rotation:
/// - sphere: both surfaces are mapped by the spherical conformal map with Möbius area
///   correction (this fixes the Möbius freedom up to a rotation, so no further Möbius
///   normalization is needed); the source map is turned by the rotation that best aligns its
///   landmark images with the target's (Procrustes / Kabsch, closed form), and the common
///   position of a pair is the normalized mean of its two aligned images. Both maps are then
///   `landmark_aligned_spherical_density_equalizing_map()` started from these conformal maps
///   (the source's rotated), with these targets.
/// - ellipsoid: both surfaces are mapped by `ellipsoidal_conformal_map()` onto the same
///   ellipsoid; the landmark images are brought to the unit sphere
///   (\f$ (x/a, y/b, z/c) \f$), aligned and averaged as above, and sent back to the
///   ellipsoid by \f$ n \mapsto (a n_x, b n_y, c n_z) \f$. Both maps are then
///   `ellipsoidal_quasiconformal_map()` with these targets.
///
/// Averaging the two aligned images moves each landmark half as far in each map as taking
/// either surface's images as the reference would move it in the other, which keeps both
/// maps close to conformal.
///
/// **Landmark correction (sphere route).** Each conformal starting map is first moved by a
/// smooth warp of the sphere that carries its landmark images exactly onto the common
/// positions (a Gaussian interpolation of the landmark displacements, close to the identity;
/// `Landmark_correction`), so that LSDEM starts with its landmarks in place and its landmark
/// term only has to hold them. LSDEM's fold-over repairs can still move landmark vertices
/// off their positions (by 0.01-0.02 on the unit sphere on maxplanck); the same warp then
/// moves each final map's landmarks back. Each warp is applied only if the warped map passes
/// the exact fold-over test (otherwise half, a quarter, an eighth of it, and the report says
/// that the correction is not exact), so both maps used for the correspondence are fold-free:
/// `source_map.fold_overs` and `target_map.fold_overs` are the exact counts of the maps after
/// the correction.
///
/// \tparam SourceMesh, TargetMesh models of `FaceListGraph` (they may differ)
/// \tparam LandmarkPairs a range of `std::pair<source vertex_descriptor, target vertex_descriptor>`
/// \tparam RegisteredPointMap a writable vertex property map of the source with 3D points as values
///
/// \param source the source surface
/// \param target the target surface
/// \param landmark_pairs corresponding vertices (source, target); at least 3, each vertex in one pair
/// \param registered_points receives, for every source vertex, its corresponding point on the target
///        (a point of a target face, in the target's coordinates)
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{registration_domain}
///     \cgalParamDescription{the route, a `Registration_domain`}
///     \cgalParamDefault{`Registration_domain::SPHERE`}
///   \cgalParamNEnd
///   \cgalParamNBegin{target_location_map}
///     \cgalParamDescription{a writable vertex property map of the source with values
///       `std::pair<target face_descriptor, std::array<double, 3> >`: the target face and the barycentric
///       coordinates of each corresponding point, in the convention of `Point_transfer`}
///     \cgalParamDefault{unused}
///   \cgalParamNEnd
///   \cgalParamNBegin{density_weight, harmonic_weight, landmark_weight, time_step, stopping_tolerance, number_of_iterations, truncation}
///     \cgalParamDescription{passed to both maps (\f$\alpha, \beta, \gamma\f$ of LSDEM; `landmark_weight` is
///       \f$\lambda\f$ of FEQCM on the ellipsoid)}
///     \cgalParamDefault{those of `landmark_aligned_spherical_density_equalizing_map()`, except
///       \f$ \gamma = 20 \f$, and of `ellipsoidal_quasiconformal_map()` except \f$ \lambda = 20 \f$:
///       registration wants the landmarks matched closely}
///   \cgalParamNEnd
///   \cgalParamNBegin{face_population_map}
///     \cgalParamDescription{the population of the source's faces (sphere route)}
///     \cgalParamDefault{the face areas of the source}
///   \cgalParamNEnd
///   \cgalParamNBegin{target_face_population_map}
///     \cgalParamDescription{the population of the target's faces (sphere route)}
///     \cgalParamDefault{the face areas of the target}
///   \cgalParamNEnd
///   \cgalParamNBegin{ellipsoid_radii}
///     \cgalParamDescription{the radii of the common ellipsoid (ellipsoid route)}
///     \cgalParamDefault{the mean of the two surfaces' `bounding_box_ellipsoid_radii()`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map, vertex_index_map}
///     \cgalParamDescription{of the source, as for `spherical_conformal_map()`; the target uses its internal maps}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \pre `source` and `target` are closed, connected, manifold triangle meshes of genus 0 without
///      degenerate faces (checked)
/// \pre `landmark_pairs` has at least 3 pairs of vertices of the two meshes, no vertex in two pairs (checked)
/// \returns the report: both maps' reports (with their exact fold-over counts, both 0), the common landmark
///   positions, the landmark error in 3D and the distortion of the registration map
/// \throws Invalid_input for an invalid mesh, a genus mismatch or a surface of genus other than 0, fewer than
///   3 pairs, a landmark vertex not in its mesh, a duplicate pair or a vertex in two pairs, or an invalid
///   parameter; nothing is written then.
/// \throws Algorithm_failure if either map has fold-overs (exact count), so that no bijective correspondence
///   can be built, if a map is fold-free only because it gave up its landmarks (`Map_report::landmarks_given_up`,
///   FEQCM route), or if a map could not be computed; nothing is written then.
template <class SourceMesh, class TargetMesh, class LandmarkPairs, class RegisteredPointMap,
          class NamedParameters = parameters::Default_named_parameters>
Registration_report register_surfaces(const SourceMesh& source, const TargetMesh& target,
                                      const LandmarkPairs& landmark_pairs, RegisteredPointMap registered_points,
                                      const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  namespace I = internal;
  typedef I::Registration_point Point;

  // topology first, so that two different genera are named as a mismatch
  {
    auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, source));
    const long es = I::euler_characteristic_of(I::to_arrays(source, vpm, CGAL::get_initialized_vertex_index_map(source, np)));
    const long et = I::euler_characteristic_of(I::to_arrays(target, get_const_property_map(vertex_point, target),
                                                            CGAL::get_initialized_vertex_index_map(target)));
    I::check_registrable_topology(es, et);
  }
  const auto as = I::closed_surface_arrays(source, np, 2);
  const auto at = I::closed_surface_arrays(target, parameters::default_values(), 2);
  std::vector<Eigen::Index> ls, lt;
  I::landmark_pair_indices(source, target, landmark_pairs, np, as, at, ls, lt);

  const Registration_domain route =
    choose_parameter(get_parameter(np, internal_np::registration_domain), Registration_domain::SPHERE);
  const double time_step = choose_parameter(get_parameter(np, internal_np::time_step), 0.01);
  const double tolerance = choose_parameter(get_parameter(np, internal_np::stopping_tolerance), 1e-3);
  const unsigned int iterations = choose_parameter(get_parameter(np, internal_np::number_of_iterations), 200u);
  const double truncation = choose_parameter(get_parameter(np, internal_np::truncation), 0.1);
  const double gamma = choose_parameter(get_parameter(np, internal_np::landmark_weight), 20.);
  const auto solver = I::solver_from_parameters(np);

  Registration_report report;
  report.domain = route;
  auto svim = CGAL::get_initialized_vertex_index_map(source, np);
  auto tvim = CGAL::get_initialized_vertex_index_map(target);
  I::Row_point_maps<SourceMesh> source_image(as.vertices.size());
  I::Row_point_maps<TargetMesh> target_image(at.vertices.size());
  I::Matrix common;
  if(route == Registration_domain::SPHERE) {
    I::Matrix Ss = I::registration_start_on_sphere(as.X, as.F, *solver, "source");
    I::Matrix St = I::registration_start_on_sphere(at.X, at.F, *solver, "target");
    Eigen::Matrix3d R;
    common = I::common_landmark_directions(I::rows_of(Ss, ls), I::rows_of(St, lt), R);
    Ss = Ss * R.transpose();
    // LSDEM starts with every landmark at its common position: its landmark term has only
    // to hold them there, instead of dragging single vertices through the mapped mesh
    // (on maxplanck that dragging folded nearly every step, and the step halvings stopped
    // the flow with the landmarks 0.01-0.02 off; benchmark/RESULTS.md)
    report.source_start_correction = I::correct_landmarks(Ss, as.F, ls, common);
    report.target_start_correction = I::correct_landmarks(St, at.F, lt, common);
    I::Row_point_maps<SourceMesh> start_s(Ss);
    I::Row_point_maps<TargetMesh> start_t(St);
    const auto shared = parameters::combine(
      parameters::density_weight(choose_parameter(get_parameter(np, internal_np::density_weight), 1.)),
      parameters::harmonic_weight(choose_parameter(get_parameter(np, internal_np::harmonic_weight), 2.)),
      parameters::landmark_weight(gamma), parameters::time_step(time_step),
      parameters::stopping_tolerance(tolerance), parameters::truncation(truncation),
      CGAL::parameters::number_of_iterations(iterations));
    report.source_map = landmark_aligned_spherical_density_equalizing_map(
      source, I::landmarks_at(as, ls, common), source_image.map(svim),
      parameters::combine(np, shared, parameters::initial_map(start_s.map(svim))));
    report.target_map = landmark_aligned_spherical_density_equalizing_map(
      target, I::landmarks_at(at, lt, common), target_image.map(tvim),
      I::target_map_parameters(np, parameters::combine(shared, parameters::initial_map(start_t.map(tvim)))));
    I::refuse_folded(report.source_map, "source");
    I::refuse_folded(report.target_map, "target");
    // the fold-over repairs of the flow move landmark vertices too: put them back
    const auto finish = [&](auto& image, const I::Index_matrix& F, const std::vector<Eigen::Index>& l,
                            Landmark_correction& correction, Map_report& map) {
      I::Matrix Y = image.matrix();
      correction = I::correct_landmarks(Y, F, l, common);
      image.points = std::decay_t<decltype(image)>(Y).points;
      map.fold_overs = I::count_inverted_faces_about_center(Y, F); // exact, of the map that is used
      map.landmark_error = (I::rows_of(Y, l) - common).rowwise().norm().mean();
    };
    finish(source_image, as.F, ls, report.source_correction, report.source_map);
    finish(target_image, at.F, lt, report.target_correction, report.target_map);
  } else {
    Eigen::Vector3d radii;
    if constexpr(!is_default_parameter<NamedParameters, internal_np::ellipsoid_radii_t>::value) {
      const auto& r = get_parameter(np, internal_np::ellipsoid_radii);
      radii = Eigen::Vector3d(double(r[0]), double(r[1]), double(r[2]));
    } else {
      radii = 0.5 * (I::bounding_box_radii(as.X) + I::bounding_box_radii(at.X));
      radii /= radii.mean();
    }
    I::check_radii(radii);
    const std::array<double, 3> ra{{radii[0], radii[1], radii[2]}};
    report.radii.assign(ra.begin(), ra.end());
    report.source_map = ellipsoidal_conformal_map(source, source_image.map(svim), parameters::combine(np, parameters::ellipsoid_radii(ra)));
    report.target_map = ellipsoidal_conformal_map(target, target_image.map(tvim), parameters::ellipsoid_radii(ra));
    I::refuse_folded(report.source_map, "source (conformal)");
    I::refuse_folded(report.target_map, "target (conformal)");
    const auto to_sphere = [&](const I::Matrix& E) {
      I::Matrix U(E.rows(), 3);
      for(Eigen::Index k = 0; k < E.rows(); ++k) U.row(k) = I::row3(E, k).cwiseQuotient(radii).normalized().transpose();
      return U;
    };
    Eigen::Matrix3d R;
    common = I::common_landmark_directions(to_sphere(I::rows_of(source_image.matrix(), ls)),
                                           to_sphere(I::rows_of(target_image.matrix(), lt)), R);
    for(Eigen::Index k = 0; k < common.rows(); ++k) common.row(k) = common.row(k).cwiseProduct(radii.transpose());
    const auto shared = parameters::combine(parameters::landmark_weight(gamma), parameters::ellipsoid_radii(ra));
    report.source_map = ellipsoidal_quasiconformal_map(source, I::landmarks_at(as, ls, common),
                                                       source_image.map(svim), parameters::combine(np, shared));
    report.target_map = ellipsoidal_quasiconformal_map(target, I::landmarks_at(at, lt, common),
                                                       target_image.map(tvim), shared);
  }
  I::refuse_folded(report.source_map, "source");
  I::refuse_folded(report.target_map, "target");

  // the correspondence: each source vertex's image, located in the target's map
  // (breadth-first, so that each walk starts next to the previous answer)
  typedef Point_transfer<TargetMesh, Unit_sphere_domain, Point> Sphere_transfer;
  typedef Point_transfer<TargetMesh, Ellipsoid_domain, Point> Ellipsoid_transfer;
  const I::Matrix Ys = source_image.matrix();
  std::vector<Eigen::Index> order, parent;
  I::breadth_first_vertex_order(as.F, Ys.rows(), order, parent);
  std::vector<typename Sphere_transfer::Face_location> located(std::size_t(Ys.rows()));
  I::Matrix registered(Ys.rows(), 3);
  const auto transfer_all = [&](const auto& transfer) {
    for(const Eigen::Index i : order) {
      const auto loc = transfer.locate(Point(Ys(i, 0), Ys(i, 1), Ys(i, 2)));
      located[std::size_t(i)] = loc;
      const Point p = transfer.point_on_surface(loc);
      registered.row(i) << p.x(), p.y(), p.z();
    }
  };
  if(route == Registration_domain::SPHERE)
    transfer_all(Sphere_transfer(target, target_image.map(tvim), Unit_sphere_domain()));
  else
    transfer_all(Ellipsoid_transfer(target, target_image.map(tvim), Ellipsoid_domain{report.radii[0], report.radii[1], report.radii[2]}));

  // the report
  const auto Xt = I::to_arrays(target, get_const_property_map(vertex_point, target), tvim).X;
  report.target_diagonal = (Xt.colwise().maxCoeff() - Xt.colwise().minCoeff()).norm();
  for(std::size_t k = 0; k < ls.size(); ++k) {
    const double e = (registered.row(ls[k]) - Xt.row(lt[k])).norm();
    report.landmark_error_mean += e / double(ls.size());
    report.landmark_error_max = (std::max)(report.landmark_error_max, e);
  }
  for(const auto& p : source_image.points) report.source_domain_points.push_back({{p.x(), p.y(), p.z()}});
  for(const auto& p : target_image.points) report.target_domain_points.push_back({{p.x(), p.y(), p.z()}});
  for(Eigen::Index k = 0; k < common.rows(); ++k)
    report.landmark_positions.push_back({{common(k, 0), common(k, 1), common(k, 2)}});
  {
    auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, source));
    const I::Matrix Xs = I::to_arrays(source, vpm, svim).X;
    const I::Distortion d = I::distortion(Xs, registered, as.F);
    report.mean_abs_mu = d.abs_mu.mean;
    report.mean_abs_darea = d.abs_darea.mean;
  }

  // outputs, only now that everything succeeded
  for(std::size_t i = 0; i < as.vertices.size(); ++i) {
    const Eigen::Index r = Eigen::Index(i);
    put(registered_points, as.vertices[i],
        typename boost::property_traits<RegisteredPointMap>::value_type(registered(r, 0), registered(r, 1), registered(r, 2)));
  }
  if constexpr(!is_default_parameter<NamedParameters, internal_np::target_location_map_t>::value) {
    auto out = get_parameter(np, internal_np::target_location_map);
    for(std::size_t i = 0; i < as.vertices.size(); ++i) put(out, as.vertices[i], located[i]);
  }
  return report;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_SURFACE_REGISTRATION_H
