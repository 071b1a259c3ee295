// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Regions of the sphere given as spherical polygons (rings of longitude /
// latitude vertices joined by great-circle arcs, with holes; several polygons
// per region), and the area of their overlap with the faces of a sphere mesh.
//
// Everything is done on the unit sphere in 3D: a ring crossing the
// antimeridian or winding around a pole is an ordinary closed curve there.
//
// Which side of a ring is its inside. RFC 7946 asks for exterior rings wound
// counterclockwise (inside on the left) and holes clockwise, but also asks
// readers not to reject files that do not follow the rule, and many files
// (those made for d3, for instance) wind the other way. A ring here encloses
// the side of smaller area; a side of exactly half the sphere (a hemisphere
// bounded by a great circle) is the left side. A region larger than a
// hemisphere is therefore given as several polygons.
//
// Point in ring. Each ring keeps a reference point R whose side is known
// (just to the left of an edge, nearer to it than to any other edge); a point
// q is on the side of R iff the arc from R to q (through a point 90 degrees
// from R when q is farther than that, so that arcs are minor) crosses the ring
// an even number of times. The crossing
// test of two arcs uses CGAL's exact orientation predicate on the double
// coordinates, so parities are consistent and exact.
//
// Overlap of a face with a polygon, exactly (subdivision 0): see
// enclosed_face_fraction(). Or sampled: each face is split into s^2 congruent
// sub-triangles (s = subdivision); the centroid of each is classified and the
// overlap fraction is the share of inside sub-triangles. Only faces near the
// ring (a ring edge's bounding cap meets the face's cap) are subdivided, and
// their samples are classified from the face centroid by counting crossings of
// the nearby edges only (the arc from the centroid to a sample stays inside
// the face); face centroids are classified by a breadth-first walk, each from
// the centroid of an already classified neighbour. The error of a fraction is
// of the order of the sub-triangle area along the boundary: with s = 8, the
// test measures a relative area error below 1e-3 for a region of ~100 faces.

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_REGIONS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_REGIONS_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsCartogram
/// A point of the globe: longitude and latitude in degrees (WGS 84 order, as in GeoJSON).
struct Lon_lat
{
  double lon = 0; ///< longitude in degrees, in [-180, 180]
  double lat = 0; ///< latitude in degrees, in [-90, 90]
};

/// \ingroup PkgDensityEqualizingMapsCartogram
/// A spherical polygon: closed rings of vertices joined by great-circle arcs (the shorter
/// arc; consecutive vertices must not be antipodal). `rings[0]` is the exterior ring,
/// the others are holes. A ring lists each vertex once (the closing vertex of GeoJSON
/// is not repeated). Each ring encloses the smaller of the two sides it bounds (the
/// left side for exactly half the sphere), whatever its winding.
struct Spherical_polygon
{
  std::vector<std::vector<Lon_lat> > rings; ///< exterior ring, then holes
};

/// \ingroup PkgDensityEqualizingMapsCartogram
/// A region of the globe (a country, ...): an identifier and one or more polygons.
struct Spherical_region
{
  std::string id;                          ///< the identifier, as in the values table
  std::vector<Spherical_polygon> polygons; ///< the parts of the region (a multipolygon)
};

namespace internal {

inline Eigen::Vector3d unit_vector(const Lon_lat& p)
{
  const double d = 3.14159265358979323846 / 180;
  const double lo = p.lon * d, la = p.lat * d;
  return Eigen::Vector3d(std::cos(la) * std::cos(lo), std::cos(la) * std::sin(lo), std::sin(la));
}

inline Lon_lat lon_lat(const Eigen::Vector3d& v)
{
  const double d = 180 / 3.14159265358979323846;
  Lon_lat p;
  p.lon = std::atan2(v.y(), v.x()) * d;
  p.lat = std::atan2(v.z(), std::hypot(v.x(), v.y())) * d;
  return p;
}

/// Exact sign of det(a, b, c) for the double coordinates.
inline int orientation_about_center(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef K::Point_3 P;
  static const P o(0, 0, 0);
  return int(CGAL::orientation(o, P(a.x(), a.y(), a.z()), P(b.x(), b.y(), b.z()), P(c.x(), c.y(), c.z())));
}

/// Whether the minor arcs ab and cd cross at a point interior to both (exact
/// signs). `degenerate` is set when a sign is 0 (an end of one arc on the great
/// circle of the other): the answer (false then) may be wrong, the caller routes
/// around it.
inline bool arcs_cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d, bool& degenerate)
{
  const int abc = orientation_about_center(a, b, c), abd = orientation_about_center(a, b, d);
  if(abc == abd && abc != 0) return false; // c and d strictly on the same side
  const int cda = orientation_about_center(c, d, a), cdb = orientation_about_center(c, d, b);
  if(cda == cdb && cda != 0) return false;
  if(abc == 0 || abd == 0 || cda == 0 || cdb == 0) { degenerate = true; return false; }
  // opposite sides both ways: the great circles meet at +-p; the arcs share p iff
  return abc == cdb; // S2 SimpleCrossing: (-abc) * (-cdb) > 0
}

