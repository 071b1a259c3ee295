// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_POINT_LOCATION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_POINT_LOCATION_H

// Point location in the image of a fold-free map, on index arrays
// (ALGORITHMS.md section 11, "Remeshing"): which image face contains a query
// point, and its barycentric coordinates there.
//
// * Planar_point_locator: a planar triangulation of a convex domain (the FECM
//   chart).
// * Spherical_point_locator: a closed mesh star-shaped about the origin (a map
//   onto the unit sphere or an ellipsoid). Face (i,j,k) contains the ray
//   through q when q lies on the inner side of the three planes through the
//   origin and an edge: orientation(0, f_j, f_k, q) etc., exact predicates.
//   These tests are invariant under any linear map of positive determinant,
//   so an ellipsoid needs no rescaling to the sphere.
// * Flat_torus_point_locator (flat_torus_point_location.h): the layout of a
//   map onto the flat torus, walked in the universal cover.
//
// All walk from a start face towards the query, crossing an edge whose
// line (plane) separates the face from the query, choosing among such edges
// at random (the randomized visibility walk terminates on any triangulation).
// Starts come from the caller (the previous answer of a coherent batch) or
// from a bucket grid of the domain filled once by walking. Containment is
// decided by exact predicates on the very doubles stored, and shared edges are
// tested with the same points in both faces, so a query on an edge or a vertex
// is found in one of the incident faces and never falls in a crack; the
// barycentric coordinates are computed afterwards and clamped to [0, 1].

#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Face adjacency across edges (see face_neighbors()); int, as the faces' own
/// indices (Index_matrix), which halves what a walk keeps per face.
using Face_neighbor_matrix = Eigen::Matrix<int, Eigen::Dynamic, 3>;

// ---------------------------------------------------------------------------
// Mesh traversal and planar point location
// ---------------------------------------------------------------------------

/// Vertex-to-face incidence in compressed rows.
struct Vertex_faces
{
  std::vector<Eigen::Index> start, faces;
  Vertex_faces() = default;
  Vertex_faces(const Index_matrix& F, Eigen::Index n) : start(static_cast<std::size_t>(n) + 1, 0)
  {
    for(Eigen::Index k = 0; k < F.rows(); ++k)
      for(int c = 0; c < 3; ++c) ++start[F(k, c) + 1];
    for(Eigen::Index i = 0; i < n; ++i) start[i + 1] += start[i];
    faces.resize(static_cast<std::size_t>(3 * F.rows()));
    std::vector<Eigen::Index> fill(start.begin(), start.end() - 1);
    for(Eigen::Index k = 0; k < F.rows(); ++k)
      for(int c = 0; c < 3; ++c) faces[fill[F(k, c)]++] = k;
  }
  Eigen::Index begin(Eigen::Index i) const { return start[i]; }
  Eigen::Index end(Eigen::Index i) const { return start[i + 1]; }
};

/// Breadth-first order of the vertices along mesh edges and each vertex's
/// parent (-1 for the root): consecutive queries of a continuous per-vertex
/// field start their point location next to the parent's answer.
inline void breadth_first_vertex_order(const Index_matrix& F, Eigen::Index n, std::vector<Eigen::Index>& order,
                                       std::vector<Eigen::Index>& parent)
{
  const Vertex_faces vf(F, n);
  order.clear();
  order.reserve(static_cast<std::size_t>(n));
  parent.assign(static_cast<std::size_t>(n), -2);
  for(Eigen::Index root = 0; root < n; ++root) {
    if(parent[root] != -2) continue;
    parent[root] = -1;
    std::size_t head = order.size();
    order.push_back(root);
    while(head < order.size()) {
      const Eigen::Index i = order[head++];
      for(Eigen::Index s = vf.begin(i); s < vf.end(i); ++s)
        for(int c = 0; c < 3; ++c) {
          const Eigen::Index j = F(vf.faces[s], c);
          if(parent[j] == -2) { parent[j] = i; order.push_back(j); }
        }
    }
  }
}

