// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_POINT_TRANSFER_H
#define CGAL_DENSITY_EQUALIZING_MAPS_POINT_TRANSFER_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/mapped_surface.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <array>
#include <map>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsPointTransfer
/// The unit sphere centred at the origin: the domain of `spherical_conformal_map()`,
/// `spherical_density_equalizing_map()` and their landmark variants.
struct Unit_sphere_domain
{
};

/// \ingroup PkgDensityEqualizingMapsPointTransfer
/// The ellipsoid \f$ x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 \f$: the domain of the ellipsoidal maps.
struct Ellipsoid_domain
{
  double a = 1, b = 1, c = 1; ///< the semi-axes, positive
};

/// \ingroup PkgDensityEqualizingMapsPointTransfer
/// The torus with radii \f$ R > r > 0 \f$ about the \f$ z \f$ axis: the domain of the toroidal maps.
struct Torus_domain
{
  double R = 2, r = 1; ///< major and minor radius
};

namespace internal {

inline Domain_shape domain_shape(const ::CGAL::Density_equalizing_maps::Unit_sphere_domain&) { return Domain_shape(); }

inline Domain_shape domain_shape(const ::CGAL::Density_equalizing_maps::Ellipsoid_domain& e)
{
  if(!(e.a > 0) || !(e.b > 0) || !(e.c > 0) || !std::isfinite(e.a) || !std::isfinite(e.b) || !std::isfinite(e.c))
    throw Invalid_input("ellipsoid radii must be positive and finite");
  Domain_shape d;
  d.kind = Domain_kind::ELLIPSOID;
  d.radii = Eigen::Vector3d(e.a, e.b, e.c);
  return d;
}

inline Domain_shape domain_shape(const ::CGAL::Density_equalizing_maps::Torus_domain& t)
{
  validate_torus_radii(t.R, t.r);
  Domain_shape d;
  d.kind = Domain_kind::TORUS;
  d.radii = Eigen::Vector3d(t.R, t.r, 0);
  return d;
}

template <class Point>
Eigen::Vector3d to_eigen(const Point& p)
{
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsPointTransfer
/// \brief Carries points between a closed triangle mesh and a domain (sphere,
/// ellipsoid, torus) through a fold-free map of the mesh onto that domain.
///
/// A map given by the images of the vertices (for instance the output of any map of
/// the package) is extended piecewise linearly: on the sphere and the ellipsoid the
/// image of a point of face \f$ T = (i, j, k) \f$ with barycentric coordinates
/// \f$ \lambda \f$ is the radial projection of \f$ \lambda_i f_i + \lambda_j f_j + \lambda_k f_k \f$
/// onto the domain; on the torus it is \f$ \phi \f$ of the same combination in the
/// flat-torus layout. This is a bijection for a fold-free map, and the class evaluates it
/// in both directions:
/// - `pull_back()`: a point of the domain to the input surface: the face whose image
///   contains it (the face whose cone from the origin contains the point on the sphere and
///   the ellipsoid, whose flat-torus layout contains its torus coordinates on the torus),
///   barycentric coordinates there, and their combination of the input positions;
/// - `push_forward()`: a point of the input surface (face and barycentric coordinates)
///   to the domain.
///
/// Containment is decided with exact orientation predicates on the stored coordinates,
/// and the two faces of an edge test it with the same points: a query exactly on a vertex
/// or an edge, or in a sliver face, is located in one of the faces that contain it. The
/// barycentric coordinates are computed afterwards in floating point and clamped to
/// \f$ [0, 1] \f$. `push_forward()` and `pull_back()` invert each other up to round-off.
///
/// Preparation (constructor) validates the mesh and the map, builds the face adjacency
/// and a bucket grid of the domain (\f$ O(n) \f$). A query walks from a start face to the
/// face containing it (randomized visibility walk): from the previous answer when the
/// queries of a batch are close to each other, else from the bucket of the query.
///
/// Locations use the convention of `CGAL::Polygon_mesh_processing::locate()`: the
/// barycentric coordinates `(w0, w1, w2)` of face `f` refer to
/// `source(halfedge(f, tm), tm)`, `target(halfedge(f, tm), tm)` and
/// `target(next(halfedge(f, tm), tm), tm)`.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeGraph`
/// \tparam Domain `Unit_sphere_domain`, `Ellipsoid_domain` or `Torus_domain`
/// \tparam Point_3 the point type of the answers, constructible from three doubles
///         (default: the value type of the mesh's internal vertex point map)
template <class TriangleMesh, class Domain = Unit_sphere_domain,
          class Point_3 = typename boost::property_traits<
            typename CGAL::GetVertexPointMap<TriangleMesh>::const_type>::value_type>
class Point_transfer
{
public:
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  /// A point of the input surface: a face and barycentric coordinates (see the class description).
  typedef std::pair<face_descriptor, std::array<double, 3> > Face_location;

  /// \brief Prepares the transfer through the map `mapped` of `tm` onto `domain`.
  ///
  /// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points
  ///
  /// \param tm the input mesh: closed, manifold, connected, genus 0 (sphere, ellipsoid) or 1 (torus);
  ///        it is copied, and may be modified or destroyed afterwards as long as its face
  ///        descriptors stay valid for the answers of `locate()`
  /// \param mapped the image of every vertex on the domain (within \f$ 10^{-6} \f$, relative)
  /// \param domain the domain, with its radii
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
  /// \cgalNamedParamsEnd
  ///
  /// \pre the map is fold-free: checked, see below
  /// \throws Invalid_input if the mesh is not a valid closed surface of the domain's genus, if
  ///   the radii are invalid, if a mapped point is not on the domain, or if the map is not
  ///   fold-free (a face inverted or degenerate on the domain, counted with exact predicates;
  ///   on the torus also a layout that does not cover the torus exactly once).
  template <class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
  Point_transfer(const TriangleMesh& tm, MappedPointMap mapped, const Domain& domain,
                 const NamedParameters& np = parameters::default_values())
    : m_arrays(arrays(tm, np)),
      m_surface(m_arrays.X, m_arrays.F, internal::read_points(m_arrays, mapped), internal::domain_shape(domain))
  {
    // corner of each face where the Polygon_mesh_processing convention starts
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    m_first_corner.resize(m_arrays.faces.size());
    for(std::size_t k = 0; k < m_arrays.faces.size(); ++k) {
      const int s = static_cast<int>(get(vim, source(halfedge(m_arrays.faces[k], tm), tm)));
      int c = 0;
      while(c < 2 && m_arrays.F(Eigen::Index(k), c) != s) ++c;
      m_first_corner[k] = c;
      m_face_index[m_arrays.faces[k]] = k;
    }
  }

  /// \brief Locates a point of the domain in the mapped mesh.
  ///
  /// On the sphere and the ellipsoid, `q` stands for the ray from the origin through it
  /// (any non-zero point); on the torus for its torus coordinates (any point off the `z` axis).
  /// \param q a point of the domain
  /// \returns the face of the input mesh whose image contains `q`, with the barycentric
  ///   coordinates of `q` in that image
  /// \throws Invalid_input if `q` is not finite, or is the origin (sphere, ellipsoid) or on the
  ///   `z` axis (torus)
  Face_location locate(const Point_3& q) const { return to_face_location(locate_internal(q)); }

  /// \brief The point of the input surface that the map sends to `q` (its preimage).
  /// \param q a point of the domain, as for `locate()`
  /// \returns the point at `locate(q)` on the input mesh
  /// \throws Invalid_input as `locate()`
  Point_3 pull_back(const Point_3& q) const { return to_point(m_surface.surface_point(locate_internal(q))); }

  /// \brief Pulls back a range of domain points; consecutive queries that are close to each
  /// other (e.g. vertices of a mesh in breadth-first order) cost a few walk steps each.
  /// \tparam PointRange a range of `Point_3`
  /// \tparam OutputIterator an output iterator accepting `Point_3`
  /// \param queries points of the domain
  /// \param out receives the preimages, in order
  /// \returns the output iterator after the last point
  /// \throws Invalid_input as `locate()` (points before the offending one have been written)
  template <class PointRange, class OutputIterator>
  OutputIterator pull_back(const PointRange& queries, OutputIterator out) const
  {
    for(const auto& q : queries) *out++ = pull_back(q);
    return out;
  }

  /// \brief The image on the domain of a point of the input surface.
  /// \param loc a face of the input mesh and barycentric coordinates (non-negative, sum 1)
  /// \returns the point of the domain the map sends `loc` to
  Point_3 push_forward(const Face_location& loc) const
  {
    return to_point(m_surface.domain_point(to_surface_point(loc)));
  }

  /// \brief The point of the input surface at `loc` (as `CGAL::Polygon_mesh_processing::construct_point()`).
  /// \param loc a face of the input mesh and barycentric coordinates
  /// \returns the barycentric combination of the face's input positions
  Point_3 point_on_surface(const Face_location& loc) const
  {
    return to_point(m_surface.surface_point(to_surface_point(loc)));
  }

  // The validated mesh and map on index arrays (used by the applications; internal
  // type, so not part of the documented interface).
  const internal::Mapped_surface& mapped_surface() const { return m_surface; }

private:
  template <class NamedParameters>
  static internal::Mesh_arrays<TriangleMesh> arrays(const TriangleMesh& tm, const NamedParameters& np)
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, tm));
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    return internal::to_arrays(tm, vpm, vim);
  }

  // locate() on index arrays: no face-descriptor conversion, no allocation
  internal::Surface_point locate_internal(const Point_3& q) const
  {
    const Eigen::Vector3d p = internal::to_eigen(q);
    const internal::Surface_point s = m_surface.locate(p, m_surface.hint_after(m_last_query, m_last, p));
    if(s.face < 0) throw Invalid_input("the query point has no direction on the domain (zero, on the axis or not finite)");
    m_last = s;
    m_last_query = p;
    return s;
  }

  static Point_3 to_point(const Eigen::Vector3d& p) { return Point_3(p.x(), p.y(), p.z()); }

  Face_location to_face_location(const internal::Surface_point& s) const
  {
    const int c = m_first_corner[s.face];
    return Face_location(m_arrays.faces[s.face], {{s.barycentric[c], s.barycentric[(c + 1) % 3],
                                                   s.barycentric[(c + 2) % 3]}});
  }

  internal::Surface_point to_surface_point(const Face_location& loc) const
  {
    const auto it = m_face_index.find(loc.first);
    if(it == m_face_index.end()) throw Invalid_input("the location's face is not a face of the mesh");
    internal::Surface_point s;
    s.face = Eigen::Index(it->second);
    const int c = m_first_corner[it->second];
    for(int j = 0; j < 3; ++j) s.barycentric[(c + j) % 3] = loc.second[j];
    return s;
  }

  internal::Mesh_arrays<TriangleMesh> m_arrays;
  internal::Mapped_surface m_surface;
  std::vector<int> m_first_corner;
  std::map<face_descriptor, std::size_t> m_face_index;
  mutable internal::Surface_point m_last;
  mutable Eigen::Vector3d m_last_query = Eigen::Vector3d::Zero();
};

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_POINT_TRANSFER_H
