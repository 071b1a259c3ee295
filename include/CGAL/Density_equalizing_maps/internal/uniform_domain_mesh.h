// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H

// Near-uniform triangulations of the domains with a prescribed number of
// vertices (ALGORITHMS.md section 11, "Remeshing"), on index arrays.
//
// Sphere and ellipsoid, coarse to fine (multilevel_ellipsoid_mesh):
//  1. a coarse mesh of V_c ~ 300 vertices: the icosahedral geodesic sphere of
//     the largest frequency below V_c, completed by edge splits at Fibonacci
//     directions, intrinsic Delaunay flips, the linear map diag(a, b, c) onto the
//     ellipsoid (every face stays positively oriented about the origin);
//  2. 1,000 DistMesh steps on it (repulsive springs towards 1.1 x the mean edge
//     length, tangential, radial projection back, intrinsic Delaunay flips):
//     the size imbalance of the linear map relaxes only diffusively, in a number
//     of steps growing with the vertex count, so it is removed where that is
//     cheap, and the flips create the 5-7 defects that the curvature of the
//     ellipsoid needs (a valence-6 lattice sheared by the linear map cannot be
//     both equilateral and uniform);
//  3. one to three subdivision levels (factors <= 6, product k with
//     k^2 (V_c - 2) + 2 within 1 % of N): each face split by its barycentric
//     grid, new points projected radially, then 80 DistMesh steps (1.2 x the
//     mean), enough as the defects are those of the coarse mesh and the
//     subdivided faces have the coarse shapes already.
// The geodesic sphere itself is kept for the unit sphere when 10 f^2 + 2 is
// within 1 % of N (delta_shape 0.016-0.030). Measured (test_domain_mesh_quality,
// see benchmark/RESULTS.md, issue 12 item 2): delta_shape 0.016-0.045 and
// delta_size 0.19-0.67 on the sphere and the ellipsoids 1:1:2, 1:2:3, 1:1:5
// for N = 100 ... 100,000, about 0.2 s for 10,000 and 2 s for 100,000
// vertices. Before (geodesic sphere of N vertices, linear map, spring
// relaxation directly at N): delta_size 1.5-4.2 and delta_shape 0.07-0.13 on
// the ellipsoids from N = 8,500, 40 s for 1:1:5 at 100,000; on the sphere
// delta_shape 0.066-0.084 for N = 100-700 and 0.050, delta_size 0.75 at
// N = 10,140 and 20,000 (many vertices inserted into a geodesic sphere heal
// slowly). Also measured and rejected: ODT smoothing (circumcentres) and
// two-sided springs at the coarse level keep the sheared lattice
// (delta_shape 0.07-0.08); valence-driven flips jam the springs (0.11).
//
// Torus: a triangular lattice of nu x nv vertices on the flat torus, each row
// shifted by half a column (nv even, so the shift closes up), every vertex of
// valence 6. The rows are spaced so that d(theta) is proportional to
// w(theta)^beta, w = R + r cos(theta) the radius of the parallel: beta = 1
// gives equilateral (conformal) triangles whose areas vary as w^2, beta = -1
// equal areas with aspect ratios varying as w^2; beta is the largest value
// that keeps delta_size = (1 + beta) ln(w_max / w_min) within the target,
// i.e. the best shapes at the required size uniformity.
// At R/r = 3 the best such lattice has delta_shape 0.072 at delta_size 0.69
// (0.23 at N = 100): a lattice meets item 8 (valence 6) but not item 2.
//
// Torus, relaxed (relaxed_torus_mesh, `torus_lattice(false)`): the lattice with
// about 300 vertices (rows for delta_size 0.5) relaxed by 2,000 DistMesh steps
// in the flat-torus coordinates (forces from the 3D chords, moved by the inverse
// Jacobian of the parameterization, so every vertex is exactly on the torus;
// exact orientation in the unwrapped flat torus), then subdivision levels with
// 80 steps as on the ellipsoid. Its flips create vertices of valence 5 and 7.
// Measured on (3, 1), N = 100 ... 100,000: delta_shape 0.036-0.042, delta_size
// 0.19-0.50 (item 2), 0.26 s at 10,000 vertices. Starting from the rows for
// delta_size 0.69 gave 0.055 at N = 150, from equal-area rows 0.045.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/point_location.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

struct Triangle_arrays
{
  Matrix X;
  Index_matrix F;
};

/// The midpoint subdivision of a mesh of the unit sphere: each face split into
/// four at the midpoints of its edges, the new points projected radially. The
/// vertices keep their indices, the new ones follow; the four faces of face k
/// are 4k..4k+3. Seen from the centre, each new face lies inside its old one
/// (the projected midpoint of an edge is on the ray through the chord's midpoint).
inline Triangle_arrays midpoint_subdivision_on_sphere(const Triangle_arrays& m)
{
  std::map<std::pair<int, int>, int> midpoint_of;
  std::vector<Eigen::Vector3d> added;
  const Eigen::Index n = m.X.rows();
  auto midpoint = [&](int a, int b) {
    const std::pair<int, int> key = std::minmax(a, b);
    const auto it = midpoint_of.find(key);
    if(it != midpoint_of.end()) return it->second;
    added.push_back((m.X.row(a) + m.X.row(b)).transpose().normalized());
    return midpoint_of[key] = int(n + Eigen::Index(added.size()) - 1);
  };
  Triangle_arrays s;
  s.F.resize(4 * m.F.rows(), 3);
  for(Eigen::Index k = 0; k < m.F.rows(); ++k) {
    const int a = m.F(k, 0), b = m.F(k, 1), c = m.F(k, 2);
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    s.F.row(4 * k) << a, ab, ca;
    s.F.row(4 * k + 1) << ab, b, bc;
    s.F.row(4 * k + 2) << ca, bc, c;
    s.F.row(4 * k + 3) << ab, bc, ca;
  }
  s.X.resize(n + Eigen::Index(added.size()), 3);
  s.X.topRows(n) = m.X;
  for(std::size_t i = 0; i < added.size(); ++i) s.X.row(n + Eigen::Index(i)) = added[i].transpose();
  return s;
}