inline bool arcs_cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d)
{
  bool degenerate = false;
  return arcs_cross(a, b, c, d, degenerate);
}

/// Signed area of the spherical triangle abc (Van Oosterom and Strackee), in (-2 pi, 2 pi].
inline double signed_triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return 2 * std::atan2(a.dot(b.cross(c)), 1 + a.dot(b) + b.dot(c) + c.dot(a));
}

/// Angular distance from p to the minor arc ab.
inline double distance_to_arc(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d n = a.cross(b).normalized();
  const Eigen::Vector3d foot = p - p.dot(n) * n;
  const double endpoints = std::min(std::acos(std::clamp(p.dot(a), -1., 1.)), std::acos(std::clamp(p.dot(b), -1., 1.)));
  if(foot.norm() > 1e-12 && a.cross(foot).dot(n) > 0 && foot.cross(b).dot(n) > 0)
    return std::min(endpoints, std::asin(std::min(1., std::abs(p.dot(n)))));
  return endpoints;
}

/// A spherical cap: the points v with v . center >= cos(radius).
struct Spherical_cap
{
  Eigen::Vector3d center = Eigen::Vector3d::UnitZ();
  double radius = 4; // > pi: the whole sphere
  double cos_radius = -1, sin_radius = 0;

  void set_radius(double r)
  {
    radius = r;
    cos_radius = std::cos(r);
    sin_radius = std::sin(r);
  }

  bool meets(const Spherical_cap& o) const
  {
    if(radius + o.radius >= 3.14159265358979323846) return true;
    // angle(center, o.center) <= radius + o.radius, without acos
    return center.dot(o.center) >= cos_radius * o.cos_radius - sin_radius * o.sin_radius - 1e-12;
  }
};

/// The cap of the arc ab: centred at its midpoint.
inline Spherical_cap arc_cap(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  Spherical_cap c;
  c.center = (a + b).normalized();
  c.set_radius(0.5 * std::acos(std::clamp(a.dot(b), -1., 1.)) + 1e-12);
  return c;
}

/// A ring on the unit sphere, with its enclosed side and a reference point.
class Spherical_ring
{
public:
  /// \pre at least 3 distinct vertices, no two consecutive vertices antipodal (checked by the caller)
  explicit Spherical_ring(std::vector<Eigen::Vector3d> v) : m_v(std::move(v))
  {
    const std::size_t n = m_v.size();
    m_edge_caps.reserve(n);
    for(std::size_t i = 0; i < n; ++i) m_edge_caps.push_back(arc_cap(m_v[i], m_v[(i + 1) % n]));
    // area of the left side, modulo 4 pi, from a point in general position
    const Eigen::Vector3d p = Eigen::Vector3d(0.5773, 0.2121, 0.7884).normalized();
    double sum = 0;
    for(std::size_t i = 0; i < n; ++i) sum += signed_triangle_area(p, m_v[i], m_v[(i + 1) % n]);
    const double four_pi = 4 * 3.14159265358979323846;
    m_left_area = std::fmod(sum, four_pi);
    if(m_left_area < 0) m_left_area += four_pi;
    m_left_is_inside = m_left_area <= 0.5 * four_pi * (1 + 1e-9);
    choose_reference();
    // bounding cap of the enclosed side: from the vertex mean if every vertex is within
    // 90 degrees of it and the enclosed side is the one inside that cap
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for(const auto& x : m_v) mean += x;
    if(mean.norm() > 1e-9) {
      mean.normalize();
      double r = 0;
      for(std::size_t i = 0; i < n; ++i) {
        const Spherical_cap& e = m_edge_caps[i];
        r = std::max(r, std::acos(std::clamp(mean.dot(e.center), -1., 1.)) + e.radius);
      }
      if(r < 0.5 * 3.14159265358979323846 - 1e-6 && !encloses(-mean)) {
        m_cap.center = mean;
        m_cap.set_radius(r);
      }
    }
  }

  const std::vector<Eigen::Vector3d>& vertices() const { return m_v; }
  std::size_t size() const { return m_v.size(); }
  const Eigen::Vector3d& vertex(std::size_t i) const { return m_v[i]; }
  const Eigen::Vector3d& next_vertex(std::size_t i) const { return m_v[(i + 1) % m_v.size()]; }
  const Spherical_cap& edge_cap(std::size_t i) const { return m_edge_caps[i]; }
  /// Whether the enclosed side is to the left of the ring's direction (seen from outside).
  bool left_is_inside() const { return m_left_is_inside; }
  /// A cap containing the enclosed side (the whole sphere if none smaller was found).
  const Spherical_cap& cap() const { return m_cap; }
  /// Area of the enclosed side.
  double enclosed_area() const
  {
    return m_left_is_inside ? m_left_area : 4 * 3.14159265358979323846 - m_left_area;
  }