/// Neighbouring faces: row k, column a is the face across the edge opposite
/// corner a of face k (the face holding the directed edge F(k,a+2) -> F(k,a+1)),
/// -1 on a boundary edge.
inline Face_neighbor_matrix face_neighbors(const Index_matrix& F, const Vertex_faces& vf)
{
  Face_neighbor_matrix N(F.rows(), 3);
  parallel_for(F.rows(), [&](Eigen::Index first, Eigen::Index last) {
    for(Eigen::Index k = first; k < last; ++k)
      for(int a = 0; a < 3; ++a) {
        const int b = F(k, (a + 1) % 3), c = F(k, (a + 2) % 3);
        N(k, a) = -1;
        for(Eigen::Index s = vf.begin(c); s < vf.end(c); ++s) { // the face with the directed edge (c, b)
          const Eigen::Index g = vf.faces[s];
          if(g == k) continue;
          for(int e = 0; e < 3; ++e)
            if(F(g, e) == c && F(g, (e + 1) % 3) == b) N(k, a) = static_cast<int>(g);
        }
      }
  });
  return N;
}

// ---------------------------------------------------------------------------
// Shared pieces of the walks
// ---------------------------------------------------------------------------

/// A small linear congruential generator: the walk's random edge order.
struct Walk_random
{
  std::uint64_t state = 0x853c49e6748fea9bULL;
  int next_of_three()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<int>((state >> 33) % 3);
  }
};

/// Step budget of a walk before falling back to exhaustive search (a walk
/// from a bucket start takes a handful of steps; the budget only guards
/// against a corrupt or folded input).
inline std::size_t walk_step_budget(Eigen::Index faces)
{
  return static_cast<std::size_t>(20 * std::sqrt(double(faces)) + 1000);
}

/// Barycentric coordinates from three signed sub-volumes (or areas) that the
/// exact test found non-negative: clamped (round-off can make a zero slightly
/// negative), normalized; the centroid if all three vanish in floating point.
inline Eigen::Vector3d normalized_barycentric(Eigen::Vector3d l)
{
  l = l.cwiseMax(0.);
  const double s = l.sum();
  if(!(s > 0) || !std::isfinite(s)) return Eigen::Vector3d::Constant(1. / 3);
  return l / s;
}

/// What a walk needs of a triangulation besides its positions: a face at each
/// vertex (-1 for an unused vertex) and the neighbours across the edges
/// (face_neighbors()). It depends on the faces only, so a triangulation
/// located in at several positions (FECM's chart before and after its
/// correction, for every radii) computes it once.
struct Walk_adjacency
{
  std::vector<int> vertex_face;
  Face_neighbor_matrix neighbor;

  Walk_adjacency() = default;
  Walk_adjacency(const Index_matrix& F, Eigen::Index n)
  {
    const Vertex_faces vf(F, n);
    vertex_face.assign(static_cast<std::size_t>(n), -1);
    for(Eigen::Index i = 0; i < n; ++i)
      if(vf.end(i) > vf.begin(i)) vertex_face[i] = static_cast<int>(vf.faces[vf.begin(i)]);
    neighbor = face_neighbors(F, vf);
  }
};

/// Point location in a planar triangulation (n x 2 positions, faces that may
/// leave some vertices unused) by a randomized visibility walk with exact
/// orientation predicates; brute force if the walk does not settle (possible
/// only where the triangulation folds). The domain is assumed convex (it is
/// the outer triangle of a punctured sphere chart), so leaving it through a
/// boundary edge means the point lies outside. Walks that run side by side
/// each pass their own Walk_random; the others share the locator's.
class Planar_point_locator
{
public:
  Planar_point_locator(const Matrix& Q, const Index_matrix& F)
    : Planar_point_locator(Q, F, std::make_shared<const Walk_adjacency>(F, Q.rows()))
  {}

