// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_MEASURES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_MEASURES_H

// Quality measures of a map between a triangle mesh and its image with the same
// connectivity (ALGORITHMS.md section 11): exact fold-over counts, Beltrami
// coefficients, log area ratios, density variances and the uniformity of the
// faces (delta_size, delta_shape). They diagnose any pure
// triangle mesh: unlike the mapping functions they do not require a closed
// genus-0 surface.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/input.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/boost/graph/named_params_helper.h>

#include <type_traits>
#include <utility>

namespace CGAL {
namespace Density_equalizing_maps {

namespace internal_np {
enum center_t { center };
} // namespace internal_np

namespace parameters {
/// \ingroup PkgDensityEqualizingMapsMeasures
/// Named parameter: the point about which `number_of_fold_overs()` tests the
/// orientation of the image faces (default: the origin).
/// \param t the center point
/// \returns a named parameter pack holding `t`
template <typename T>
CGAL::Named_function_parameters<T, internal_np::center_t> center(const T& t)
{ return CGAL::Named_function_parameters<T, internal_np::center_t>(t); }
} // namespace parameters

/// \ingroup PkgDensityEqualizingMapsMeasures
/// Variances of the normalized densities on a map (`N - 1` normalization, as in the papers' tables).
struct Density_variance
{
  /// variance of `rho_V / mean(rho_V)`, `rho_V = M rho_F` the area-weighted average of the
  /// face densities of the incident image faces (paper 001, Table 1)
  double vertex = 0;
  /// variance of `rho_F / mean(rho_F)`, `rho_F = population / image face area` (paper 000's tables)
  double face = 0;
};

/// \ingroup PkgDensityEqualizingMapsMeasures
/// Mean and standard deviation (`N - 1` normalization) over the faces of the
/// angle distortion `|mu|` and of the area distortion `|d_area|` of a map.
struct Distortion_statistics
{
  double mean_abs_mu = 0;    ///< mean of the per-face `|mu|`
  double sd_abs_mu = 0;      ///< standard deviation of the per-face `|mu|`
  double mean_abs_darea = 0; ///< mean of the per-face `|d_area|`
  double sd_abs_darea = 0;   ///< standard deviation of the per-face `|d_area|`
};

namespace internal {

template <class P, class = void> struct Has_z : std::false_type {};
template <class P> struct Has_z<P, std::void_t<decltype(std::declval<const P&>().z())> > : std::true_type {};

/// The input arrays of any pure triangle mesh (no topological validation: a
/// measure must be able to diagnose whatever it is given).
template <class TriangleMesh, class NamedParameters>
Mesh_arrays<TriangleMesh> measure_arrays(const TriangleMesh& tm, const NamedParameters& np)
{
  Mesh_arrays<TriangleMesh> a = unvalidated_arrays(tm, np);
  normalize_scale(a); // the measures are scale-invariant; lengths near 1e+-100 would overflow
  return a;
}

/// Image positions as an n x 3 matrix; 2D points get z = 0, so the area and
/// Beltrami measures also apply to planar maps.
template <class TriangleMesh, class PointMap>
Matrix read_mapped_points(const Mesh_arrays<TriangleMesh>& a, PointMap pm)
{
  typedef typename boost::property_traits<PointMap>::value_type Point;
  Matrix Y(a.vertices.size(), 3);
  for(std::size_t i = 0; i < a.vertices.size(); ++i) {
    const Point& p = get(pm, a.vertices[i]);
    Y(i, 0) = CGAL::to_double(p.x());
    Y(i, 1) = CGAL::to_double(p.y());
    if constexpr(Has_z<Point>::value) Y(i, 2) = CGAL::to_double(p.z());
    else Y(i, 2) = 0;
  }
  return Y;
}

template <class TriangleMesh, class FaceValueMap>
void write_face_values(const Mesh_arrays<TriangleMesh>& a, const Vector& v, FaceValueMap out)
{
  typedef typename boost::property_traits<FaceValueMap>::value_type Value;
  for(std::size_t k = 0; k < a.faces.size(); ++k) put(out, a.faces[k], Value(v[k]));
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Counts, with exact predicates, the faces of a map onto a sphere or an
/// ellipsoid (any surface star-shaped about `center`) whose image is inverted.
///
/// The image of face `(i,j,k)` is inverted when `orientation(center, f_i, f_j, f_k)`
/// differs from the orientation of a correct face, that is positive when the input
/// mesh is oriented with outward normals (negative if it is oriented inward: the
/// count is relative to the input's orientation, read from the sign of its enclosed volume).
/// A degenerate image face and a face with a non-finite corner count as inverted.
/// The input positions are only used to find that orientation.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points (`x()`, `y()`, `z()`)
///
/// \param tm a pure triangle mesh, closed for the orientation test to be meaningful
/// \param mapped the image of every vertex
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{center}
///     \cgalParamDescription{the point about which the image is star-shaped}
///     \cgalParamType{a point type with `x()`, `y()`, `z()`}
///     \cgalParamDefault{the origin}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{the input positions}
///     \cgalParamDefault{`get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map}
///     \cgalParamDescription{a map from vertices to indices 0..n-1}
///     \cgalParamDefault{an internal or dynamically filled map}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre for the count to mean inverted faces, `tm` is closed and oriented outward and the domain of
///      `mapped` is star-shaped about `center`
/// \returns the number of inverted faces (0 for a bijective map)
/// \throws Invalid_input if a face is not a triangle
template <class TriangleMesh, class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t number_of_fold_overs(const TriangleMesh& tm, MappedPointMap mapped,
                                 const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  const auto a = internal::measure_arrays(tm, np);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  if constexpr(!is_default_parameter<NamedParameters, internal_np::center_t>::value) {
    const auto& p = get_parameter(np, internal_np::center);
    c = Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  return internal::count_fold_overs_about_center(internal::read_mapped_points(a, mapped), a.F,
                                                  internal::enclosed_volume_sign(a.X, a.F), c);
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Counts, with exact predicates, the faces of a planar map that are not
/// oriented counter-clockwise.
///
/// Degenerate images and faces with a non-finite corner count as folded. Use it on
/// maps that preserve orientation (e.g. the flat-torus coordinates of
/// `toroidal_density_equalizing_map()`); for a map expected to be clockwise
/// everywhere, `number_of_faces(tm) - number_of_planar_fold_overs(...)` counts the bad faces
/// only if no image face is degenerate.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam PlanarPointMap a model of `ReadablePropertyMap` from vertices to 2D points (`x()`, `y()`)
///
/// \param tm a pure triangle mesh
/// \param uv the planar image of every vertex
/// \param np optional named parameters: `vertex_index_map` as for `number_of_fold_overs()`
///
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre for the count to mean inverted faces, the faces of `tm` are consistently oriented
/// \returns the number of faces whose image is clockwise or degenerate
/// \throws Invalid_input if a face is not a triangle
template <class TriangleMesh, class PlanarPointMap, class NamedParameters = parameters::Default_named_parameters>
std::size_t number_of_planar_fold_overs(const TriangleMesh& tm, PlanarPointMap uv,
                                        const NamedParameters& np = parameters::default_values())
{
  const auto a = internal::measure_arrays(tm, np);
  internal::Matrix W(a.vertices.size(), 2);
  for(std::size_t i = 0; i < a.vertices.size(); ++i) {
    const auto& p = get(uv, a.vertices[i]);
    W(i, 0) = CGAL::to_double(p.x());
    W(i, 1) = CGAL::to_double(p.y());
  }
  return internal::count_planar_fold_overs_checked(W, a.F, 1);
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Computes `|mu|` per face, the magnitude of the Beltrami coefficient of
/// the piecewise-linear map from the input mesh to its image (angle distortion).
///
/// Each input triangle and its image are flattened isometrically, and `|mu| = (s1 - s2) / (s1 + s2)`
/// with `s1 >= s2` the singular values of the affine map between them: 0 for a
/// similarity (conformal), up to 1 for a degenerate image. Blind to orientation:
/// count fold-overs with `number_of_fold_overs()`.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points (2D points are read with `z = 0`)
/// \tparam FaceValueMap a model of `WritablePropertyMap` from faces to a floating-point type
///
/// \param tm a pure triangle mesh with non-degenerate faces
/// \param mapped the image of every vertex
/// \param mu_out receives `|mu|` of every face
/// \param np optional named parameters: `vertex_point_map` (input positions) and
///        `vertex_index_map` as for `number_of_fold_overs()`
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre no face of `tm` is degenerate
/// \throws Invalid_input if a face is not a triangle
template <class TriangleMesh, class MappedPointMap, class FaceValueMap,
          class NamedParameters = parameters::Default_named_parameters>
void beltrami_coefficient_magnitudes(const TriangleMesh& tm, MappedPointMap mapped, FaceValueMap mu_out,
                                     const NamedParameters& np = parameters::default_values())
{
  const auto a = internal::measure_arrays(tm, np);
  internal::write_face_values(a, internal::beltrami_magnitude_3d(a.X, internal::read_mapped_points(a, mapped), a.F),
                              mu_out);
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Computes per face the log area ratio
/// `d_area(T) = log( (|f(T)| / sum |f|) / (|T| / sum |T|) )` of the map `f` from the
/// input mesh to its image (flat triangle areas on both sides; 0 for an area-preserving map up to scale).
///
/// A degenerate image face gives `-infinity`.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points (2D points are read with `z = 0`)
/// \tparam FaceValueMap a model of `WritablePropertyMap` from faces to a floating-point type
///
/// \param tm a pure triangle mesh with non-degenerate faces
/// \param mapped the image of every vertex
/// \param darea_out receives `d_area` of every face
/// \param np optional named parameters: `vertex_point_map` (input positions) and
///        `vertex_index_map` as for `number_of_fold_overs()`
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre no face of `tm` is degenerate
/// \throws Invalid_input if a face is not a triangle
template <class TriangleMesh, class MappedPointMap, class FaceValueMap,
          class NamedParameters = parameters::Default_named_parameters>
void log_area_ratios(const TriangleMesh& tm, MappedPointMap mapped, FaceValueMap darea_out,
                     const NamedParameters& np = parameters::default_values())
{
  const auto a = internal::measure_arrays(tm, np);
  const internal::Matrix Y = internal::read_mapped_points(a, mapped);
  internal::write_face_values(a, internal::log_area_ratio(internal::face_areas(a.X, a.F), internal::face_areas(Y, a.F)),
                              darea_out);
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Computes how far a map is from equalizing a density: the variances of the
/// normalized face and vertex densities on the image.
///
/// With `P_T` the population of face `T` and `|f(T)|` the area of its image, the face
/// density is `rho_F = P_T / |f(T)|` and the vertex density `rho_V = M rho_F`, `M` the
/// average over the incident faces weighted by their image areas. Both are 0 for a
/// perfect density-equalizing map. Called with the identity map
/// (`mapped = get(CGAL::vertex_point, tm)`) it gives the density variance of the input.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points (2D points are read with `z = 0`)
///
/// \param tm a pure triangle mesh with non-degenerate faces
/// \param mapped the image of every vertex
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{face_population_map}
///     \cgalParamDescription{the population of every face (positive)}
///     \cgalParamType{a model of `ReadablePropertyMap` from faces to a floating-point type}
///     \cgalParamDefault{the area of the input face (area-preserving target)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_density_map}
///     \cgalParamDescription{a positive density per input vertex, used when no
///       `face_population_map` is given: the population of a face is its area times
///       the mean density of its corners}
///     \cgalParamType{a model of `ReadablePropertyMap` from vertices to a floating-point type}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{the input positions}
///     \cgalParamDefault{`get(CGAL::vertex_point, tm)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map}
///     \cgalParamDescription{a map from vertices to indices 0..n-1}
///     \cgalParamDefault{an internal or dynamically filled map}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre no face of `tm` is degenerate
/// \pre the population, when given, is positive and finite (checked)
/// \throws Invalid_input if a face is not a triangle or the population is not positive and finite
/// \returns the variances of the normalized vertex and face densities
template <class TriangleMesh, class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
Density_variance density_variance(const TriangleMesh& tm, MappedPointMap mapped,
                                  const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = internal::measure_arrays(tm, np);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const internal::Density_variances v =
    internal::density_variances(internal::read_mapped_points(a, mapped), a.F, population);
  Density_variance r;
  r.vertex = v.vertex;
  r.face = v.face;
  return r;
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Summarizes the angle and area distortion of a map: mean and standard
/// deviation over the faces of `|mu|` (see `beltrami_coefficient_magnitudes()`) and
/// of `|d_area|` (see `log_area_ratios()`), as reported in the papers' tables.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points (2D points are read with `z = 0`)
///
/// \param tm a pure triangle mesh with non-degenerate faces
/// \param mapped the image of every vertex
/// \param np optional named parameters: `vertex_point_map` (input positions) and
///        `vertex_index_map` as for `number_of_fold_overs()`
/// \pre every face of `tm` is a triangle (checked: `Invalid_input` otherwise)
/// \pre no face of `tm` is degenerate
/// \throws Invalid_input if a face is not a triangle
/// \returns the means and standard deviations of `|mu|` and `|d_area|` over the faces
template <class TriangleMesh, class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
Distortion_statistics map_distortion(const TriangleMesh& tm, MappedPointMap mapped,
                                     const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = internal::measure_arrays(tm, np);
  const internal::Distortion d = internal::distortion(a.X, internal::read_mapped_points(a, mapped), a.F);
  Distortion_statistics s;
  s.mean_abs_mu = d.abs_mu.mean;
  s.sd_abs_mu = d.abs_mu.sd;
  s.mean_abs_darea = d.abs_darea.mean;
  s.sd_abs_darea = d.abs_darea.sd;
  return s;
}

/// \ingroup PkgDensityEqualizingMapsMeasures
/// How uniform the triangles of a mesh are (paper 000, eqs. 43-45), the two quality
/// measures of remeshing.
struct Mesh_uniformity
{
  /// \f$ \delta_{size} = \ln(A_{max} / A_{min}) \f$, the spread of the face areas
  /// (natural log; 0 if all faces have the same area, infinite if one is degenerate)
  double delta_size = 0;
  /// \f$ \delta_{shape} \f$, the mean over the faces of the irregularity
  /// \f$ R_T = \sum_{a=1}^3 |\ell_a / (\ell_1 + \ell_2 + \ell_3) - 1/3| \f$
  /// of the edge lengths (0 for equilateral triangles, at most 2/3 for a needle)
  double delta_shape = 0;
};

/// \ingroup PkgDensityEqualizingMapsMeasures
/// \brief Computes the size and shape uniformity \f$ \delta_{size} \f$ and
/// \f$ \delta_{shape} \f$ of the faces of a triangle mesh (paper 000, eqs. 43-45), as
/// reported for remeshed surfaces (see `remesh_through_map()`).
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \param tm a pure triangle mesh with at least one face
/// \param np optional named parameters: `vertex_point_map` and `vertex_index_map` as for
///        `number_of_fold_overs()`
/// \returns both measures over all faces of `tm`
/// \throws Invalid_input if a face is not a triangle
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Mesh_uniformity mesh_uniformity(const TriangleMesh& tm, const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const auto a = internal::measure_arrays(tm, np);
  const internal::Mesh_uniformity u = internal::mesh_uniformity(a.X, a.F);
  Mesh_uniformity r;
  r.delta_size = u.delta_size;
  r.delta_shape = u.delta_shape;
  return r;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_MEASURES_H