  /// True iff q is on the enclosed side (q off the ring).
  bool encloses(const Eigen::Vector3d& q) const
  {
    bool inside = m_reference_inside;
    if(m_reference.dot(q) >= 0) {
      inside ^= all_crossings_parity(m_reference, q);
    } else { // through a point at 90 degrees from R, so that both arcs are minor
      Eigen::Vector3d m = q - q.dot(m_reference) * m_reference;
      if(m.norm() < 1e-9) m = m_reference.unitOrthogonal();
      m.normalize();
      inside ^= all_crossings_parity(m_reference, m) != all_crossings_parity(m, q);
    }
    return inside;
  }

  /// Parity of the crossings of the arc pq with the edges listed (indices).
  /// `degenerate` is set if the arc passes exactly through a ring vertex or along an edge.
  bool crossing_parity(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const std::vector<int>& edges,
                       bool& degenerate) const
  {
    bool odd = false;
    for(int i : edges)
      if(arcs_cross(p, q, m_v[std::size_t(i)], next_vertex(std::size_t(i)), degenerate)) odd = !odd;
    return odd;
  }

private:
  bool all_crossings_parity(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const
  {
    bool odd = false;
    for(std::size_t i = 0; i < m_v.size(); ++i)
      if(arcs_cross(p, q, m_v[i], next_vertex(i))) odd = !odd;
    return odd;
  }

  // The reference point R: just to the left of the midpoint of an edge, closer
  // to that edge than to any other, so that it is on the left side. Among the
  // longest edges, the one whose midpoint is farthest from the other edges.
  void choose_reference()
  {
    const std::size_t n = m_v.size();
    std::vector<std::size_t> order(n);
    for(std::size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return m_edge_caps[i].radius > m_edge_caps[j].radius; });
    double best = 0;
    for(std::size_t k = 0; k < std::min<std::size_t>(n, 16); ++k) {
      const std::size_t e = order[k];
      const Eigen::Vector3d& mid = m_edge_caps[e].center;
      double d = m_edge_caps[e].radius; // stay well inside the edge's span
      for(std::size_t i = 0; i < n; ++i)
        if(i != e) d = std::min(d, distance_to_arc(mid, m_v[i], next_vertex(i)));
      if(d <= best) continue;
      best = d;
      const Eigen::Vector3d left = m_v[e].cross(next_vertex(e)).normalized();
      const double delta = 0.25 * d;
      m_reference = (std::cos(delta) * mid + std::sin(delta) * left).normalized();
    }
    if(!(best > 1e-12))
      throw Invalid_input("a ring of " + std::to_string(n) + " vertices touches itself (no point near an edge is clear of the others)");
    m_reference_inside = m_left_is_inside;
  }

  std::vector<Eigen::Vector3d> m_v;
  std::vector<Spherical_cap> m_edge_caps;
  Spherical_cap m_cap;
  double m_left_area = 0;
  bool m_left_is_inside = true;
  Eigen::Vector3d m_reference = Eigen::Vector3d::UnitZ();
  bool m_reference_inside = false;
};

/// The rings of a polygon on the unit sphere, checked: `where` names the polygon in messages.
inline std::vector<Spherical_ring> polygon_rings(const Spherical_polygon& p, const std::string& where)
{
  if(p.rings.empty()) throw Invalid_input(where + ": a polygon without rings");
  std::vector<Spherical_ring> rings;
  for(std::size_t k = 0; k < p.rings.size(); ++k) {
    const std::string ring = where + ", ring " + std::to_string(k);
    std::vector<Eigen::Vector3d> v;
    for(const Lon_lat& x : p.rings[k]) {
      if(!(std::isfinite(x.lon) && std::isfinite(x.lat) && std::abs(x.lat) <= 90 && std::abs(x.lon) <= 540))
        throw Invalid_input(ring + ": invalid position (" + std::to_string(x.lon) + ", " + std::to_string(x.lat) + ")");
      const Eigen::Vector3d u = unit_vector(x);
      if(!v.empty() && (u - v.back()).norm() < 1e-12) continue; // repeated point (also 180 / -180, the poles)
      v.push_back(u);
    }
    while(v.size() > 1 && (v.front() - v.back()).norm() < 1e-12) v.pop_back();
    if(v.size() < 3) throw Invalid_input(ring + ": fewer than 3 distinct positions");
    for(std::size_t i = 0; i < v.size(); ++i)
      if(v[i].dot(v[(i + 1) % v.size()]) < -1 + 1e-12)
        throw Invalid_input(ring + ": positions " + std::to_string(i) + " and " + std::to_string(i + 1) +
                            " are antipodal, the great-circle edge between them is undefined");
    rings.emplace_back(std::move(v));
  }
  return rings;
}