/// N points of the spherical Fibonacci lattice: z uniform in (-1, 1) (equal
/// areas per point), longitude advancing by the golden angle.
inline Matrix fibonacci_sphere_points(Eigen::Index n)
{
  const double golden_angle = M_PI * (3. - std::sqrt(5.));
  Matrix P(n, 3);
  for(Eigen::Index i = 0; i < n; ++i) {
    const double z = 1. - (2. * double(i) + 1.) / double(n);
    const double s = std::sqrt(std::max(0., 1. - z * z)), phi = golden_angle * double(i);
    P.row(i) << s * std::cos(phi), s * std::sin(phi), z;
  }
  return P;
}

/// Replaces the content of `out` by the mesh (X, F).
template <class PolygonMesh>
void write_triangle_mesh(const Matrix& X, const Index_matrix& F, PolygonMesh& out)
{
  typedef typename boost::property_traits<typename CGAL::GetVertexPointMap<PolygonMesh>::type>::value_type Point;
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(X.rows()));
  for(Eigen::Index i = 0; i < X.rows(); ++i) points.emplace_back(X(i, 0), X(i, 1), X(i, 2));
  std::vector<std::array<std::size_t, 3> > triangles(static_cast<std::size_t>(F.rows()));
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    triangles[k] = {{std::size_t(F(k, 0)), std::size_t(F(k, 1)), std::size_t(F(k, 2))}};
  CGAL::clear(out);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, out);
}