  /// With the adjacency of F computed beforehand (shared, not copied).
  Planar_point_locator(const Matrix& Q, const Index_matrix& F, std::shared_ptr<const Walk_adjacency> adjacency)
    : m_F(F), m_adjacency(std::move(adjacency)), m_max_steps(walk_step_budget(F.rows()))
  {
    const Eigen::Index n = Q.rows();
    m_P.reserve(static_cast<std::size_t>(n));
    for(Eigen::Index i = 0; i < n; ++i) m_P.emplace_back(Q(i, 0), Q(i, 1));
    const double balance = parallel_sum(F.rows(), [&](Eigen::Index k) {
      return double(static_cast<int>(CGAL::orientation(m_P[F(k, 0)], m_P[F(k, 1)], m_P[F(k, 2)])));
    });
    m_sign = balance >= 0 ? 1 : -1;
  }

  /// A face incident to vertex i (-1 if none).
  Eigen::Index incident_face(Eigen::Index i) const { return m_adjacency->vertex_face[i]; }

  /// The face containing q (on its closure), or -1 if q is outside the domain.
  Eigen::Index locate(const Eigen::Vector2d& q, Eigen::Index start) const { return locate(q, start, m_random); }

  /// The same with the walk's own random edge order (for walks side by side).
  Eigen::Index locate(const Eigen::Vector2d& q2, Eigen::Index start, Walk_random& random) const
  {
    const Epick::Point_2 q(q2.x(), q2.y());
    const Face_neighbor_matrix& neighbor = m_adjacency->neighbor;
    Eigen::Index f = start >= 0 ? start : 0;
    for(std::size_t step = 0; step < m_max_steps; ++step) {
      const int r = random.next_of_three();
      bool moved = false;
      for(int t = 0; t < 3 && !moved; ++t) {
        const int a = (r + t) % 3;
        if(side_of_edge(f, a, q) < 0) {
          const Eigen::Index g = neighbor(f, a);
          if(g < 0) return -1;
          f = g;
          moved = true;
        }
      }
      if(!moved) return f;
    }
    // The walk did not settle (folded region): search every face.
    for(Eigen::Index k = 0; k < m_F.rows(); ++k)
      if(side_of_edge(k, 0, q) >= 0 && side_of_edge(k, 1, q) >= 0 && side_of_edge(k, 2, q) >= 0) return k;
    return -1;
  }

  /// Barycentric coordinates of q in face f (clamped to be non-negative).
  Eigen::Vector3d barycentric(Eigen::Index f, const Eigen::Vector2d& q) const
  {
    Eigen::Vector2d v[3];
    for(int a = 0; a < 3; ++a) v[a] = Eigen::Vector2d(m_P[m_F(f, a)].x(), m_P[m_F(f, a)].y());
    auto area2 = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y, const Eigen::Vector2d& z) {
      return (y.x() - x.x()) * (z.y() - x.y()) - (y.y() - x.y()) * (z.x() - x.x());
    };
    return normalized_barycentric(
      Eigen::Vector3d(m_sign * area2(q, v[1], v[2]), m_sign * area2(v[0], q, v[2]), m_sign * area2(v[0], v[1], q)));
  }

  const Index_matrix& faces() const { return m_F; }

private:
  /// Sign (relative to the triangulation's orientation) of q against the line
  /// of the edge of f opposite corner a: negative means q is beyond it.
  int side_of_edge(Eigen::Index f, int a, const Epick::Point_2& q) const
  {
    return m_sign * static_cast<int>(CGAL::orientation(m_P[m_F(f, (a + 1) % 3)], m_P[m_F(f, (a + 2) % 3)], q));
  }

  const Index_matrix& m_F;
  std::shared_ptr<const Walk_adjacency> m_adjacency;
  std::vector<Epick::Point_2> m_P;
  int m_sign = 1;
  std::size_t m_max_steps = 1000;
  mutable Walk_random m_random;
};

