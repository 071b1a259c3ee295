// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H

// Near-uniform triangulations of the domains with a prescribed number of
// vertices (ALGORITHMS.md section 11, "Remeshing"), on index arrays.
//
// Sphere and ellipsoid: N points of the spherical Fibonacci lattice (N
// exactly), triangulated by their convex hull (exact, CGAL::convex_hull_3: the
// hull of points on a sphere is their spherical Delaunay triangulation), mapped
// to the ellipsoid by the linear map diag(a, b, c) (the hull is affinely
// invariant, so the triangulation stays valid), then relaxed as in DistMesh
// (Persson-Strang 2004): edges shorter than 1.2 x their r.m.s. length push
// their endpoints apart, the points are projected back onto the surface, and
// edges are flipped to the intrinsic Delaunay criterion (opposite angles sum
// below pi). A step that would invert a face (exact orientation about the
// origin) is halved. The Fibonacci lattice alone is uniform away from its two
// poles; the relaxation removes the polar defects and, on the ellipsoid, the
// area distortion of the linear map.
//
// Torus: a triangular lattice of nu x nv vertices on the flat torus, each row
// shifted by half a column (nv even, so the shift closes up), every vertex of
// valence 6. The rows are spaced so that d(theta) is proportional to
// w(theta)^beta, w = R + r cos(theta) the radius of the parallel: beta = 1
// gives equilateral (conformal) triangles whose areas vary as w^2, beta = -1
// equal areas with aspect ratios varying as w^2; beta is the largest value
// that keeps delta_size = (1 + beta) ln(w_max / w_min) within the target,
// i.e. the best shapes at the required size uniformity.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
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

/// The convex hull of points in convex position (all of them are hull
/// vertices), faces oriented outward, rows of X kept.
inline Index_matrix convex_hull_faces(const Matrix& P)
{
  typedef Epick::Point_3 Point;
  std::vector<Point> pts;
  pts.reserve(static_cast<std::size_t>(P.rows()));
  for(Eigen::Index i = 0; i < P.rows(); ++i) pts.emplace_back(P(i, 0), P(i, 1), P(i, 2));
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
  if(Eigen::Index(hull.number_of_vertices()) != P.rows())
    throw Invalid_input("internal error: a domain point is not a vertex of the convex hull");
  // hull vertices -> input rows (the hull copies the points exactly)
  std::map<Point, int> row;
  for(Eigen::Index i = 0; i < P.rows(); ++i) row.emplace(pts[i], int(i));
  std::vector<int> index(hull.number_of_vertices(), -1);
  for(auto v : hull.vertices()) index[v.idx()] = row.at(hull.point(v));
  Index_matrix F(hull.number_of_faces(), 3);
  Eigen::Index k = 0;
  for(auto f : hull.faces()) {
    int c = 0;
    for(auto v : vertices_around_face(hull.halfedge(f), hull)) F(k, c++) = index[v.idx()];
    ++k;
  }
  return F;
}

/// The closest-in-direction point of the ellipsoid (radial projection).
inline void project_radially(Matrix& X, const Eigen::Vector3d& radii) { project_to_ellipsoid(X, radii); }

inline double corner_angle(const Eigen::Vector3d& apex, const Eigen::Vector3d& p, const Eigen::Vector3d& q)
{
  const Eigen::Vector3d a = p - apex, b = q - apex;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// One pass of intrinsic-Delaunay edge flips on a closed mesh star-shaped
/// about the origin: an edge whose opposite angles sum above pi is flipped
/// unless the new edge exists already or a new face would not be positively
/// oriented about the origin (exact). Each face takes part in at most one flip
/// per pass. Returns the number of flips.
inline std::size_t delaunay_flip_pass(const Matrix& X, Index_matrix& F)
{
  const Eigen::Index n = X.rows(), m = F.rows();
  auto key = [n](long long i, long long j) { return i * n + j; };
  std::unordered_map<long long, int> directed; // directed edge -> halfedge 3k + c (from corner c to c+1)
  directed.reserve(static_cast<std::size_t>(3 * m));
  std::unordered_set<long long> undirected;
  undirected.reserve(static_cast<std::size_t>(3 * m));
  for(Eigen::Index k = 0; k < m; ++k)
    for(int c = 0; c < 3; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3);
      directed[key(i, j)] = int(3 * k + c);
      undirected.insert(key(std::min(i, j), std::max(i, j)));
    }
  std::vector<char> touched(static_cast<std::size_t>(m), 0);
  const Epick::Point_3 origin(0, 0, 0);
  auto point = [&X](int i) { return Epick::Point_3(X(i, 0), X(i, 1), X(i, 2)); };
  std::size_t flips = 0;
  for(Eigen::Index k = 0; k < m; ++k)
    for(int c = 0; c < 3 && !touched[k]; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3), a = F(k, (c + 2) % 3);
      if(i > j) continue; // each edge once
      const auto it = directed.find(key(j, i));
      if(it == directed.end()) continue;
      const int g = it->second / 3, e = it->second % 3;
      if(touched[g]) continue;
      const int b = F(g, (e + 2) % 3);
      const double opposite = corner_angle(row_vector3(X, a), row_vector3(X, i), row_vector3(X, j)) +
                              corner_angle(row_vector3(X, b), row_vector3(X, j), row_vector3(X, i));
      if(opposite <= M_PI + 1e-12) continue;
      if(a == b || undirected.count(key(std::min(a, b), std::max(a, b)))) continue;
      // (i, j, a) and (j, i, b) become (i, b, a) and (j, a, b)
      if(CGAL::orientation(origin, point(i), point(b), point(a)) != CGAL::POSITIVE ||
         CGAL::orientation(origin, point(j), point(a), point(b)) != CGAL::POSITIVE)
        continue;
      F.row(k) << i, b, a;
      F.row(g) << j, a, b;
      undirected.erase(key(std::min(i, j), std::max(i, j)));
      undirected.insert(key(std::min(a, b), std::max(a, b)));
      touched[k] = touched[g] = 1;
      ++flips;
    }
  return flips;
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