/// The icosahedral geodesic sphere of frequency f: every face of the regular
/// icosahedron split into f^2 triangles by its barycentric grid, the points
/// projected radially onto the unit sphere; 10 f^2 + 2 vertices, all of
/// valence 6 but the 12 of the icosahedron (valence 5), faces oriented outward.
inline Triangle_arrays geodesic_sphere(int f)
{
  const double t = (1 + std::sqrt(5.)) / 2;
  const double V[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const int T[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  std::map<std::array<int, 4>, int> id; // shared points: corners and edge points by their edge, others by face
  std::vector<Eigen::Vector3d> P;
  std::vector<Eigen::Vector3i> G;
  auto vertex = [&](int face, int i, int j) {
    const int w[3] = {f - i - j, i, j};
    const int* c = T[face];
    std::array<int, 4> key{{-1, -1, -1, -1}};
    int nonzero = 0;
    for(int a = 0; a < 3; ++a) nonzero += w[a] > 0;
    if(nonzero == 1) {
      for(int a = 0; a < 3; ++a) if(w[a] == f) key = {{c[a], -1, -1, 0}};
    } else if(nonzero == 2) {
      int a = 0;
      while(w[a] == 0) ++a;
      int b = a + 1;
      while(w[b] == 0) ++b;
      // the edge (c[a], c[b]) with w[b] steps from c[a]: store from the lower vertex
      if(c[a] < c[b]) key = {{c[a], c[b], w[b], 1}};
      else key = {{c[b], c[a], w[a], 1}};
    } else {
      key = {{face, i, j, 2}};
    }
    auto it = id.find(key);
    if(it != id.end()) return it->second;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for(int a = 0; a < 3; ++a) p += w[a] * Eigen::Vector3d(V[c[a]][0], V[c[a]][1], V[c[a]][2]);
    P.push_back(p.normalized());
    return id[key] = int(P.size()) - 1;
  };
  for(int face = 0; face < 20; ++face)
    for(int i = 0; i < f; ++i)
      for(int j = 0; i + j < f; ++j) {
        G.emplace_back(vertex(face, i, j), vertex(face, i + 1, j), vertex(face, i, j + 1));
        if(i + j + 1 < f) G.emplace_back(vertex(face, i + 1, j), vertex(face, i + 1, j + 1), vertex(face, i, j + 1));
      }
  Triangle_arrays a;
  a.X.resize(Eigen::Index(P.size()), 3);
  for(std::size_t k = 0; k < P.size(); ++k) a.X.row(k) = P[k].transpose();
  a.F.resize(Eigen::Index(G.size()), 3);
  for(std::size_t k = 0; k < G.size(); ++k) a.F.row(k) = G[k].transpose();
  if(count_inverted_faces_about_center(a.X, a.F) > 0) a.F.col(1).swap(a.F.col(2));
  return a;
}

/// Adds `extra` vertices to a mesh of the unit sphere by splitting one edge
/// in each of `extra` faces spread uniformly (the faces containing `extra`
/// Fibonacci directions; each face and its neighbour take one split at most).
inline void insert_spread_vertices(Triangle_arrays& a, Eigen::Index extra)
{
  if(extra <= 0) return;
  const Spherical_point_locator locator(a.X, a.F, 1);
  const Face_neighbor_matrix N = face_neighbors(a.F, Vertex_faces(a.F, a.X.rows()));
  const Matrix D = fibonacci_sphere_points(extra);
  std::vector<char> used(static_cast<std::size_t>(a.F.rows()), 0);
  std::vector<std::array<Eigen::Index, 2> > splits; // (face, corner opposite the split edge)
  for(Eigen::Index s = 0; s < extra; ++s) {
    Eigen::Index k = locator.locate(row_vector3(D, s));
    // the face itself or, if taken, a free neighbour; split its longest edge whose other face is free
    std::array<Eigen::Index, 2> best{{-1, -1}};
    double best_length = -1;
    for(int attempt = 0; attempt < 4 && best[0] < 0; ++attempt) {
      const Eigen::Index c = attempt == 0 ? k : N(k, attempt - 1);
      if(used[c]) continue;
      for(int e = 0; e < 3; ++e) {
        const Eigen::Index g = N(c, e);
        if(used[g]) continue;
        const double l = (a.X.row(a.F(c, (e + 1) % 3)) - a.X.row(a.F(c, (e + 2) % 3))).norm();
        if(l > best_length) { best_length = l; best = {{c, e}}; }
      }
    }
    if(best[0] < 0) continue;
    used[best[0]] = used[N(best[0], best[1])] = 1;
    splits.push_back(best);
  }
  const Eigen::Index n0 = a.X.rows(), m0 = a.F.rows(), added = Eigen::Index(splits.size());
  a.X.conservativeResize(n0 + added, 3);
  a.F.conservativeResize(m0 + 2 * added, 3);
  for(Eigen::Index s = 0; s < added; ++s) {
    const Eigen::Index k = splits[s][0];
    const int c = int(splits[s][1]);
    const Eigen::Index g = N(k, c);
    const int p = a.F(k, c), i = a.F(k, (c + 1) % 3), j = a.F(k, (c + 2) % 3);
    int e = 0;
    while(a.F(g, e) == i || a.F(g, e) == j) ++e;
    const int q = a.F(g, e);
    const int mid = int(n0 + s);
    a.X.row(mid) = (a.X.row(i) + a.X.row(j)).normalized();
    // (p, i, j) and (q, j, i) become (p, i, mid), (p, mid, j), (q, j, mid), (q, mid, i)
    a.F.row(k) << p, i, mid;
    a.F.row(m0 + 2 * s) << p, mid, j;
    a.F.row(g) << q, j, mid;
    a.F.row(m0 + 2 * s + 1) << q, mid, i;
  }
  // a collision left some Fibonacci directions without a split: retry with as many
  if(added < extra) insert_spread_vertices(a, extra - added);
}

/// The closest-in-direction point of the ellipsoid (radial projection).
inline void project_radially(Matrix& X, const Eigen::Vector3d& radii) { project_to_ellipsoid(X, radii); }

/// The sign of sin(alpha + beta) for the angles alpha at `a` in (a, i, j) and
/// beta at `b` in (b, j, i), both in (0, pi): negative exactly when
/// alpha + beta > pi, i.e. when the edge (i, j) is not locally Delaunay.
/// sin(alpha + beta) = sin(alpha) cos(beta) + cos(alpha) sin(beta), each
/// factor a cross or dot product over the same positive length products, so no
/// trigonometric function is needed (the flips were 70 % of the relaxation's
/// time with atan2). Returned relative to those length products.
inline double opposite_angle_sum_sine(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& i,
                                      const Eigen::Vector3d& j)
{
  const Eigen::Vector3d ai = i - a, aj = j - a, bj = j - b, bi = i - b;
  const double ca = ai.dot(aj), cb = bj.dot(bi);
  if(ca >= 0 && cb >= 0) return 1; // two angles of at most pi/2: the common case, decided without roots
  const double sa = ai.cross(aj).norm(), sb = bj.cross(bi).norm();
  const double scale = ai.norm() * aj.norm() * bj.norm() * bi.norm();
  return (sa * cb + ca * sb) / scale;
}

/// One pass of intrinsic-Delaunay edge flips on a closed mesh: an edge whose
/// opposite angles sum above pi is flipped unless the new edge exists already
/// or a new face is not `positive` (exact orientation about the origin on the
/// ellipsoids, in the unwrapped flat torus on the torus). Each face takes part in at most one flip
/// per pass. Returns the number of flips.
template <class FaceIsPositive>
std::size_t delaunay_flip_pass(const Matrix& X, Index_matrix& F, const FaceIsPositive& positive)
{
  const Eigen::Index n = X.rows(), m = F.rows();
  const Vertex_faces vf(F, n);
  const Face_neighbor_matrix N = face_neighbors(F, vf);
  std::unordered_set<long long> created; // edges made by this pass (vf is not updated)
  auto key = [n](long long i, long long j) { return std::min(i, j) * n + std::max(i, j); };
  auto has_edge = [&](int a, int b) {
    if(created.count(key(a, b))) return true;
    for(Eigen::Index s = vf.begin(a); s < vf.end(a); ++s)
      for(int c = 0; c < 3; ++c)
        if(F(vf.faces[s], c) == b) return true;
    return false;
  };
  std::vector<char> touched(static_cast<std::size_t>(m), 0);
  std::size_t flips = 0;
  for(Eigen::Index k = 0; k < m; ++k)
    for(int c = 0; c < 3 && !touched[k]; ++c) {
      // edge (i, j) opposite corner c = a; across it face g with opposite vertex b
      const int a = F(k, c), i = F(k, (c + 1) % 3), j = F(k, (c + 2) % 3);
      const Eigen::Index g = N(k, c);
      if(g < 0 || touched[g] || g < k) continue; // each edge once, from its face of lower index
      int e = 0;
      while(e < 3 && (F(g, e) == i || F(g, e) == j)) ++e;
      const int b = F(g, e);
      if(a == b ||
         opposite_angle_sum_sine(row_vector3(X, a), row_vector3(X, b), row_vector3(X, i), row_vector3(X, j)) >= -1e-12 ||
         has_edge(a, b))
        continue;
      // (a, i, j) and (b, j, i) become (a, i, b) and (b, j, a)
      if(!positive(a, i, b) || !positive(b, j, a)) continue;
      F.row(k) << a, i, b;
      F.row(g) << b, j, a;
      created.insert(key(a, b));
      touched[k] = touched[g] = 1;
      ++flips;
    }
  return flips;
}

/// Face (i, j, k) positively oriented about the origin (exact).
struct Positive_about_origin
{
  const Matrix& X;
  bool operator()(int i, int j, int k) const
  {
    auto point = [this](int v) { return Epick::Point_3(X(v, 0), X(v, 1), X(v, 2)); };
    return CGAL::orientation(Epick::Point_3(0, 0, 0), point(i), point(j), point(k)) == CGAL::POSITIVE;
  }
};

inline std::size_t delaunay_flip_pass(const Matrix& X, Index_matrix& F)
{
  return delaunay_flip_pass(X, F, Positive_about_origin{X});
}

inline void delaunay_flips(const Matrix& X, Index_matrix& F)
{
  for(int pass = 0; pass < 20 && delaunay_flip_pass(X, F) > 0; ++pass) {}
}

/// Unique undirected edges (i < j) of a closed mesh.
inline std::vector<std::array<int, 2> > mesh_edges(const Index_matrix& F)
{
  std::vector<std::array<int, 2> > e;
  e.reserve(static_cast<std::size_t>(3 * F.rows() / 2));
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3);
      if(i < j) e.push_back({{i, j}});
    }
  return e;
}