/// The overlap of mesh faces with regions: per face, (region, fraction of the face's area).
struct Face_region_overlaps
{
  std::vector<std::vector<std::pair<std::size_t, double> > > parts; ///< per face
  double overlapping_fraction = 0; ///< sum over faces of the fraction covered by more than one region (face units)
  std::size_t sampled_overlaps = 0; ///< exact overlaps asked for but ill-posed (a ring edge along a face's edge): sampled
};

/// The centroid, bounding cap and neighbours of each face of a mesh on the unit sphere.
struct Sphere_faces
{
  std::vector<Eigen::Vector3d> centroid;
  std::vector<Spherical_cap> cap;
  std::vector<std::array<Eigen::Index, 3> > neighbour;

  Sphere_faces(const Matrix& X, const Index_matrix& F)
  {
    const Eigen::Index m = F.rows();
    centroid.resize(std::size_t(m));
    cap.resize(std::size_t(m));
    for(Eigen::Index f = 0; f < m; ++f) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for(int j = 0; j < 3; ++j) c += X.row(F(f, j)).transpose().normalized();
      c.normalize();
      double r = 0;
      for(int j = 0; j < 3; ++j) r = std::max(r, std::acos(std::clamp(c.dot(X.row(F(f, j)).transpose().normalized()), -1., 1.)));
      centroid[std::size_t(f)] = c;
      cap[std::size_t(f)].center = c;
      cap[std::size_t(f)].set_radius(r + 1e-9);
    }
    neighbour = face_neighbours(F);
  }

  static std::vector<std::array<Eigen::Index, 3> > face_neighbours(const Index_matrix& F)
  {
    std::vector<std::array<Eigen::Index, 3> > nb(std::size_t(F.rows()), {{-1, -1, -1}});
    std::vector<std::pair<std::pair<int, int>, Eigen::Index> > edges;
    edges.reserve(std::size_t(3 * F.rows()));
    for(Eigen::Index f = 0; f < F.rows(); ++f)
      for(int j = 0; j < 3; ++j) {
        const int a = F(f, j), b = F(f, (j + 1) % 3);
        edges.push_back({{std::min(a, b), std::max(a, b)}, f * 3 + j});
      }
    std::sort(edges.begin(), edges.end());
    for(std::size_t k = 0; k + 1 < edges.size(); ++k)
      if(edges[k].first == edges[k + 1].first) {
        const Eigen::Index e0 = edges[k].second, e1 = edges[k + 1].second;
        nb[std::size_t(e0 / 3)][std::size_t(e0 % 3)] = e1 / 3;
        nb[std::size_t(e1 / 3)][std::size_t(e1 % 3)] = e0 / 3;
        ++k;
      }
    return nb;
  }
};

/// Barycentric coordinates of the centroids of the s^2 congruent sub-triangles of a triangle.
inline std::vector<Eigen::Vector3d> subtriangle_centroids(int s)
{
  std::vector<Eigen::Vector3d> out;
  for(int i = 0; i < s; ++i)
    for(int j = 0; i + j < s; ++j) {
      const double u = (i + 1. / 3) / s, v = (j + 1. / 3) / s;
      out.emplace_back(1 - u - v, u, v);
      if(i + j + 2 <= s) {
        const double u2 = (i + 2. / 3) / s, v2 = (j + 2. / 3) / s;
        out.emplace_back(1 - u2 - v2, u2, v2);
      }
    }
  return out;
}

