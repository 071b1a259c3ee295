// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_TEXTURE_COORDINATES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_TEXTURE_COORDINATES_H

/// \file texture_coordinates.h
/// Texture coordinates per face corner for the image of a map: the
/// equirectangular chart (longitude, latitude) of a sphere or an ellipsoid, and
/// the flat-torus coordinates of a toroidal map. Both are normalized to the
/// unit square [0,1]^2 = one copy of the domain, and a face that crosses the
/// seam gets texture coordinates beyond 1 (its corners on the far side are
/// duplicated with u + 1, or v + 1), so no face stretches across the square:
/// viewers read them with the usual "repeat" wrap mode.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/IO/triangle_soup.h>

#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// A triangle mesh with texture coordinates per corner: face `k` has the
/// positions `points[faces[k][c]]` and the texture coordinates `uv[uv_faces[k][c]]`.
struct Textured_mesh
{
  std::vector<std::array<double, 3> > points;
  std::vector<std::array<double, 2> > uv;
  std::vector<std::array<std::size_t, 3> > faces;
  std::vector<std::array<std::size_t, 3> > uv_faces;
};

namespace internal {

constexpr double pi = 3.14159265358979323846264338327950288;

/// The angle in (-pi, pi] equal to `a` modulo 2 pi.
inline double wrapped_angle(double a)
{
  a = std::remainder(a, 2 * pi);
  return a <= -pi ? a + 2 * pi : a;
}

/// A point of the sphere or ellipsoid in the chart: longitude, latitude and whether it is a pole.
struct Geographic
{
  double longitude = 0, latitude = 0;
  bool pole = false;
};

inline Geographic geographic(const Point3& p, const Point3& center, const Point3& radii)
{
  const double x = (p[0] - center[0]) / radii[0], y = (p[1] - center[1]) / radii[1], z = (p[2] - center[2]) / radii[2];
  const double rho = std::hypot(x, y);
  Geographic g;
  g.pole = !(rho > 1e-12 * std::abs(z));
  g.longitude = g.pole ? 0. : std::atan2(y, x);
  g.latitude = std::atan2(z, rho);
  return g;
}

/// Appends a texture coordinate (longitude, latitude) normalized to [0,1]^2 and returns its index.
inline std::size_t add_uv(Textured_mesh& t, double longitude, double latitude)
{
  t.uv.push_back({{(longitude + pi) / (2 * pi), (latitude + pi / 2) / pi}});
  return t.uv.size() - 1;
}

/// The longitudes of the corners made continuous across the face, starting
/// from the first non-polar corner in [-pi, pi): the other corners differ from
/// it by less than pi. A polar corner takes the mean of the others' longitudes,
/// which keeps the face's chart a proper triangle reaching the pole line.
inline std::array<double, 3> unwrapped_longitudes(const std::array<Geographic, 3>& g)
{
  std::array<double, 3> u{{0, 0, 0}};
  int first = -1, regular = 0;
  for(int c = 0; c < 3; ++c)
    if(!g[c].pole) {
      if(first < 0) first = c;
      u[c] = g[first].longitude + wrapped_angle(g[c].longitude - g[first].longitude);
      ++regular;
    }
  double sum = 0;
  for(int c = 0; c < 3; ++c)
    if(!g[c].pole) sum += u[c];
  for(int c = 0; c < 3; ++c)
    if(g[c].pole) u[c] = regular > 0 ? sum / regular : 0.;
  return u;
}

/// +1 if the corners wind once counter-clockwise about the polar axis (seen
/// from +z), -1 clockwise, 0 if the axis does not pass through the face.
inline int winding_about_axis(const std::array<Geographic, 3>& g)
{
  for(const Geographic& c : g)
    if(c.pole) return 0;
  double turn = 0;
  for(int c = 0; c < 3; ++c) turn += wrapped_angle(g[(c + 1) % 3].longitude - g[c].longitude);
  return turn > pi ? 1 : (turn < -pi ? -1 : 0);
}

/// Where the polar axis meets the plane of the triangle (a, b, c).
inline Point3 axis_point(const Point3& a, const Point3& b, const Point3& c, const Point3& center)
{
  // barycentric coordinates of the axis in the projection to the xy-plane
  const double d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
  const double wb = ((center[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (center[1] - a[1])) / d;
  const double wc = ((b[0] - a[0]) * (center[1] - a[1]) - (center[0] - a[0]) * (b[1] - a[1])) / d;
  const double wa = 1 - wb - wc;
  return {{center[0], center[1], wa * a[2] + wb * b[2] + wc * c[2]}};
}

inline void add_textured_face(Textured_mesh& t, const std::array<std::size_t, 3>& corners,
                              const std::array<Geographic, 3>& g)
{
  std::array<double, 3> u = unwrapped_longitudes(g);
  // the face's leftmost corner in [-pi, pi): its chart starts in the unit square
  const double shift = std::min({u[0], u[1], u[2]}) < -pi ? 2 * pi : 0.;
  for(double& x : u) x += shift;
  std::array<std::size_t, 3> uv;
  for(int c = 0; c < 3; ++c) uv[c] = add_uv(t, u[c], g[c].latitude);
  t.faces.push_back(corners);
  t.uv_faces.push_back(uv);
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief The equirectangular texture coordinates of a mesh on a sphere or an
/// axis-aligned ellipsoid: `u = (longitude + pi) / (2 pi)`, `v = (latitude + pi/2) / pi`
/// of the point `((x - c_x)/a, (y - c_y)/b, (z - c_z)/c)` (the parametric longitude and latitude).
///
/// Seam: the longitudes of a face are made continuous from its first corner, so a face
/// across the antimeridian has corners with `u > 1` (duplicated texture coordinates).
/// Poles: a corner on the polar axis takes the mean `u` of the face's two other corners
/// and `v = 0` or `1`; a face through which the axis passes (its corners wind once around
/// it) is split into three triangles at the point where the axis meets it, that point
/// getting `v = 0` or `1`, so the returned mesh has one more vertex and two more faces per
/// such pole. Every other face keeps its corners and its orientation.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam PointMap a model of `ReadablePropertyMap` from vertices to 3D points
/// \param tm a triangle mesh
/// \param points positions on the sphere or ellipsoid (e.g. the output of a map)
/// \param radii the semi-axes `(a, b, c)` (default the unit sphere)
/// \param center the center (default the origin)
/// \throws Invalid_input if a face is not a triangle or a radius is not positive
/// \returns the textured mesh (positions, texture coordinates, faces of both)
template <class TriangleMesh, class PointMap>
Textured_mesh equirectangular_texture(const TriangleMesh& tm, PointMap points,
                                      const std::array<double, 3>& radii = {{1., 1., 1.}},
                                      const std::array<double, 3>& center = {{0., 0., 0.}})
{
  for(double r : radii)
    if(!(r > 0) || !std::isfinite(r)) throw Invalid_input("the radii of the chart must be positive and finite");
  const Triangle_soup s = triangle_soup(tm, points);
  Textured_mesh t;
  t.points = s.points;
  std::vector<internal::Geographic> g;
  for(const auto& p : s.points) g.push_back(internal::geographic(p, center, radii));
  for(const auto& f : s.faces) {
    const std::array<internal::Geographic, 3> gf{{g[f[0]], g[f[1]], g[f[2]]}};
    if(internal::winding_about_axis(gf) == 0) {
      internal::add_textured_face(t, f, gf);
      continue;
    }
    const internal::Point3 P = internal::axis_point(s.points[f[0]], s.points[f[1]], s.points[f[2]], center);
    internal::Geographic gp = internal::geographic(P, center, radii);
    gp.pole = true;
    gp.latitude = (P[2] - center[2] > 0 ? 1 : -1) * internal::pi / 2;
    t.points.push_back(P);
    const std::size_t ip = t.points.size() - 1;
    for(int c = 0; c < 3; ++c) {
      const int d = (c + 1) % 3;
      internal::add_textured_face(t, {{f[c], f[d], ip}}, {{gf[c], gf[d], gp}});
    }
  }
  return t;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief The flat-torus texture coordinates of a toroidal map, from the outputs
/// `flat_torus_coordinates` and `flat_torus_offsets` of `toroidal_density_equalizing_map()`
/// (or `toroidal_parameterization()`): the corners of a face are laid out from the
/// source of `halfedge(f, tm)` by adding each halfedge's lattice offset, and normalized
/// by the periods: `u / (2 pi R)`, `(v + pi r) / (2 pi r)`. A fold-free map gives
/// counter-clockwise (or, for an inward-oriented mesh, all clockwise) texture triangles
/// that tile the unit square exactly once: their areas sum to 1.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeGraph`
/// \tparam PointMap a model of `ReadablePropertyMap` from vertices to 3D points
/// \tparam FlatMap a model of `ReadablePropertyMap` from vertices to 2D points
/// \tparam OffsetMap a model of `ReadablePropertyMap` from halfedges to pairs of integers readable with `[0]`, `[1]` or `.first`, `.second`
/// \param tm a triangle mesh
/// \param points the positions to write (e.g. the points on the 3D torus)
/// \param flat the flat-torus point `(u, v)` of every vertex
/// \param offsets the lattice offset of every halfedge of a face
/// \param R the major radius, period `2 pi R` in `u`
/// \param r the minor radius, period `2 pi r` in `v`
/// \throws Invalid_input if a face is not a triangle, the radii are not positive or the
///         offsets of a face do not sum to zero
/// \returns the textured mesh (positions, texture coordinates, faces of both)
template <class TriangleMesh, class PointMap, class FlatMap, class OffsetMap>
Textured_mesh flat_torus_texture(const TriangleMesh& tm, PointMap points, FlatMap flat, OffsetMap offsets,
                                 double R, double r)
{
  if(!(R > 0) || !(r > 0) || !std::isfinite(R) || !std::isfinite(r))
    throw Invalid_input("the torus radii must be positive and finite");
  const double pu = 2 * internal::pi * R, pv = 2 * internal::pi * r;
  Textured_mesh t;
  auto index = get(CGAL::dynamic_vertex_property_t<std::size_t>(), tm);
  for(auto v : vertices(tm)) {
    put(index, v, t.points.size());
    t.points.push_back(internal::to_point3(get(points, v)));
  }
  std::size_t k = 0;
  for(auto f : faces(tm)) {
    std::array<std::size_t, 3> corners{{0, 0, 0}}, uv{{0, 0, 0}};
    long ou = 0, ov = 0;
    int c = 0;
    for(auto h : halfedges_around_face(halfedge(f, tm), tm)) {
      if(c == 3) throw Invalid_input("face " + std::to_string(k) + " is not a triangle");
      const auto v = source(h, tm);
      const auto& q = get(flat, v);
      corners[c] = get(index, v);
      t.uv.push_back({{(CGAL::to_double(q.x()) + pu * double(ou)) / pu,
                       (CGAL::to_double(q.y()) + pv * double(ov) + pv / 2) / pv}});
      uv[c++] = t.uv.size() - 1;
      const auto o = get(offsets, h);
      const auto [du, dv] = o;
      ou += du;
      ov += dv;
    }
    if(c != 3) throw Invalid_input("face " + std::to_string(k) + " is not a triangle");
    if(ou != 0 || ov != 0)
      throw Invalid_input("the lattice offsets of face " + std::to_string(k) + " do not sum to zero");
    t.faces.push_back(corners);
    t.uv_faces.push_back(uv);
    ++k;
  }
  return t;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Signed area of the texture triangle of face `k` (positive when counter-clockwise).
/// \param t a textured mesh
/// \param k a face index of `t`
/// \returns the signed area of face `k` in texture space
inline double texture_area(const Textured_mesh& t, std::size_t k)
{
  const auto& a = t.uv[t.uv_faces[k][0]];
  const auto& b = t.uv[t.uv_faces[k][1]];
  const auto& c = t.uv[t.uv_faces[k][2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_TEXTURE_COORDINATES_H