/// Spring displacement towards equal edge lengths: every edge pulls or
/// pushes its endpoints in proportion to its deviation from the mean length.
/// At rest all edges have the same length, so the triangles are equilateral
/// and of equal area as far as the connectivity allows.
inline Matrix equal_length_springs(const Matrix& X, const std::vector<std::array<int, 2> >& edges)
{
  double sum = 0;
  for(const auto& e : edges) sum += (X.row(e[0]) - X.row(e[1])).norm();
  const double target = sum / double(edges.size());
  Matrix D = Matrix::Zero(X.rows(), 3);
  for(const auto& e : edges) {
    const Eigen::RowVector3d d = X.row(e[0]) - X.row(e[1]);
    const double l = d.norm();
    if(!(l > 0)) continue;
    const Eigen::RowVector3d f = (target - l) / l * d;
    D.row(e[0]) += f;
    D.row(e[1]) -= f;
  }
  return D;
}

/// Keeps the tangential part of the displacements D: the normal part only
/// moves the points off the surface, and the radial projection back would turn
/// it into a drift along the surface where the surface is not a sphere.
inline void remove_normal_components(const Matrix& X, const Eigen::Vector3d& radii, Matrix& D)
{
  const Eigen::Vector3d w = radii.cwiseProduct(radii).cwiseInverse();
  for(Eigen::Index i = 0; i < X.rows(); ++i) {
    const Eigen::Vector3d n = row_vector3(X, i).cwiseProduct(w).normalized();
    const Eigen::Vector3d d = row_vector3(D, i);
    D.row(i) = (d - d.dot(n) * n).transpose();
  }
}

/// Spring relaxation on the ellipsoid with radii `radii` (the sphere for
/// (1,1,1)): steps of 0.3 x the spring displacement, radial projection back
/// onto the surface (displacements made tangential first), intrinsic Delaunay
/// flips after each of the first 20 steps and then every 10; a step that
/// would invert a face (exact orientation about the origin) is halved.
inline void relax_on_ellipsoid(Matrix& X, Index_matrix& F, const Eigen::Vector3d& radii, int iterations)
{
  std::vector<std::array<int, 2> > edges = mesh_edges(F);
  for(int it = 0; it < iterations; ++it) {
    Matrix D = equal_length_springs(X, edges);
    remove_normal_components(X, radii, D);
    double dt = 0.3;
    for(int attempt = 0; attempt < 8; ++attempt) {
      Matrix Y = X + dt * D;
      project_radially(Y, radii);
      if(count_inverted_faces_about_center(Y, F) == 0) { X.swap(Y); break; }
      dt *= 0.5;
    }
    if(it < 20 || (it + 1) % 10 == 0 || it + 1 == iterations) {
      delaunay_flips(X, F);
      edges = mesh_edges(F);
    }
  }
}

/// DistMesh's force (Persson and Strang 2004): every edge shorter than
/// `scale` x the mean edge length pushes its endpoints apart in proportion to
/// the shortfall; longer edges exert no force. With scale > 1 every edge is
/// compressed, the points spread like a gas under uniform pressure, and the
/// closed surface confines them: the equilibrium has equal edge lengths
/// wherever the connectivity allows. Measured against the two-sided springs
/// above (which also pull): shapes and sizes both better on ellipsoids.
inline Matrix repulsive_springs(const Matrix& X, const std::vector<std::array<int, 2> >& edges, double scale)
{
  double sum = 0;
  for(const auto& e : edges) sum += (X.row(e[0]) - X.row(e[1])).norm();
  const double target = scale * sum / double(edges.size());
  Matrix D = Matrix::Zero(X.rows(), 3);
  for(const auto& e : edges) {
    const Eigen::RowVector3d d = X.row(e[0]) - X.row(e[1]);
    const double l = d.norm();
    if(!(l > 0) || l >= target) continue;
    const Eigen::RowVector3d f = (target - l) / l * d;
    D.row(e[0]) += f;
    D.row(e[1]) -= f;
  }
  return D;
}