/// The walks of the interpolations below: the queries query_at(p), p in
/// [0, m), located in fixed blocks of parallel_block positions (in parallel
/// when asked for). A walk starts at the answer for position
/// parent_position(p) when that lies earlier in the same block, else at the
/// block's previous answer, else at fallback_start(p); found(p, face, query)
/// receives each answer (face -1: outside the domain). A block never starts
/// from another block's answers and has its own random edge order, so the
/// faces found are the same on any number of threads. Returns the number of
/// queries outside the domain.
template <class QueryAt, class ParentPosition, class FallbackStart, class Found>
std::size_t locate_in_fixed_blocks(const Planar_point_locator& locator, Eigen::Index m, const QueryAt& query_at,
                                   const ParentPosition& parent_position, const FallbackStart& fallback_start,
                                   const Found& found)
{
  std::vector<Eigen::Index> located(static_cast<std::size_t>(m), -1);
  std::vector<std::size_t> block_outside(static_cast<std::size_t>((m + parallel_block - 1) / parallel_block), 0);
  for_each_fixed_block(m, [&](Eigen::Index block, Eigen::Index begin, Eigen::Index end) {
    Walk_random random;
    Eigen::Index last = -1;
    for(Eigen::Index p = begin; p < end; ++p) {
      const Eigen::Index parent = parent_position(p);
      Eigen::Index start = parent >= begin ? located[parent] : -1;
      if(start < 0) start = last;
      if(start < 0) start = fallback_start(p);
      const Eigen::Vector2d q = query_at(p);
      const Eigen::Index f = locator.locate(q, start, random);
      located[p] = f;
      found(p, f, q);
      if(f < 0) ++block_outside[static_cast<std::size_t>(block)];
      else last = f;
    }
  });
  return std::accumulate(block_outside.begin(), block_outside.end(), std::size_t(0));
}

/// The values (n x 2, per vertex of the locator's triangulation) at q: their
/// linear interpolation in the face f containing q, or outside_map(q) if q
/// lies outside the domain (f = -1; the maps interpolated here are known in
/// closed form on the domain's boundary, and this extends them continuously).
template <class OutsideMap>
Eigen::RowVector2d interpolated_value(const Planar_point_locator& locator, const Matrix& values, Eigen::Index f,
                                      const Eigen::Vector2d& q, const OutsideMap& outside_map)
{
  if(f < 0) return outside_map(q).transpose();
  const Index_matrix& F = locator.faces();
  const Eigen::Vector3d l = locator.barycentric(f, q);
  return l[0] * values.row(F(f, 0)) + l[1] * values.row(F(f, 1)) + l[2] * values.row(F(f, 2));
}

/// For every vertex i of `order`, the values (n x 2) interpolated at
/// queries[i] (see interpolated_value(); rows not in `order` are left unset).
/// `order` is breadth-first and each walk starts at the parent's answer
/// (locate_in_fixed_blocks()); with an empty `parent`, at the previous one.
template <class OutsideMap>
Matrix interpolate_at_vertex_queries(const Planar_point_locator& locator, const Matrix& values,
                                     const Matrix& queries, const std::vector<Eigen::Index>& order,
                                     const std::vector<Eigen::Index>& parent, OutsideMap outside_map,
                                     std::size_t* outside = nullptr)
{
  const Eigen::Index n = queries.rows(), m = Eigen::Index(order.size());
  std::vector<Eigen::Index> position; // of each vertex in `order`
  if(!parent.empty()) {
    position.assign(static_cast<std::size_t>(n), -1);
    for(Eigen::Index p = 0; p < m; ++p) position[order[p]] = p;
  }
  Matrix out(n, 2);
  const std::size_t n_out = locate_in_fixed_blocks(
    locator, m, [&](Eigen::Index p) { return Eigen::Vector2d(queries(order[p], 0), queries(order[p], 1)); },
    [&](Eigen::Index p) {
      return !parent.empty() && parent[order[p]] >= 0 ? position[parent[order[p]]] : Eigen::Index(-1);
    },
    [&](Eigen::Index p) { return locator.incident_face(order[p]); },
    [&](Eigen::Index p, Eigen::Index f, const Eigen::Vector2d& q) {
      out.row(order[p]) = interpolated_value(locator, values, f, q, outside_map);
    });
  if(outside) *outside = n_out;
  return out;
}