/// The share of the flat face (corner[0], corner[1], corner[2]) (vertices on the unit
/// sphere) that lies, seen from the centre, on the enclosed side of `ring`, exactly up to
/// round-off; negative where that is ill-posed (a ring edge along an edge of the face),
/// for the caller to use samples there.
///
/// Seen from the centre, the face is the cone over its corners and a ring edge is the
/// chord between its ends: a point (1 - t) u + t w of the chord has a direction on the
/// arc u w, and its side of a plane through the centre is linear in t, so clipping the
/// chord to the cone's three planes clips the arc exactly. The clipped pieces, projected
/// from the centre onto the face's plane, are straight segments; with the pieces of the
/// face's edges that lie on the enclosed side (each classified at its midpoint by the
/// crossings of the arc from the face's centroid, whose side is known), they bound the
/// face's covered part, whose area the shoelace formula gives. Ring edges are taken
/// with the enclosed side on their left, the face's edges counterclockwise, both seen
/// from outside the sphere.
inline double enclosed_face_fraction(const Spherical_ring& ring, const std::vector<int>& near,
                                     const Eigen::Vector3d& centroid, bool centroid_enclosed,
                                     std::array<Eigen::Vector3d, 3> corner)
{
  Eigen::Vector3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
  if(normal.dot(corner[0] + corner[1] + corner[2]) < 0) {
    std::swap(corner[1], corner[2]);
    normal = -normal;
  }
  const double twice_area = normal.norm();
  if(!(twice_area > 0)) return -1;
  normal /= twice_area;
  const double offset = normal.dot(corner[0]);
  const Eigen::Vector3d e1 = (corner[1] - corner[0]).normalized(), e2 = normal.cross(e1);
  const auto in_plane = [&](const Eigen::Vector3d& direction) {
    const Eigen::Vector3d p = direction * (offset / normal.dot(direction)) - corner[0];
    return Eigen::Vector2d(p.dot(e1), p.dot(e2));
  };
  std::array<Eigen::Vector2d, 3> flat;
  std::array<Eigen::Vector3d, 3> inward; // normal of the plane through the centre and edge i, into the cone
  for(int i = 0; i < 3; ++i) {
    flat[std::size_t(i)] = in_plane(corner[std::size_t(i)]);
    inward[std::size_t(i)] = corner[std::size_t(i)].cross(corner[std::size_t((i + 1) % 3)]).normalized();
  }
  double twice_covered = 0;
  const auto shoelace = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { twice_covered += p.x() * q.y() - q.x() * p.y(); };
  const auto position_on_edge = [&](int i, const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = flat[std::size_t((i + 1) % 3)] - flat[std::size_t(i)];
    return std::clamp((p - flat[std::size_t(i)]).dot(d) / d.squaredNorm(), 0., 1.);
  };
  std::array<std::vector<double>, 3> hits; // where ring pieces meet edge i, in [0, 1] from corner i
  const double on_plane = 1e-14;
  for(int j : near) {
    Eigen::Vector3d u = ring.vertex(std::size_t(j)), w = ring.next_vertex(std::size_t(j));
    if(!ring.left_is_inside()) std::swap(u, w);
    double t0 = 0, t1 = 1;
    int enters = -1, leaves = -1;
    bool outside = false;
    for(int i = 0; i < 3 && !outside; ++i) {
      const double fu = inward[std::size_t(i)].dot(u), fw = inward[std::size_t(i)].dot(w);
      if(std::abs(fu) <= on_plane && std::abs(fw) <= on_plane) return -1; // along the face's edge
      if(fu < 0 && fw < 0) outside = true;
      else if(fu < 0 || fw < 0) {
        const double t = fu / (fu - fw);
        if(fu < 0 && t > t0) { t0 = t; enters = i; }
        if(fw < 0 && t < t1) { t1 = t; leaves = i; }
      }
    }
    if(outside || t0 >= t1) continue;
    const Eigen::Vector2d p = in_plane((1 - t0) * u + t0 * w), q = in_plane((1 - t1) * u + t1 * w);
    shoelace(p, q);
    if(enters >= 0) hits[std::size_t(enters)].push_back(position_on_edge(enters, p));
    if(leaves >= 0) hits[std::size_t(leaves)].push_back(position_on_edge(leaves, q));
  }
  for(int i = 0; i < 3; ++i) {
    std::vector<double>& h = hits[std::size_t(i)];
    h.push_back(0);
    h.push_back(1);
    std::sort(h.begin(), h.end());
    const Eigen::Vector3d& a = corner[std::size_t(i)];
    const Eigen::Vector3d& b = corner[std::size_t((i + 1) % 3)];
    for(std::size_t k = 0; k + 1 < h.size(); ++k) {
      if(!(h[k + 1] > h[k])) continue;
      const Eigen::Vector3d mid = (a + 0.5 * (h[k] + h[k + 1]) * (b - a)).normalized();
      bool degenerate = false;
      bool enclosed = centroid_enclosed != ring.crossing_parity(centroid, mid, near, degenerate);
      if(degenerate) enclosed = ring.encloses(mid);
      if(enclosed) shoelace(in_plane(a + h[k] * (b - a)), in_plane(a + h[k + 1] * (b - a)));
    }
  }
  const double fraction = twice_covered / twice_area;
  if(!(fraction > -1e-9 && fraction < 1 + 1e-9)) return -1;
  return std::clamp(fraction, 0., 1.);
}