/// DistMesh relaxation on the ellipsoid: `iterations` steps of 0.2 x the
/// repulsive-spring displacement (made tangential), radial projection back
/// onto the surface, intrinsic Delaunay flips after each of the first
/// `early_flips` steps and then every `flip_every`. A step that would invert
/// faces (exact orientation about the origin) is retried with the vertices of
/// those faces held still: halving the whole step instead stalls for good
/// as soon as one face is nearly degenerate about the origin (measured: the
/// linear map of a 280-vertex geodesic sphere onto the 1:1:5 ellipsoid stuck
/// at delta_shape 0.20 after 1,000 steps; held still locally, 0.048).
inline void distmesh_relax_on_ellipsoid(Matrix& X, Index_matrix& F, const Eigen::Vector3d& radii, int iterations,
                                        double scale, int early_flips, int flip_every)
{
  std::vector<std::array<int, 2> > edges = mesh_edges(F);
  for(int it = 0; it < iterations; ++it) {
    Matrix D = repulsive_springs(X, edges, scale);
    remove_normal_components(X, radii, D);
    for(int attempt = 0; attempt < 8; ++attempt) {
      Matrix Y = X + 0.2 * D;
      project_radially(Y, radii);
      const std::vector<Eigen::Index> inverted = inverted_faces_about_center(Y, F);
      if(inverted.empty()) { X.swap(Y); break; }
      for(Eigen::Index k : inverted)
        for(int c = 0; c < 3; ++c) D.row(F(k, c)).setZero();
    }
    if(it < early_flips || (it + 1) % flip_every == 0 || it + 1 == iterations) {
      delaunay_flips(X, F);
      edges = mesh_edges(F);
    }
  }
}

/// The split of every face of a closed mesh (n vertices) into k^2 faces by its
/// barycentric grid: k - 1 new points on each edge (shared by its two faces)
/// and (k - 1)(k - 2) / 2 inside each face, n' = k^2 (n - 2) + 2 in all (genus
/// 0; n' = k^2 n on the torus). New vertex n + q is the combination
/// `weights[q]` of the old vertices `corners[q]`; faces keep their orientation.
struct Face_subdivision
{
  Index_matrix F;
  std::vector<std::array<int, 3> > corners;
  std::vector<Eigen::Vector3d> weights;
};

inline Face_subdivision subdivide_faces(const Index_matrix& F, Eigen::Index n, int k)
{
  const Eigen::Index m = F.rows();
  Face_subdivision s;
  s.F.resize(m * k * k, 3);
  std::unordered_map<long long, int> first_edge_point; // edge (lo, hi) -> its point 1 step from lo
  Eigen::Index f = 0;
  std::vector<int> grid(static_cast<std::size_t>((k + 1) * (k + 1)));
  auto add = [&](int a, int b, int c, const Eigen::Vector3d& w) {
    s.corners.push_back({{a, b, c}});
    s.weights.push_back(w);
    return int(n + Eigen::Index(s.corners.size()) - 1);
  };
  for(Eigen::Index face = 0; face < m; ++face) {
    const int v[3] = {F(face, 0), F(face, 1), F(face, 2)};
    auto at = [&grid, k](int i, int j) -> int& { return grid[i * (k + 1) + j]; };
    // the point of edge (p, q) of this face s steps from p, 1 <= s < k
    auto edge_point = [&](int p, int q, int steps) {
      const int lo = std::min(p, q), hi = std::max(p, q);
      const long long key = (long long)lo * n + hi;
      auto it = first_edge_point.find(key);
      if(it == first_edge_point.end()) {
        it = first_edge_point.emplace(key, int(n + Eigen::Index(s.corners.size()))).first;
        for(int r = 1; r < k; ++r) add(lo, hi, hi, Eigen::Vector3d(double(k - r) / k, double(r) / k, 0.));
      }
      return it->second + (p == lo ? steps : k - steps) - 1;
    };
    for(int i = 0; i <= k; ++i)
      for(int j = 0; i + j <= k; ++j) {
        const int w0 = k - i - j;
        if(w0 == k) at(i, j) = v[0];
        else if(i == k) at(i, j) = v[1];
        else if(j == k) at(i, j) = v[2];
        else if(j == 0) at(i, j) = edge_point(v[0], v[1], i);
        else if(i == 0) at(i, j) = edge_point(v[0], v[2], j);
        else if(w0 == 0) at(i, j) = edge_point(v[1], v[2], j);
        else at(i, j) = add(v[0], v[1], v[2], Eigen::Vector3d(double(w0) / k, double(i) / k, double(j) / k));
      }
    for(int i = 0; i < k; ++i)
      for(int j = 0; i + j < k; ++j) {
        s.F.row(f++) << at(i, j), at(i + 1, j), at(i, j + 1);
        if(i + j + 1 < k) s.F.row(f++) << at(i + 1, j), at(i + 1, j + 1), at(i, j + 1);
      }
  }
  return s;
}

/// subdivide_faces() on the ellipsoid: the new points interpolated linearly
/// and projected radially. Each small face keeps the shape and 1/k^2 of the
/// area of its parent, and since scaling a point along its ray does not change
/// the sign of an orientation about the origin, faces positively oriented
/// about the origin stay so.
inline Triangle_arrays subdivide_onto_ellipsoid(const Triangle_arrays& c, int k, const Eigen::Vector3d& radii)
{
  const Face_subdivision s = subdivide_faces(c.F, c.X.rows(), k);
  Triangle_arrays t;
  t.F = s.F;
  Matrix fresh(Eigen::Index(s.corners.size()), 3);
  for(std::size_t q = 0; q < s.corners.size(); ++q)
    fresh.row(q) = s.weights[q](0) * c.X.row(s.corners[q][0]) + s.weights[q](1) * c.X.row(s.corners[q][1]) +
                   s.weights[q](2) * c.X.row(s.corners[q][2]);
  project_radially(fresh, radii);
  t.X.resize(c.X.rows() + fresh.rows(), 3);
  t.X << c.X, fresh;
  return t;
}