/// The DistMesh displacement: every edge shorter than 1.2 x the r.m.s. edge
/// length pushes its endpoints apart in proportion to the shortfall.
inline Matrix distmesh_forces(const Matrix& X, const std::vector<std::array<int, 2> >& edges)
{
  double sum_sq = 0;
  for(const auto& e : edges) sum_sq += (X.row(e[0]) - X.row(e[1])).squaredNorm();
  const double target = 1.2 * std::sqrt(sum_sq / double(edges.size()));
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

/// DistMesh relaxation on the ellipsoid with radii `radii` (the sphere for
/// (1,1,1)), keeping every face positively oriented about the origin.
inline void relax_on_ellipsoid(Matrix& X, Index_matrix& F, const Eigen::Vector3d& radii, int iterations)
{
  double dt = 0.2;
  for(int it = 0; it < iterations; ++it) {
    const Matrix D = distmesh_forces(X, mesh_edges(F));
    for(int attempt = 0; attempt < 8; ++attempt) {
      Matrix Y = X + dt * D;
      project_radially(Y, radii);
      if(count_inverted_faces_about_center(Y, F) == 0) { X.swap(Y); break; }
      dt *= 0.5;
    }
    delaunay_flips(X, F);
  }
}

/// Number of relaxation steps: enough for the polar defects of the lattice
/// and the linear map's distortion to even out (measured: the quality stops
/// improving after about this many on the sphere and on a 3:2:1 ellipsoid).
inline int relaxation_iterations(const Eigen::Vector3d& radii)
{
  const double anisotropy = radii.maxCoeff() / radii.minCoeff();
  return static_cast<int>(std::min(200., 20. + 30. * std::log2(anisotropy)));
}

inline void check_vertex_count(Eigen::Index n, Eigen::Index minimum)
{
  if(n < minimum)
    throw Invalid_input("a domain mesh needs at least " + std::to_string(minimum) + " vertices (requested " +
                        std::to_string(n) + ")");
}

/// Near-uniform mesh of the ellipsoid with radii (a, b, c) (the unit sphere
/// for (1,1,1)) with exactly n vertices, faces oriented outward.
inline Triangle_arrays uniform_ellipsoid_mesh(Eigen::Index n, const Eigen::Vector3d& radii)
{
  check_vertex_count(n, 12);
  Triangle_arrays t;
  const Matrix S = fibonacci_sphere_points(n);
  t.F = convex_hull_faces(S);
  t.X = S * radii.asDiagonal();
  relax_on_ellipsoid(t.X, t.F, radii, relaxation_iterations(radii));
  return t;
}

/// Rows (nv) and columns (nu) of the torus lattice: nv even, nu x nv within
/// 1 % of n when possible, columns and rows in the ratio of equilateral
/// triangles on the torus (nu / nv = sqrt(3)/2 R / r), best compromise otherwise.
inline std::array<int, 2> torus_lattice_size(Eigen::Index n, double R, double r)
{
  const double ideal_rows = std::sqrt(double(n) * 2. * r / (std::sqrt(3.) * R));
  std::array<int, 2> best{{0, 0}};
  double best_cost = std::numeric_limits<double>::infinity();
  for(int nv = 4; nv <= std::max(4, int(3 * ideal_rows) + 4); nv += 2) {
    const int nu = std::max(3, int(std::lround(double(n) / nv)));
    const double count_error = std::abs(double(nu) * nv - double(n)) / double(n);
    const double aspect_error = std::abs(std::log(nv / ideal_rows));
    const double cost = (count_error <= 0.01 ? 0. : 100. * count_error) + aspect_error;
    if(cost < best_cost) { best_cost = cost; best = {{nu, nv}}; }
  }
  return best;
}

/// The exponent beta of the row spacing (see the file comment).
inline double torus_row_exponent(double R, double r, double delta_size_target)
{
  const double spread = std::log((R + r) / (R - r));
  return std::max(-1., std::min(1., delta_size_target / spread - 1.));
}

/// Angles theta_j of the nv rows, j = 0..nv-1, with d(theta) proportional to
/// (R + r cos theta)^beta, theta_0 = -pi (the inner equator, where the flat
/// torus of the package has its seam), integrated numerically.
inline std::vector<double> torus_row_angles(int nv, double R, double r, double beta)
{
  const int samples = 64 * nv;
  std::vector<double> cumulative(samples + 1, 0.);
  for(int s = 0; s < samples; ++s) {
    const double theta = -M_PI + (s + 0.5) * 2 * M_PI / samples;
    cumulative[s + 1] = cumulative[s] + std::pow(R + r * std::cos(theta), beta);
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

/// Triangular lattice on the torus (R, r) with about n vertices (see
/// torus_lattice_size()), every vertex of valence 6, faces oriented outward.
inline Triangle_arrays uniform_torus_mesh(Eigen::Index n, double R, double r, double delta_size_target = 0.69)
{
  check_vertex_count(n, 16);
  const std::array<int, 2> size = torus_lattice_size(n, R, r);
  const int nu = size[0], nv = size[1];
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

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_UNIFORM_DOMAIN_MESH_H