/// The share of a face covered by a polygon (exterior ring minus holes) from
/// enclosed_face_fraction(); negative if one ring's is ill-posed. `side[g][k]`: whether
/// the face's centroid is enclosed by ring g; `near[g][k]`: ring g's edges near the face.
inline double exact_polygon_fraction(const std::vector<Spherical_ring>& rings,
                                     const std::vector<std::vector<std::vector<int> > >& near,
                                     const std::vector<std::vector<char> >& side, std::size_t k,
                                     const Eigen::Vector3d& centroid, const std::array<Eigen::Vector3d, 3>& corner)
{
  double covered = 0;
  for(std::size_t g = 0; g < rings.size(); ++g) {
    const double f = near[g][k].empty() ? double(side[g][k] == 1)
                                        : enclosed_face_fraction(rings[g], near[g][k], centroid, side[g][k] == 1, corner);
    if(f < 0) return -1;
    covered += g == 0 ? f : -f;
  }
  return std::max(0., covered);
}

/// The fraction of each face of (X, F) (a mesh of the unit sphere, vertices on it)
/// covered by each polygon of each region, with s^2 samples per face near a boundary
/// (s = subdivision), or exact where well posed (subdivision 0; 8 x 8 samples then
/// only measure the overlaps between regions).
inline Face_region_overlaps face_region_overlaps(const Matrix& X, const Index_matrix& F,
                                                 const std::vector<Spherical_region>& regions, int subdivision)
{
  const std::size_t m = std::size_t(F.rows());
  const Sphere_faces faces(X, F);
  const bool exact_fractions = subdivision == 0;
  const std::vector<Eigen::Vector3d> bary = subtriangle_centroids(exact_fractions ? 8 : subdivision);
  const double sample_weight = 1. / double(bary.size());
  std::vector<std::vector<std::pair<std::size_t, double> > > parts(m);
  // per face: which samples are covered already (for overlaps), only for faces near a boundary
  std::vector<std::vector<unsigned char> > covered(m);
  std::vector<double> total(m, 0.);
  double overlapping = 0;
  std::size_t sampled = 0;

  std::vector<int> face_slot(m, -1);
  for(std::size_t r = 0; r < regions.size(); ++r) {
    std::vector<double> region_fraction(m, 0.);
    std::vector<std::size_t> touched;
    for(std::size_t p = 0; p < regions[r].polygons.size(); ++p) {
      const std::string where = "region \"" + regions[r].id + "\", polygon " + std::to_string(p);
      const std::vector<Spherical_ring> rings = polygon_rings(regions[r].polygons[p], where);
      // faces that can meet the polygon: those meeting the exterior ring's cap
      std::vector<std::size_t> candidates;
      for(std::size_t f = 0; f < m; ++f)
        if(rings[0].cap().meets(faces.cap[f])) candidates.push_back(f);
      for(std::size_t k = 0; k < candidates.size(); ++k) face_slot[candidates[k]] = int(k);
      const std::size_t nc = candidates.size();
      // per ring: nearby edges of each candidate face, centroid sides
      std::vector<std::vector<std::vector<int> > > near(rings.size(), std::vector<std::vector<int> >(nc));
      std::vector<std::vector<char> > side(rings.size(), std::vector<char>(nc, -1));
      for(std::size_t g = 0; g < rings.size(); ++g) {
        const Spherical_ring& ring = rings[g];
        for(std::size_t e = 0; e < ring.size(); ++e)
          for(std::size_t k = 0; k < nc; ++k)
            if(ring.edge_cap(e).meets(faces.cap[candidates[k]])) near[g][k].push_back(int(e));
        // breadth-first classification of the centroids
        std::deque<std::size_t> queue;
        for(std::size_t seed = 0; seed < nc; ++seed) {
          if(side[g][seed] >= 0) continue;
          side[g][seed] = ring.encloses(faces.centroid[candidates[seed]]) ? 1 : 0;
          queue.push_back(seed);
          while(!queue.empty()) {
            const std::size_t k = queue.front();
            queue.pop_front();
            const std::size_t f = candidates[k];
            for(Eigen::Index nbf : faces.neighbour[f]) {
              if(nbf < 0 || face_slot[std::size_t(nbf)] < 0) continue;
              const std::size_t kn = std::size_t(face_slot[std::size_t(nbf)]);
              if(side[g][kn] >= 0) continue;
              std::vector<int> edges = near[g][k];
              edges.insert(edges.end(), near[g][kn].begin(), near[g][kn].end());
              std::sort(edges.begin(), edges.end());
              edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
              bool degenerate = false;
              const bool flip = ring.crossing_parity(faces.centroid[f], faces.centroid[std::size_t(nbf)], edges, degenerate);
              if(degenerate) continue; // through a ring vertex: reach that face another way (or seed it)
              side[g][kn] = char(side[g][k] ^ (flip ? 1 : 0));
              queue.push_back(kn);
            }
          }
        }
      }
      // fractions
      for(std::size_t k = 0; k < nc; ++k) {
        const std::size_t f = candidates[k];
        bool near_boundary = false;
        for(std::size_t g = 0; g < rings.size(); ++g) near_boundary = near_boundary || !near[g][k].empty();
        double fraction = 0;
        if(!near_boundary) {
          bool in = side[0][k] == 1;
          for(std::size_t g = 1; g < rings.size() && in; ++g) in = side[g][k] == 0;
          if(!in) continue;
          fraction = 1;
          if(!covered[f].empty() || total[f] > 0) overlapping += std::min(1., total[f]);
        } else {
          if(covered[f].empty()) covered[f].assign(bary.size(), total[f] >= 1 - 1e-12 ? 1 : 0);
          const Eigen::Vector3d a = X.row(F(Eigen::Index(f), 0)).transpose(), b = X.row(F(Eigen::Index(f), 1)).transpose(),
                                c = X.row(F(Eigen::Index(f), 2)).transpose();
          for(std::size_t s = 0; s < bary.size(); ++s) {
            const Eigen::Vector3d q = (bary[s][0] * a + bary[s][1] * b + bary[s][2] * c).normalized();
            bool in = true;
            for(std::size_t g = 0; g < rings.size() && in; ++g) {
              bool degenerate = false;
              bool enclosed = (side[g][k] == 1) != rings[g].crossing_parity(faces.centroid[f], q, near[g][k], degenerate);
              if(degenerate) enclosed = rings[g].encloses(q);
              in = (g == 0) ? enclosed : !enclosed;
            }
            if(!in) continue;
            fraction += sample_weight;
            if(covered[f][s]) overlapping += sample_weight;
            covered[f][s] = 1;
          }
          if(exact_fractions) { // where it is well posed
            const double exact = exact_polygon_fraction(rings, near, side, k, faces.centroid[f], {{a, b, c}});
            if(exact >= 0) fraction = exact;
            else ++sampled;
          }
          if(fraction == 0) continue;
        }
        if(region_fraction[f] == 0) touched.push_back(f);
        region_fraction[f] += fraction;
        total[f] += fraction;
      }
      for(std::size_t f : candidates) face_slot[f] = -1;
    }
    for(std::size_t f : touched) parts[f].push_back({r, std::min(1., region_fraction[f])});
  }
  // a face covered more than once (overlapping input regions) is shared in proportion
  for(std::size_t f = 0; f < m; ++f)
    if(total[f] > 1)
      for(auto& p : parts[f]) p.second /= total[f];
  Face_region_overlaps out;
  out.parts = std::move(parts);
  out.overlapping_fraction = overlapping;
  out.sampled_overlaps = sampled;
  return out;
}