/// The subdivision factors k_1, ..., k_L (each at most 6, as few as possible)
/// whose product k puts k^2 (V_c - 2) + 2 within 1 % of n for a coarse mesh of
/// V_c vertices near `coarse_target`: the coarse mesh is relaxed for long (its
/// global size balance is cheap there) and each subdivision level only needs a
/// few local steps, as its defects are those of the coarse mesh.
inline std::vector<int> subdivision_factors(Eigen::Index n, double coarse_target)
{
  const double ideal = std::sqrt(double(n - 2) / coarse_target);
  std::vector<int> best;
  double best_score = std::numeric_limits<double>::infinity();
  for(int k = 1; double(k) <= 2. * ideal + 1.; ++k) {
    // k^2 / 2 is the largest rounding error of the vertex count
    if(k > 1 && 0.5 * double(k) * double(k) > 0.01 * double(n)) break;
    if(double(n - 2) / double(k * k) < 12.) break;
    std::vector<int> factors;
    int rest = k;
    for(int p = 6; p >= 2; --p)
      while(rest % p == 0) { factors.push_back(p); rest /= p; }
    if(rest != 1) continue;
    // closeness of the coarse size to its target first, then fewer levels
    const double score = std::abs(std::log(double(k) / ideal)) + 0.15 * double(factors.size());
    if(score < best_score) { best_score = score; best = factors; }
  }
  return best;
}

/// Coarse-to-fine DistMesh mesh of the ellipsoid with about n vertices (see
/// the file comment).
inline Triangle_arrays multilevel_ellipsoid_mesh(Eigen::Index n, const Eigen::Vector3d& radii)
{
  const std::vector<int> factors = subdivision_factors(n, 300.);
  Eigen::Index k = 1;
  for(int p : factors) k *= p;
  const Eigen::Index coarse = Eigen::Index(std::llround(double(n - 2) / double(k * k))) + 2;
  int f = std::max(1, static_cast<int>(std::floor(std::sqrt((double(coarse) - 2.) / 10.))));
  Triangle_arrays t = geodesic_sphere(f);
  insert_spread_vertices(t, coarse - t.X.rows());
  delaunay_flips(t.X, t.F);
  t.X = t.X * radii.asDiagonal(); // linear: every face stays positively oriented about the origin
  distmesh_relax_on_ellipsoid(t.X, t.F, radii, 1000, 1.1, 20, 10);
  for(int p : factors) {
    t = subdivide_onto_ellipsoid(t, p, radii);
    delaunay_flips(t.X, t.F);
    distmesh_relax_on_ellipsoid(t.X, t.F, radii, 80, 1.2, 0, 10);
  }
  return t;
}

inline void check_vertex_count(Eigen::Index n, Eigen::Index minimum)
{
  if(n < minimum)
    throw Invalid_input("a domain mesh needs at least " + std::to_string(minimum) + " vertices (requested " +
                        std::to_string(n) + ")");
}

/// Near-uniform mesh of the ellipsoid with radii (a, b, c) (the unit sphere
/// for (1,1,1)) with n vertices within 1 %, faces oriented outward: the
/// geodesic sphere when its 10 f^2 + 2 vertices are within 1 % of n on the
/// unit sphere (f <= 100, measured up to there: delta_size 0.669 at f = 100,
/// growing slowly with f), the coarse-to-fine DistMesh mesh otherwise.
inline Triangle_arrays uniform_ellipsoid_mesh(Eigen::Index n, const Eigen::Vector3d& radii)
{
  check_vertex_count(n, 12);
  if(radii == Eigen::Vector3d::Ones()) {
    const int f = static_cast<int>(std::lround(std::sqrt((double(n) - 2.) / 10.)));
    const double geodesic = 10. * f * f + 2.;
    if(f >= 1 && f <= 100 && std::abs(geodesic - double(n)) <= 0.01 * double(n)) {
      Triangle_arrays t = geodesic_sphere(f);
      relax_on_ellipsoid(t.X, t.F, radii, 60); // measured: delta_size and delta_shape stop improving there
      return t;
    }
  }
  return multilevel_ellipsoid_mesh(n, radii);
}

/// The exponent beta of the row spacing (see the file comment).
inline double torus_row_exponent(double R, double r, double delta_size_target)
{
  const double spread = std::log((R + r) / (R - r));
  return std::max(-1., std::min(1., delta_size_target / spread - 1.));
}

/// Angles theta_j of the nv rows, j = 0..nv-1, with d(theta) proportional to
/// (R + r cos theta)^beta (equal steps of the integral of w^-beta), theta_0 = -pi (the inner equator, where the flat
/// torus of the package has its seam), integrated numerically.
inline std::vector<double> torus_row_angles(int nv, double R, double r, double beta)
{
  const int samples = 64 * nv;
  std::vector<double> cumulative(samples + 1, 0.);
  for(int s = 0; s < samples; ++s) {
    const double theta = -M_PI + (s + 0.5) * 2 * M_PI / samples;
    cumulative[s + 1] = cumulative[s] + std::pow(R + r * std::cos(theta), -beta);
  }
  std::vector<double> rows(nv);
  int s = 0;
  for(int j = 0; j < nv; ++j) {
    const double target = cumulative[samples] * j / nv;
    while(s < samples && cumulative[s + 1] < target) ++s;
    const double f = (target - cumulative[s]) / (cumulative[s + 1] - cumulative[s]);
    rows[j] = -M_PI + (s + (j == 0 ? 0. : f)) * 2 * M_PI / samples;
  }
  return rows;
}

