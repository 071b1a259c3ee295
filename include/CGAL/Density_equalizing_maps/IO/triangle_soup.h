// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_TRIANGLE_SOUP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_TRIANGLE_SOUP_H

/// \file triangle_soup.h
/// The common currency of the readers and writers of this folder: a triangle
/// mesh as points and 0-based index triples, in the order of `vertices(tm)` and
/// `faces(tm)` (the file order for a `CGAL::Surface_mesh` read from a file).

#include <CGAL/Density_equalizing_maps/Map_report.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/Dynamic_property_map.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// Points and 0-based triangles.
struct Triangle_soup
{
  std::vector<std::array<double, 3> > points;
  std::vector<std::array<std::size_t, 3> > faces;
};

namespace internal {

using Point3 = std::array<double, 3>;
using Triangle = std::array<std::size_t, 3>;

template <class P, class = void> struct Point_has_z : std::false_type {};
template <class P> struct Point_has_z<P, std::void_t<decltype(std::declval<const P&>().z())> > : std::true_type {};

template <class P> Point3 to_point3(const P& p)
{
  Point3 q{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), 0.}};
  if constexpr(Point_has_z<P>::value) q[2] = CGAL::to_double(p.z());
  return q;
}

inline Point3 minus(const Point3& a, const Point3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }

inline Point3 cross(const Point3& a, const Point3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

inline double norm(const Point3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/// Area of every face of the soup.
inline std::vector<double> face_areas(const Triangle_soup& s)
{
  std::vector<double> A(s.faces.size());
  for(std::size_t k = 0; k < s.faces.size(); ++k) {
    const Triangle& t = s.faces[k];
    A[k] = 0.5 * norm(cross(minus(s.points[t[1]], s.points[t[0]]), minus(s.points[t[2]], s.points[t[0]])));
  }
  return A;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// The soup of `tm` with the positions `points` (3D, or 2D read with z = 0).
/// \throws Invalid_input unless every face is a triangle
/// \param tm a triangle mesh
/// \param points the positions of its vertices
/// \returns the soup, vertices in the order of `vertices(tm)`
template <class TriangleMesh, class PointMap>
Triangle_soup triangle_soup(const TriangleMesh& tm, PointMap points)
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  Triangle_soup s;
  auto index = get(CGAL::dynamic_vertex_property_t<std::size_t>(), tm);
  for(vertex_descriptor v : vertices(tm)) {
    put(index, v, s.points.size());
    s.points.push_back(internal::to_point3(get(points, v)));
  }
  for(auto f : faces(tm)) {
    std::array<std::size_t, 3> t{{0, 0, 0}};
    std::size_t k = 0;
    for(vertex_descriptor v : vertices_around_face(halfedge(f, tm), tm)) {
      if(k == 3) throw Invalid_input("face " + std::to_string(s.faces.size()) + " is not a triangle");
      t[k++] = get(index, v);
    }
    if(k != 3) throw Invalid_input("face " + std::to_string(s.faces.size()) + " is not a triangle");
    s.faces.push_back(t);
  }
  return s;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Builds `tm` (cleared first) from the soup, with `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()`:
/// vertices and faces keep the soup's order.
/// \throws Invalid_input if the soup is not an oriented 2-manifold (after repair of nothing: it must be one already)
/// \param s the soup
/// \param tm receives the mesh
template <class TriangleMesh>
void triangle_soup_to_mesh(const Triangle_soup& s, TriangleMesh& tm)
{
  typedef typename boost::property_traits<typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>::value_type Point;
  std::vector<Point> points;
  points.reserve(s.points.size());
  for(const auto& p : s.points) points.push_back(Point(p[0], p[1], p[2]));
  std::vector<std::vector<std::size_t> > polygons;
  polygons.reserve(s.faces.size());
  for(const auto& f : s.faces) polygons.push_back({f[0], f[1], f[2]});
  if(!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons))
    throw Invalid_input("the triangles do not form an oriented 2-manifold mesh");
  clear(tm);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, tm);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_TRIANGLE_SOUP_H