/// The values interpolated at the points Q (m x 2, row p next to row p - 1,
/// as along the rings of a sample), each walk starting at the previous
/// answer; a block's first walk starts at a face of vertex start_vertex(p).
template <class StartVertex, class OutsideMap>
Matrix interpolate_at_points(const Planar_point_locator& locator, const Matrix& values, const Matrix& Q,
                             const StartVertex& start_vertex, OutsideMap outside_map)
{
  Matrix out(Q.rows(), 2);
  locate_in_fixed_blocks(
    locator, Q.rows(), [&](Eigen::Index p) { return Eigen::Vector2d(Q(p, 0), Q(p, 1)); },
    [](Eigen::Index) { return Eigen::Index(-1); },
    [&](Eigen::Index p) { return locator.incident_face(start_vertex(p)); },
    [&](Eigen::Index p, Eigen::Index f, const Eigen::Vector2d& q) {
      out.row(p) = interpolated_value(locator, values, f, q, outside_map);
    });
  return out;
}

// ---------------------------------------------------------------------------
// Spherical point location: cones from the origin
// ---------------------------------------------------------------------------

/// Direction buckets of the sphere: the six faces of the cube [-1,1]^3, each
/// split into G x G cells in the gnomonic coordinates (x/|z|, y/|z|) etc.
class Cube_map_grid
{
public:
  explicit Cube_map_grid(int g = 1) : m_g(std::max(1, g)) {}
  int resolution() const { return m_g; }
  std::size_t size() const { return static_cast<std::size_t>(6 * m_g * m_g); }

  std::size_t bucket(const Eigen::Vector3d& d) const
  {
    int axis = 0;
    for(int c = 1; c < 3; ++c)
      if(std::abs(d[c]) > std::abs(d[axis])) axis = c;
    const double w = std::abs(d[axis]);
    const int side = 2 * axis + (d[axis] < 0 ? 1 : 0);
    const double s = d[(axis + 1) % 3] / w, t = d[(axis + 2) % 3] / w; // in [-1, 1]
    return static_cast<std::size_t>((side * m_g + cell(t)) * m_g + cell(s));
  }

  /// The direction through the centre of bucket b.
  Eigen::Vector3d center(std::size_t b) const
  {
    const int i = int(b % m_g), j = int((b / m_g) % m_g), side = int(b / (std::size_t(m_g) * m_g));
    const int axis = side / 2;
    Eigen::Vector3d d;
    d[axis] = side % 2 ? -1. : 1.;
    d[(axis + 1) % 3] = -1. + (i + 0.5) * 2. / m_g;
    d[(axis + 2) % 3] = -1. + (j + 0.5) * 2. / m_g;
    return d;
  }

private:
  int cell(double s) const
  {
    const int c = static_cast<int>(std::floor((s + 1.) * 0.5 * m_g));
    return std::min(std::max(c, 0), m_g - 1);
  }
  int m_g;
};

/// Point location in a closed triangle mesh whose faces all have the same
/// exact orientation `sign` about the origin (a fold-free map onto the unit
/// sphere or an ellipsoid centred at the origin, see count_fold_overs_about_center).
/// Such a mesh projects radially onto the sphere as a covering of degree one,
/// so every ray from the origin meets exactly one face (or the common boundary
/// of several).
class Spherical_point_locator
{
public:
  Spherical_point_locator() = default;

  /// \pre every face has exact orientation `sign` (+1 or -1) about the origin, the mesh is closed.
  Spherical_point_locator(const Matrix& Y, const Index_matrix& F, int sign)
    : m_F(F), m_sign(sign >= 0 ? 1 : -1), m_max_steps(walk_step_budget(F.rows()))
  {
    const Eigen::Index n = Y.rows();
    m_Y = Y;
    m_P.reserve(static_cast<std::size_t>(n));
    for(Eigen::Index i = 0; i < n; ++i) m_P.emplace_back(Y(i, 0), Y(i, 1), Y(i, 2));
    m_neighbor = face_neighbors(F, Vertex_faces(F, n));
    fill_buckets();
  }

  const Index_matrix& faces() const { return m_F; }
  Eigen::Index number_of_faces() const { return m_F.rows(); }