/// Triangular lattice of nu x nv vertices (nv even) on the torus (R, r),
/// every vertex of valence 6, faces oriented outward.
inline Triangle_arrays torus_lattice(int nu, int nv, double R, double r, double delta_size_target)
{
  const std::vector<double> theta = torus_row_angles(nv, R, r, torus_row_exponent(R, r, delta_size_target));
  Triangle_arrays t;
  t.X.resize(Eigen::Index(nu) * nv, 3);
  auto id = [nu, nv](int i, int j) {
    // row nv is row 0 shifted by nv / 2 columns (the half-column shifts add up)
    const int wraps = (j >= nv) ? 1 : 0;
    j -= wraps * nv;
    i += wraps * (nv / 2);
    return ((i % nu) + nu) % nu + nu * j;
  };
  for(int j = 0; j < nv; ++j)
    for(int i = 0; i < nu; ++i) {
      const double phi = 2 * M_PI * (i + 0.5 * j) / nu;
      t.X.row(id(i, j)) = torus_point(R * phi, r * theta[j], R, r).transpose();
    }
  t.F.resize(2 * Eigen::Index(nu) * nv, 3);
  Eigen::Index k = 0;
  for(int j = 0; j < nv; ++j)
    for(int i = 0; i < nu; ++i) {
      // up triangle (i,j) (i+1,j) (i,j+1); down triangle (i+1,j) (i+1,j+1) (i,j+1)
      // (row j+1 is shifted right by half a column, so (i,j+1) sits above the middle of (i,j)-(i+1,j))
      t.F.row(k++) << id(i, j), id(i + 1, j), id(i, j + 1);
      t.F.row(k++) << id(i + 1, j), id(i + 1, j + 1), id(i, j + 1);
    }
  // u grows with the longitude and v with theta: (u, v) counter-clockwise is outward on the torus
  return t;
}

/// The lattice with about n vertices: among the sizes nu x nv (nv even) within
/// 1 % of n (the nearest to n if none is), the one with the lowest delta_shape
/// (each candidate is built and measured: a few milliseconds).
inline Triangle_arrays uniform_torus_mesh(Eigen::Index n, double R, double r, double delta_size_target = 0.69)
{
  check_vertex_count(n, 16);
  std::vector<std::array<int, 2> > candidates;
  double nearest = std::numeric_limits<double>::infinity();
  std::array<int, 2> nearest_size{{0, 0}};
  for(int nv = 4; nv * 3 <= n; nv += 2)
    for(int nu = std::max(3, int(n / nv) - 1); nu <= int(n / nv) + 1; ++nu) {
      const double error = std::abs(double(nu) * nv - double(n)) / double(n);
      if(error <= 0.01) candidates.push_back({{nu, nv}});
      if(error < nearest) { nearest = error; nearest_size = {{nu, nv}}; }
    }
  if(candidates.empty()) candidates.push_back(nearest_size);
  // equilateral on average: nu / nv near sqrt(3)/2 R / r; keep the plausible ones
  const double ideal = std::sqrt(3.) / 2 * R / r;
  std::sort(candidates.begin(), candidates.end(), [ideal](const std::array<int, 2>& a, const std::array<int, 2>& b) {
    return std::abs(std::log(double(a[0]) / a[1] / ideal)) < std::abs(std::log(double(b[0]) / b[1] / ideal));
  });
  if(candidates.size() > 8) candidates.resize(8);
  Triangle_arrays best;
  double best_shape = std::numeric_limits<double>::infinity();
  for(const auto& c : candidates) {
    // the row exponent comes from the continuous torus; coarse lattices (few
    // rows) can exceed the size target by the discretization: tighten it
    double target = delta_size_target;
    Triangle_arrays t = torus_lattice(c[0], c[1], R, r, target);
    for(int retry = 0; retry < 6 && mesh_uniformity(t.X, t.F).delta_size > delta_size_target; ++retry) {
      target *= 0.9;
      t = torus_lattice(c[0], c[1], R, r, target);
    }
    const double shape = mesh_uniformity(t.X, t.F).delta_shape;
    if(shape < best_shape) { best_shape = shape; best = std::move(t); }
  }
  return best;
}

/// d reduced to (-period / 2, period / 2]: the difference of two flat-torus
/// coordinates along the shorter way round.
inline double wrapped_difference(double d, double period) { return d - period * std::round(d / period); }

/// Face (i, j, k) positively oriented in the flat torus (exact), its corners
/// j and k unwrapped next to i: counter-clockwise in (u, v) is outward.
struct Positive_on_flat_torus
{
  const Matrix& U;
  double period_u, period_v;
  Epick::Point_2 unwrapped(int v, int origin) const
  {
    return Epick::Point_2(U(origin, 0) + wrapped_difference(U(v, 0) - U(origin, 0), period_u),
                          U(origin, 1) + wrapped_difference(U(v, 1) - U(origin, 1), period_v));
  }
  bool operator()(int i, int j, int k) const
  {
    return CGAL::orientation(Epick::Point_2(U(i, 0), U(i, 1)), unwrapped(j, i), unwrapped(k, i)) == CGAL::POSITIVE;
  }
};

inline Matrix torus_points(const Matrix& U, double R, double r)
{
  Matrix X(U.rows(), 3);
  for(Eigen::Index i = 0; i < U.rows(); ++i) X.row(i) = torus_point(U(i, 0), U(i, 1), R, r).transpose();
  return X;
}