/// The point of the minor arc ab nearest to p (all on the unit sphere).
inline Eigen::Vector3d nearest_point_on_arc(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d n = a.cross(b).normalized();
  const Eigen::Vector3d foot = p - p.dot(n) * n;
  if(foot.norm() > 1e-12 && a.cross(foot).dot(n) >= 0 && foot.cross(b).dot(n) >= 0) return foot.normalized();
  return p.dot(a) >= p.dot(b) ? a : b;
}

/// Moves every vertex of the sphere mesh (X, F) that lies within `reach` radians of a
/// region's border onto the nearest point of that border, unless that would turn over or
/// flatten one of its faces (exact orientation about the centre). Returns the number moved.
///
/// Why: a border that passes a vertex closely cuts thin slivers off the faces around it.
/// With exact overlaps every sliver counts, and a face holding a sliver of a region that a
/// cartogram must shrink a thousandfold must shrink with it, though the rest of the face is
/// sea; through the vertex, the border leaves those faces alone.
inline std::size_t snap_vertices_to_borders(Matrix& X, const Index_matrix& F, const std::vector<Spherical_region>& regions,
                                            double reach)
{
  const Eigen::Index n = X.rows();
  // spatial hash of the vertices, cells of side `reach` (chord lengths)
  const double cell = std::max(reach, 1e-9);
  auto key = [&](const Eigen::Vector3d& x) {
    const auto c = [&](double v) { return long(std::floor((v + 1.5) / cell)); };
    return std::array<long, 3>{{c(x.x()), c(x.y()), c(x.z())}};
  };
  std::map<std::array<long, 3>, std::vector<Eigen::Index> > grid;
  for(Eigen::Index i = 0; i < n; ++i) grid[key(X.row(i).transpose())].push_back(i);
  const std::size_t nv = static_cast<std::size_t>(n);
  std::vector<double> best(nv, reach);
  std::vector<Eigen::Vector3d> target(nv);
  std::vector<char> has_target(nv, 0);
  for(const Spherical_region& r : regions)
    for(std::size_t p = 0; p < r.polygons.size(); ++p)
      for(const Spherical_ring& ring : polygon_rings(r.polygons[p], "region \"" + r.id + "\", polygon " + std::to_string(p)))
        for(std::size_t e = 0; e < ring.size(); ++e) {
          const Eigen::Vector3d& a = ring.vertex(e);
          const Eigen::Vector3d& b = ring.next_vertex(e);
          const double length = std::acos(std::clamp(a.dot(b), -1., 1.));
          const int steps = std::max(1, int(std::ceil(length / (0.5 * cell))));
          std::vector<std::array<long, 3> > seen;
          for(int k = 0; k <= steps; ++k) {
            const Eigen::Vector3d x = (a + (b - a) * (double(k) / steps)).normalized();
            const std::array<long, 3> c = key(x);
            for(long dx = -1; dx <= 1; ++dx)
              for(long dy = -1; dy <= 1; ++dy)
                for(long dz = -1; dz <= 1; ++dz) {
                  const std::array<long, 3> q{{c[0] + dx, c[1] + dy, c[2] + dz}};
                  if(std::find(seen.begin(), seen.end(), q) != seen.end()) continue;
                  seen.push_back(q);
                  const auto it = grid.find(q);
                  if(it == grid.end()) continue;
                  for(Eigen::Index i : it->second) {
                    const Eigen::Vector3d v = X.row(i).transpose().normalized();
                    const Eigen::Vector3d y = nearest_point_on_arc(v, a, b);
                    const double d = std::acos(std::clamp(v.dot(y), -1., 1.));
                    if(d < best[std::size_t(i)]) {
                      best[std::size_t(i)] = d;
                      target[std::size_t(i)] = y;
                      has_target[std::size_t(i)] = 1;
                    }
                  }
                }
          }
        }
  std::vector<std::vector<Eigen::Index> > faces_of(nv);
  for(Eigen::Index f = 0; f < F.rows(); ++f)
    for(int j = 0; j < 3; ++j) faces_of[std::size_t(F(f, j))].push_back(f);
  std::size_t moved = 0;
  for(Eigen::Index i = 0; i < n; ++i) {
    if(!has_target[std::size_t(i)]) continue;
    const Eigen::RowVector3d old = X.row(i);
    X.row(i) = target[std::size_t(i)].transpose();
    bool valid = true;
    for(Eigen::Index f : faces_of[std::size_t(i)])
      valid = valid && orientation_about_center(X.row(F(f, 0)).transpose(), X.row(F(f, 1)).transpose(),
                                                X.row(F(f, 2)).transpose()) > 0;
    if(valid) ++moved;
    else X.row(i) = old;
  }
  return moved;
}