  /// A face near the direction of q (from the bucket grid), a good walk start.
  Eigen::Index start_face(const Eigen::Vector3d& q) const
  {
    return m_bucket_face.empty() ? 0 : m_bucket_face[m_grid.bucket(q)];
  }

  /// Side length of a bucket seen from the origin (radians, roughly): a
  /// previous answer further away than this is a worse start than the grid.
  double bucket_angle() const { return 2. / m_grid.resolution(); }

  /// The face whose cone from the origin contains q (on its closure), walking
  /// from `start` (the bucket of q if negative). -1 only for q = 0 or a non-finite q.
  Eigen::Index locate(const Eigen::Vector3d& q3, Eigen::Index start = -1) const
  {
    if(!q3.allFinite() || q3.isZero(0)) return -1;
    const Epick::Point_3 q(q3.x(), q3.y(), q3.z());
    Eigen::Index f = start >= 0 ? start : start_face(q3);
    for(std::size_t step = 0; step < m_max_steps; ++step) {
      const int r = m_random.next_of_three();
      bool moved = false;
      for(int t = 0; t < 3 && !moved; ++t) {
        const int a = (r + t) % 3;
        if(side_of_edge(f, a, q) < 0) { f = m_neighbor(f, a); moved = true; }
      }
      if(!moved) return f;
    }
    return locate_exhaustively(q);
  }

  /// Barycentric coordinates of the ray through q in face f:
  /// l_a proportional to det[f_b, f_c, q] ((a, b, c) cyclic), so that q is a
  /// positive multiple of l_0 f_0 + l_1 f_1 + l_2 f_2.
  /// \pre f = locate(q, ...)
  Eigen::Vector3d barycentric(Eigen::Index f, const Eigen::Vector3d& q) const
  {
    Eigen::Vector3d l;
    for(int a = 0; a < 3; ++a) l[a] = m_sign * corner(f, (a + 1) % 3).cross(corner(f, (a + 2) % 3)).dot(q);
    return normalized_barycentric(l);
  }

  Eigen::Vector3d corner(Eigen::Index f, int a) const { return row_vector3(m_Y, m_F(f, a)); }

private:
  /// Sign (relative to a correct face) of q against the plane through the
  /// origin and the edge of f opposite corner a: negative means q is beyond it.
  int side_of_edge(Eigen::Index f, int a, const Epick::Point_3& q) const
  {
    static const Epick::Point_3 origin(0, 0, 0);
    return m_sign * static_cast<int>(
                      CGAL::orientation(origin, m_P[m_F(f, (a + 1) % 3)], m_P[m_F(f, (a + 2) % 3)], q));
  }

  Eigen::Index locate_exhaustively(const Epick::Point_3& q) const
  {
    for(Eigen::Index k = 0; k < m_F.rows(); ++k)
      if(side_of_edge(k, 0, q) >= 0 && side_of_edge(k, 1, q) >= 0 && side_of_edge(k, 2, q) >= 0) return k;
    return -1;
  }

  /// About one bucket per two faces; each bucket stores the face containing
  /// its centre direction, found by walking from the previous bucket's face.
  void fill_buckets()
  {
    const int g = static_cast<int>(std::max(1., std::round(std::sqrt(m_F.rows() / 12.))));
    m_grid = Cube_map_grid(g);
    m_bucket_face.assign(m_grid.size(), 0);
    Eigen::Index f = 0;
    for(std::size_t b = 0; b < m_grid.size(); ++b) {
      const Eigen::Index found = locate(m_grid.center(b), f);
      if(found >= 0) f = found;
      m_bucket_face[b] = f;
    }
  }

  Index_matrix m_F;
  Matrix m_Y;
  std::vector<Epick::Point_3> m_P;
  Face_neighbor_matrix m_neighbor;
  int m_sign = 1;
  std::size_t m_max_steps = 1000;
  Cube_map_grid m_grid;
  std::vector<Eigen::Index> m_bucket_face;
  mutable Walk_random m_random;
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_POINT_LOCATION_H