/// DistMesh on the torus (R, r), in its flat-torus coordinates (u, v): the
/// repulsive springs act on the points of the torus (3D chords), their
/// tangential part moves (u, v) by the inverse of the parameterization's
/// Jacobian (|d/du| = w / R with w = R + r cos(v / r), |d/dv| = 1, orthogonal),
/// so every vertex stays exactly on the torus; a step that would invert faces
/// of the flat torus (exact) is retried with their vertices held still;
/// intrinsic Delaunay flips (3D angles) every `flip_every` steps.
inline void distmesh_relax_on_torus(Matrix& U, Index_matrix& F, double R, double r, int iterations, double scale,
                                    int flip_every)
{
  const double period_u = 2 * M_PI * R, period_v = 2 * M_PI * r;
  std::vector<std::array<int, 2> > edges = mesh_edges(F);
  for(int it = 0; it < iterations; ++it) {
    const Matrix X = torus_points(U, R, r);
    const Matrix D = repulsive_springs(X, edges, scale);
    Matrix dU(U.rows(), 2);
    for(Eigen::Index i = 0; i < U.rows(); ++i) {
      const double phi = U(i, 0) / R, theta = U(i, 1) / r, w = R + r * std::cos(theta);
      const Eigen::Vector3d eu(-std::sin(phi), std::cos(phi), 0);
      const Eigen::Vector3d ev(-std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), std::cos(theta));
      const Eigen::Vector3d d = row_vector3(D, i);
      dU.row(i) << R * d.dot(eu) / w, d.dot(ev);
    }
    for(int attempt = 0; attempt < 8; ++attempt) {
      Matrix V = U + 0.2 * dU;
      for(Eigen::Index i = 0; i < V.rows(); ++i) {
        V(i, 0) -= period_u * std::floor(V(i, 0) / period_u);
        V(i, 1) -= period_v * std::floor(V(i, 1) / period_v);
      }
      const Positive_on_flat_torus positive{V, period_u, period_v};
      std::vector<Eigen::Index> inverted;
      for(Eigen::Index k = 0; k < F.rows(); ++k)
        if(!positive(F(k, 0), F(k, 1), F(k, 2))) inverted.push_back(k);
      if(inverted.empty()) { U.swap(V); break; }
      for(Eigen::Index k : inverted)
        for(int c = 0; c < 3; ++c) dU.row(F(k, c)).setZero();
    }
    if((it + 1) % flip_every == 0 || it + 1 == iterations) {
      const Matrix Y = torus_points(U, R, r);
      const Positive_on_flat_torus positive{U, period_u, period_v};
      for(int pass = 0; pass < 20 && delaunay_flip_pass(Y, F, positive) > 0; ++pass) {}
      edges = mesh_edges(F);
    }
  }
}

/// subdivide_faces() in the flat torus: new points interpolated between the
/// corners unwrapped next to the first one, wrapped back into the periods.
inline Matrix subdivide_on_flat_torus(const Matrix& U, Index_matrix& F, int k, double period_u, double period_v)
{
  Face_subdivision s = subdivide_faces(F, U.rows(), k);
  Matrix V(U.rows() + Eigen::Index(s.corners.size()), 2);
  V.topRows(U.rows()) = U;
  for(std::size_t q = 0; q < s.corners.size(); ++q) {
    const int a = s.corners[q][0];
    double u = U(a, 0), v = U(a, 1);
    for(int c = 1; c < 3; ++c) {
      u += s.weights[q](c) * wrapped_difference(U(s.corners[q][c], 0) - U(a, 0), period_u);
      v += s.weights[q](c) * wrapped_difference(U(s.corners[q][c], 1) - U(a, 1), period_v);
    }
    V.row(U.rows() + Eigen::Index(q)) << u - period_u * std::floor(u / period_u), v - period_v * std::floor(v / period_v);
  }
  F.swap(s.F);
  return V;
}

/// The relaxed torus mesh with about n vertices (within 1 %): the lattice of
/// uniform_torus_mesh() with about n / k^2 vertices (k a product of factors at
/// most 6, n / k^2 near 300, k^2 x the lattice's size within 1 % of n), 2,000
/// DistMesh steps on it (1.1 x the mean edge length), then each subdivision
/// level with 80 steps (1.2 x), as on the ellipsoid. The flips give up valence
/// 6 for regular shapes at uniform sizes (see the file comment).
inline Triangle_arrays relaxed_torus_mesh(Eigen::Index n, double R, double r, double start_size_target = 0.5)
{
  check_vertex_count(n, 16);
  const double period_u = 2 * M_PI * R, period_v = 2 * M_PI * r;
  const double ideal = std::sqrt(double(n) / 300.);
  std::vector<std::pair<double, std::vector<int> > > candidates; // (score, factors)
  for(int k = 1; double(k) <= 2. * ideal + 1.; ++k) {
    if(double(n) / double(k * k) < 16.) break;
    std::vector<int> f;
    int rest = k;
    for(int p = 6; p >= 2; --p)
      while(rest % p == 0) { f.push_back(p); rest /= p; }
    if(rest == 1) candidates.emplace_back(std::abs(std::log(double(k) / ideal)) + 0.15 * double(f.size()), f);
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<int> factors;
  Triangle_arrays lattice;
  for(const auto& c : candidates) {
    Eigen::Index k = 1;
    for(int p : c.second) k *= p;
    lattice = uniform_torus_mesh(Eigen::Index(std::llround(double(n) / double(k * k))), R, r, start_size_target);
    factors = c.second;
    if(std::abs(double(lattice.X.rows() * k * k) - double(n)) <= 0.01 * double(n)) break;
  }
  Matrix U(lattice.X.rows(), 2);
  for(Eigen::Index i = 0; i < U.rows(); ++i) {
    const Eigen::Vector2d c = torus_coordinates(row_vector3(lattice.X, i), R, r);
    U.row(i) << c(0), c(1);
  }
  Triangle_arrays t;
  t.F = lattice.F;
  distmesh_relax_on_torus(U, t.F, R, r, 2000, 1.1, 10);
  for(int p : factors) {
    U = subdivide_on_flat_torus(U, t.F, p, period_u, period_v);
    distmesh_relax_on_torus(U, t.F, R, r, 80, 1.2, 10);
  }
  t.X = torus_points(U, R, r);
  return t;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H