/// The area to the left of a closed chain of points of the unit sphere joined by
/// great-circle arcs, in [0, 4 pi): a fan of signed triangles from the chain's mean
/// direction, so that a small ring is not the difference of large areas. Unlike
/// Spherical_ring, it takes any chain (repeated or nearly coincident points, as a boundary
/// shrunk by a map may have).
inline double area_to_the_left(const std::vector<Lon_lat>& ring)
{
  std::vector<Eigen::Vector3d> v;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for(const Lon_lat& x : ring) {
    v.push_back(unit_vector(x));
    mean += v.back();
  }
  const Eigen::Vector3d apex = mean.norm() > 1e-9 ? mean.normalized().eval() : Eigen::Vector3d::UnitZ();
  double sum = 0;
  for(std::size_t i = 0; i < v.size(); ++i) sum += signed_triangle_area(apex, v[i], v[(i + 1) % v.size()]);
  const double four_pi = 4 * 3.14159265358979323846;
  double left = std::fmod(sum, four_pi);
  if(left < 0) left += four_pi;
  return left;
}

/// Points every `step` radians (at most) along the great-circle arc from a to b,
/// a included, b excluded. The points depend only on the unordered pair {a, b}
/// (computed from the lexicographically smaller end), so an edge shared by two
/// rings, traversed in opposite directions, gets exactly the same points.
inline void densify_arc(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double step,
                        std::vector<Eigen::Vector3d>& out)
{
  const bool forward = std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  const Eigen::Vector3d& p = forward ? a : b;
  const Eigen::Vector3d& q = forward ? b : a;
  const double angle = std::acos(std::clamp(p.dot(q), -1., 1.));
  const int n = std::max(1, int(std::ceil(angle / step)));
  std::vector<Eigen::Vector3d> pts;
  const double s = std::sin(angle);
  for(int i = 1; i < n; ++i) {
    const double t = double(i) / n;
    pts.push_back(s > 1e-15 ? ((std::sin((1 - t) * angle) * p + std::sin(t * angle) * q) / s).normalized().eval()
                            : p);
  }
  out.push_back(a);
  if(forward) out.insert(out.end(), pts.begin(), pts.end());
  else out.insert(out.end(), pts.rbegin(), pts.rend());
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_REGIONS_H
