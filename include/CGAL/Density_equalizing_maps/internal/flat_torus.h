// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_H

// A closed genus-one mesh mapped to the flat torus R^2 / Lambda Z^2,
// Lambda = diag(2 pi R, 2 pi r), without slicing it (ALGORITHMS.md 10.5).
//
// State: one point u_i in R^2 per vertex and one integer lattice offset
// o_{T,a} in Z^2 per corner. The layout of face T is the planar triangle
// p_{T,a} = u_{T_a} + Lambda o_{T,a}; the offset of a halfedge a -> b of T is
// o_{T,b} - o_{T,a}, twins carry opposite offsets. Adding the same vector to
// the three offsets of a face changes nothing, so only differences matter.
//
// Every per-face quantity (area, cotangents, gradient, Beltrami coefficient,
// LBS stiffness) is computed on the layout and scattered back to the indices
// of the closed mesh: the operators are exactly periodic and there are no
// seam copies. To reuse the planar operators of operators.h and beltrami.h
// unchanged, the layouts are stored as an "unrolled" mesh with 3m vertices and
// faces (3k, 3k+1, 3k+2): per-face blocks computed on it are the blocks of the
// closed mesh, in the same local corner order.
//
// This file also builds the initial offsets: (a) from a mesh already lying on
// the torus, (c) from two user loops, (d) from a tree-cotree decomposition,
// the periodic harmonic map, the Lagrange reduction of the period basis, the
// gauge search along v, and the periodic Linear Beltrami Solver.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>
#include <CGAL/Density_equalizing_maps/internal/validation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Per-corner lattice offsets: row k holds (o_x, o_y) of corners 0, 1, 2 of face k.
using Offset_matrix = Eigen::Matrix<int, Eigen::Dynamic, 6, Eigen::RowMajor>;
/// Per-halfedge integer pairs (halfedge 3k + c goes from F(k,c) to F(k,c+1)).
using Halfedge_offsets = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

constexpr double two_pi = 6.283185307179586476925286766559;

/// The flat torus [0, 2 pi R) x [-pi r, pi r) with its lattice.
struct Torus_radii
{
  double R = 0, r = 0;
  double period_u() const { return two_pi * R; }
  double period_v() const { return two_pi * r; }
  double cell_area() const { return period_u() * period_v(); }
};

/// Throws `Invalid_input` unless R > r > 0, both finite and in the sane range
/// of `validate_domain_radii()` (R / r at most 1e6, both in [1e-100, 1e100]).
inline void validate_torus_radii(double R, double r)
{
  const double radii[2] = {R, r};
  validate_domain_radii(radii, 2, "torus radii (R, r)");
  if(!(R > r))
    throw Invalid_input("torus radii must satisfy R > r (got R = " + std::to_string(R) + ", r = " +
                        std::to_string(r) + "): the torus would self-intersect");
}

/// Twin of every halfedge of a closed, consistently oriented triangle mesh
/// (validated before): halfedge 3k + c is F(k,c) -> F(k,(c+1)%3).
struct Halfedge_table
{
  std::vector<int> twin;
  Eigen::Index nv = 0;

  Halfedge_table() = default;
  Halfedge_table(const Index_matrix& F, Eigen::Index n) : nv(n)
  {
    const Eigen::Index m = F.rows();
    std::unordered_map<long long, int> directed;
    directed.reserve(static_cast<std::size_t>(3 * m));
    for(Eigen::Index k = 0; k < m; ++k)
      for(int c = 0; c < 3; ++c) directed[key(F(k, c), F(k, (c + 1) % 3))] = int(3 * k + c);
    twin.assign(static_cast<std::size_t>(3 * m), -1);
    for(Eigen::Index k = 0; k < m; ++k)
      for(int c = 0; c < 3; ++c) {
        auto it = directed.find(key(F(k, (c + 1) % 3), F(k, c)));
        if(it == directed.end()) throw Invalid_input("open boundary: the mesh must be closed");
        twin[3 * k + c] = it->second;
      }
  }
  long long key(long long i, long long j) const { return i * nv + j; }
  static int face(int h) { return h / 3; }
  static int next(int h) { return 3 * (h / 3) + (h % 3 + 1) % 3; }
  static int prev(int h) { return 3 * (h / 3) + (h % 3 + 2) % 3; }
  static int source(const Index_matrix& F, int h) { return F(h / 3, h % 3); }
  static int target(const Index_matrix& F, int h) { return F(h / 3, (h % 3 + 1) % 3); }
  /// The next outgoing halfedge counter-clockwise around the source of h.
  int next_ccw(int h) const { return twin[prev(h)]; }
};

/// Faces (3k, 3k+1, 3k+2) of the unrolled layout mesh.
inline Index_matrix unrolled_faces(Eigen::Index m)
{
  Index_matrix U(m, 3);
  for(Eigen::Index k = 0; k < m; ++k)
    for(int c = 0; c < 3; ++c) U(k, c) = int(3 * k + c);
  return U;
}

/// The layout points p_{T,a} = u_{T_a} + Lambda o_{T,a} as a 3m x 2 matrix (row 3k + a).
inline Matrix unrolled_layout(const Matrix& u, const Index_matrix& F, const Offset_matrix& o, const Torus_radii& t)
{
  Matrix P(3 * F.rows(), 2);
  const double pu = t.period_u(), pv = t.period_v();
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) {
      P(3 * k + a, 0) = u(F(k, a), 0) + pu * o(k, 2 * a);
      P(3 * k + a, 1) = u(F(k, a), 1) + pv * o(k, 2 * a + 1);
    }
  return P;
}

/// Spreads a per-vertex vector to the corners of the unrolled mesh.
inline Vector unrolled_values(const Vector& g, const Index_matrix& F)
{
  Vector G(3 * F.rows());
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) G[3 * k + a] = g[F(k, a)];
  return G;
}

/// Signed layout areas (counter-clockwise positive).
inline Vector layout_signed_areas(const Matrix& P_unrolled)
{
  const Eigen::Index m = P_unrolled.rows() / 3;
  Vector A(m);
  for(Eigen::Index k = 0; k < m; ++k) {
    const double ax = P_unrolled(3 * k + 1, 0) - P_unrolled(3 * k, 0), ay = P_unrolled(3 * k + 1, 1) - P_unrolled(3 * k, 1);
    const double bx = P_unrolled(3 * k + 2, 0) - P_unrolled(3 * k, 0), by = P_unrolled(3 * k + 2, 1) - P_unrolled(3 * k, 1);
    A[k] = 0.5 * (ax * by - ay * bx);
  }
  return A;
}

/// Exact orientation of each layout triangle (+1, 0, -1), on the very doubles of the layout.
inline std::vector<int> layout_orientations(const Matrix& P_unrolled)
{
  const Eigen::Index m = P_unrolled.rows() / 3;
  std::vector<int> o(static_cast<std::size_t>(m));
  for(Eigen::Index k = 0; k < m; ++k) {
    const Epick::Point_2 a(P_unrolled(3 * k, 0), P_unrolled(3 * k, 1)), b(P_unrolled(3 * k + 1, 0), P_unrolled(3 * k + 1, 1)),
      c(P_unrolled(3 * k + 2, 0), P_unrolled(3 * k + 2, 1));
    o[k] = static_cast<int>(CGAL::orientation(a, b, c));
  }
  return o;
}

/// Number of layout triangles whose exact orientation is not `expected` (+1 or -1).
inline std::size_t count_layout_fold_overs(const Matrix& P_unrolled, int expected)
{
  std::size_t n = 0;
  for(int s : layout_orientations(P_unrolled)) n += (s != expected);
  return n;
}

/// 3D images phi(u_i) on the torus (n x 3); phi is periodic, so no offsets are needed.
inline void torus_images(const Matrix& u, const Torus_radii& t, Matrix& Y)
{
  Y.resize(u.rows(), 3);
  for(Eigen::Index i = 0; i < u.rows(); ++i) Y.row(i) = torus_point(u(i, 0), u(i, 1), t.R, t.r).transpose();
}

inline Matrix torus_images(const Matrix& u, const Torus_radii& t)
{
  Matrix Y;
  torus_images(u, t, Y);
  return Y;
}

/// Corner offsets from per-halfedge offsets t_h: o_0 = 0, o_1 = t_{01}, o_2 = t_{01} + t_{12}.
/// Returns false if some face has sum t_h != 0 (not a cocycle).
inline bool corner_offsets_from_halfedges(const Halfedge_offsets& t, Eigen::Index m, Offset_matrix& o)
{
  o.setZero(m, 6);
  for(Eigen::Index k = 0; k < m; ++k)
    for(int d = 0; d < 2; ++d) {
      o(k, 2 + d) = t(3 * k, d);
      o(k, 4 + d) = t(3 * k, d) + t(3 * k + 1, d);
      if(o(k, 4 + d) + t(3 * k + 2, d) != 0) return false;
    }
  return true;
}

/// Checks the combinatorial invariant: twin halfedges carry opposite offsets.
/// Returns the first offending halfedge or -1.
inline int first_inconsistent_twin(const Offset_matrix& o, const Halfedge_table& he)
{
  auto offset = [&o](int h, int d) {
    const int k = h / 3, a = h % 3, b = (a + 1) % 3;
    return o(k, 2 * b + d) - o(k, 2 * a + d);
  };
  for(int h = 0; h < int(he.twin.size()); ++h)
    for(int d = 0; d < 2; ++d)
      if(offset(h, d) != -offset(he.twin[h], d)) return h;
  return -1;
}

/// Moves every vertex into the cell [0, 2 pi R) x [-pi r, pi r) and updates
/// the offsets so that every layout triangle is unchanged (up to round-off).
inline void wrap_into_cell(Matrix& u, const Index_matrix& F, Offset_matrix& o, const Torus_radii& t)
{
  const double pu = t.period_u(), pv = t.period_v();
  std::vector<std::array<int, 2> > shift(static_cast<std::size_t>(u.rows()));
  const double v_low = -0.5 * pv, v_high = 0.5 * pv;
  for(Eigen::Index i = 0; i < u.rows(); ++i) {
    int ku = int(std::floor(u(i, 0) / pu));
    int kv = int(std::floor((u(i, 1) - v_low) / pv));
    double a = u(i, 0) - ku * pu, b = u(i, 1) - kv * pv;
    // round-off can land exactly on the open upper end: move one more period
    // (and count it in the offsets); a last ulp below the lower end is clamped
    if(!(a < pu)) { a -= pu; ++ku; }
    if(!(b < v_high)) { b -= pv; ++kv; }
    u(i, 0) = std::max(a, 0.);
    u(i, 1) = std::max(b, v_low);
    shift[i] = {ku, kv};
  }
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) {
      o(k, 2 * a) += shift[F(k, a)][0];
      o(k, 2 * a + 1) += shift[F(k, a)][1];
    }
}

/// (a) Flat-torus coordinates of a mesh already lying on the torus (R, r):
/// u_i = phi^{-1}(x_i), offsets of nearest images. Throws if a vertex is
/// off the torus or if a face spans too much of a period to be unrolled.
inline Offset_matrix offsets_from_torus_positions(const Matrix& X, const Index_matrix& F, const Torus_radii& t,
                                                   Matrix& u)
{
  const double tolerance = 1e-3 * t.r;
  u.resize(X.rows(), 2);
  for(Eigen::Index i = 0; i < X.rows(); ++i) {
    const Eigen::Vector3d p = X.row(i).transpose();
    const double d = std::hypot(std::hypot(p.x(), p.y()) - t.R, p.z());
    if(std::abs(d - t.r) > tolerance)
      throw Invalid_input("vertex " + std::to_string(i) + " is not on the torus with R = " + std::to_string(t.R) +
                          ", r = " + std::to_string(t.r) + " (distance to the tube axis " + std::to_string(d) + ")");
    u.row(i) = torus_coordinates(p, t.R, t.r).transpose();
  }
  const double pu = t.period_u(), pv = t.period_v();
  Halfedge_offsets th(3 * F.rows(), 2);
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3);
      th(3 * k + c, 0) = int(std::lround(-(u(j, 0) - u(i, 0)) / pu));
      th(3 * k + c, 1) = int(std::lround(-(u(j, 1) - u(i, 1)) / pv));
    }
  Offset_matrix o;
  if(!corner_offsets_from_halfedges(th, F.rows(), o)) {
    for(Eigen::Index k = 0; k < F.rows(); ++k)
      for(int d = 0; d < 2; ++d)
        if(th(3 * k, d) + th(3 * k + 1, d) + th(3 * k + 2, d) != 0)
          throw Invalid_input("face " + std::to_string(k) +
                              " spans a third of a torus period or more: the mesh is too coarse to be "
                              "laid out on the flat torus");
  }
  return o;
}

/// Signed crossing numbers of dual loops: for each of the two generators, +1 on
/// the halfedge through which the loop leaves a face, -1 on its twin.
/// (d) Tree-cotree (Eppstein): BFS spanning tree of the vertices from `root`,
/// BFS spanning tree of the faces across the other edges; the two edges left
/// over close the two dual generator loops.
inline Halfedge_offsets tree_cotree_cocycles(const Index_matrix& F, const Halfedge_table& he, Eigen::Index nv,
                                             int root = 0)
{
  const int nh = int(he.twin.size());
  std::vector<char> in_tree(static_cast<std::size_t>(nh), 0); // per halfedge (both twins marked)
  // one outgoing halfedge per vertex to walk its one-ring
  std::vector<int> out(static_cast<std::size_t>(nv), -1);
  for(int h = 0; h < nh; ++h)
    if(out[Halfedge_table::source(F, h)] < 0) out[Halfedge_table::source(F, h)] = h;
  {
    std::vector<char> seen(static_cast<std::size_t>(nv), 0);
    std::deque<int> queue{root};
    seen[root] = 1;
    while(!queue.empty()) {
      const int v = queue.front(); queue.pop_front();
      const int h0 = out[v];
      int h = h0;
      do {
        const int w = Halfedge_table::target(F, h);
        if(!seen[w]) {
          seen[w] = 1;
          in_tree[h] = in_tree[he.twin[h]] = 1;
          queue.push_back(w);
        }
        h = he.next_ccw(h);
      } while(h != h0);
    }
  }
  // cotree over faces, crossing only non-tree edges; parent_halfedge[f] = halfedge of f crossed towards the parent
  const Eigen::Index m = F.rows();
  std::vector<int> parent_halfedge(static_cast<std::size_t>(m), -1), depth(static_cast<std::size_t>(m), -1);
  std::vector<char> in_cotree(static_cast<std::size_t>(nh), 0);
  {
    std::deque<int> queue{0};
    depth[0] = 0;
    while(!queue.empty()) {
      const int f = queue.front(); queue.pop_front();
      for(int c = 0; c < 3; ++c) {
        const int h = 3 * f + c;
        if(in_tree[h]) continue;
        const int g = Halfedge_table::face(he.twin[h]);
        if(depth[g] >= 0) continue;
        depth[g] = depth[f] + 1;
        parent_halfedge[g] = he.twin[h];
        in_cotree[h] = in_cotree[he.twin[h]] = 1;
        queue.push_back(g);
      }
    }
  }
  Halfedge_offsets t = Halfedge_offsets::Zero(nh, 2);
  int generator = 0;
  for(int h = 0; h < nh && generator < 2; ++h) {
    if(in_tree[h] || in_cotree[h] || h > he.twin[h]) continue;
    // loop: leave face(h) through h into g = face(twin h), then walk the cotree back to face(h)
    auto cross = [&](int leaving) { t(leaving, generator) += 1; t(he.twin[leaving], generator) -= 1; };
    cross(h);
    int a = Halfedge_table::face(he.twin[h]), b = Halfedge_table::face(h);
    // path a -> ... -> lca <- ... <- b: going up from a we leave through parent_halfedge;
    // going up from b we record halfedges and later cross them downwards (twins).
    std::vector<int> down;
    while(a != b) {
      if(depth[a] >= depth[b]) { cross(parent_halfedge[a]); a = Halfedge_table::face(he.twin[parent_halfedge[a]]); }
      else { down.push_back(he.twin[parent_halfedge[b]]); b = Halfedge_table::face(he.twin[parent_halfedge[b]]); }
    }
    for(auto it = down.rbegin(); it != down.rend(); ++it) cross(*it);
    ++generator;
  }
  CGAL_assertion(generator == 2);
  return t;
}

/// Signed crossing numbers of the pushed-off copy of an oriented vertex loop
/// (loop[i] -> loop[i+1], closed): every halfedge x -> n with n strictly in the
/// left fan of the loop at x gets +1, its twin -1.
inline void add_loop_cocycle(const Index_matrix& F, const Halfedge_table& he, const std::vector<int>& out,
                             const std::vector<int>& loop, Halfedge_offsets& t, int column)
{
  const std::size_t L = loop.size();
  auto find_out = [&](int x, int y) {
    const int h0 = out[x];
    int h = h0;
    do {
      if(Halfedge_table::target(F, h) == y) return h;
      h = he.next_ccw(h);
    } while(h != h0);
    return -1;
  };
  for(std::size_t s = 0; s < L; ++s) {
    const int x = loop[s], y = loop[(s + 1) % L], w = loop[(s + L - 1) % L];
    const int forward = find_out(x, y);
    int h = he.next_ccw(forward);
    while(Halfedge_table::target(F, h) != w) {
      t(h, column) += 1;
      t(he.twin[h], column) -= 1;
      h = he.next_ccw(h);
    }
  }
}

/// (c) Cocycles from user cut edges: two simple vertex loops meeting only at
/// one base vertex. Throws Invalid_input for out-of-range vertices, pairs that
/// are not mesh edges, a graph that is not two such loops, or loops that do
/// not cross exactly once (then they are separating or homologous and do not
/// cut the torus into a disk). `base` receives the base vertex.
inline Halfedge_offsets cut_edge_cocycles(const Index_matrix& F, const Halfedge_table& he, Eigen::Index nv,
                                          const std::vector<std::pair<int, int> >& cut, int& base)
{
  const int nh = int(he.twin.size());
  std::vector<int> out(static_cast<std::size_t>(nv), -1);
  for(int h = 0; h < nh; ++h)
    if(out[Halfedge_table::source(F, h)] < 0) out[Halfedge_table::source(F, h)] = h;
  std::unordered_map<long long, int> halfedge_of;
  halfedge_of.reserve(static_cast<std::size_t>(nh));
  for(int h = 0; h < nh; ++h) halfedge_of[he.key(Halfedge_table::source(F, h), Halfedge_table::target(F, h))] = h;

  // deduplicate undirected edges
  std::vector<std::vector<int> > adjacent(static_cast<std::size_t>(nv));
  std::size_t count = 0;
  for(std::size_t e = 0; e < cut.size(); ++e) {
    const int i = cut[e].first, j = cut[e].second;
    if(i < 0 || j < 0 || i >= nv || j >= nv)
      throw Invalid_input("cut edge " + std::to_string(e) + " (" + std::to_string(i) + ", " + std::to_string(j) +
                          ") refers to a vertex out of range");
    if(halfedge_of.find(he.key(i, j)) == halfedge_of.end())
      throw Invalid_input("cut edge " + std::to_string(e) + " (" + std::to_string(i) + ", " + std::to_string(j) +
                          ") is not an edge of the mesh");
    if(std::find(adjacent[i].begin(), adjacent[i].end(), j) != adjacent[i].end()) continue;
    adjacent[i].push_back(j);
    adjacent[j].push_back(i);
    ++count;
  }
  const std::string expected = "the cut edges must form two closed loops that meet only at one base vertex, "
                               "where they cross";
  if(count == 0) throw Invalid_input("no cut edges given: " + expected);
  base = -1;
  for(int v = 0; v < nv; ++v) {
    const std::size_t d = adjacent[v].size();
    if(d == 0 || d == 2) continue;
    if(d == 4 && base < 0) { base = v; continue; }
    throw Invalid_input(expected + " (vertex " + std::to_string(v) + " has " + std::to_string(d) + " cut edges)");
  }
  if(base < 0) throw Invalid_input(expected + " (no vertex has four cut edges)");
  // chain the two loops from the base
  std::vector<std::vector<int> > loops;
  std::vector<char> used_start(4, 0);
  std::size_t edges_walked = 0;
  for(int s = 0; s < 4; ++s) {
    if(used_start[s]) continue;
    std::vector<int> loop{base};
    int previous = base, current = adjacent[base][s];
    ++edges_walked;
    while(current != base) {
      if(int(loop.size()) > nv) throw Invalid_input(expected);
      loop.push_back(current);
      const int next = adjacent[current][0] == previous ? adjacent[current][1] : adjacent[current][0];
      previous = current; current = next;
      ++edges_walked;
    }
    for(int q = 0; q < 4; ++q)
      if(adjacent[base][q] == previous) used_start[q] = 1;
    used_start[s] = 1;
    loops.push_back(loop);
  }
  if(loops.size() != 2 || edges_walked != count)
    throw Invalid_input(expected + " (found " + std::to_string(loops.size()) + " loops through the base vertex" +
                        (edges_walked != count ? " and cut edges not on them)" : ")"));
  Halfedge_offsets iota = Halfedge_offsets::Zero(nh, 2);
  add_loop_cocycle(F, he, out, loops[0], iota, 0);
  add_loop_cocycle(F, he, out, loops[1], iota, 1);
  // intersection number of loop 0 with loop 1 = sum of iota_1 along loop 0
  int crossing = 0;
  for(std::size_t s = 0; s < loops[0].size(); ++s) {
    const int x = loops[0][s], y = loops[0][(s + 1) % loops[0].size()];
    crossing += iota(halfedge_of[he.key(x, y)], 1);
  }
  if(std::abs(crossing) != 1)
    throw Invalid_input(expected + " (their intersection number is " + std::to_string(crossing) +
                        ": they do not form two non-separating loops crossing once)");
  // t_h = (iota_b, iota_a): loop a then has period +-Lambda e_1
  Halfedge_offsets t(nh, 2);
  t.col(0) = iota.col(1);
  t.col(1) = iota.col(0);
  return t;
}

/// Load of the periodic problems: b = -sum_T S_T^T K^T (Lambda o_T), with the
/// periods (pu, pv) per coordinate; blocks are the m x 9 local stiffnesses.
inline Matrix periodic_load(const Matrix& blocks, const Index_matrix& F, const Offset_matrix& o, double pu, double pv)
{
  Matrix b = Matrix::Zero(F.rows() == 0 ? 0 : F.maxCoeff() + 1, 2);
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) {
      double sx = 0, sy = 0;
      for(int c = 0; c < 3; ++c) {
        sx += blocks(k, 3 * a + c) * pu * o(k, 2 * c);
        sy += blocks(k, 3 * a + c) * pv * o(k, 2 * c + 1);
      }
      b(F(k, a), 0) -= sx;
      b(F(k, a), 1) -= sy;
    }
  return b;
}

/// Minimizes sum_T 1/2 w_T^T K^T w_T over periodic maps (w_{T,a} = w_{T_a} +
/// Lambda o_{T,a}) with vertex `pin` fixed at `pin_value`. Both coordinates
/// share one factorization. Returns false if the solve fails.
inline bool periodic_quadratic_solve(const Matrix& blocks, const Index_matrix& F, const Offset_matrix& o, double pu,
                                     double pv, Eigen::Index nv, int pin, const Eigen::Vector2d& pin_value,
                                     const Face_block_assembler& assembler, Spd_solver& solver, Matrix& w)
{
  Sparse_matrix K = assembler.assemble(blocks);
  Matrix rhs = periodic_load(blocks, F, o, pu, pv);
  rhs.conservativeResize(nv, 2);
  std::vector<char> fixed(static_cast<std::size_t>(nv), 0);
  fixed[pin] = 1;
  Matrix values = Matrix::Zero(nv, 2);
  values.row(pin) = pin_value.transpose();
  apply_dirichlet(K, rhs, fixed, values);
  if(!solver.factor(K)) return false;
  return solver.solve(rhs, w);
}

/// Dirichlet energies G_ab = sum_T h_a,T^T K^T h_b,T of the two unit-period
/// coordinates (offsets included).
inline Eigen::Matrix2d periodic_gram(const Matrix& blocks, const Index_matrix& F, const Offset_matrix& o, const Matrix& h)
{
  Eigen::Matrix2d G = Eigen::Matrix2d::Zero();
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    Eigen::Matrix<double, 3, 2> c;
    for(int a = 0; a < 3; ++a)
      for(int d = 0; d < 2; ++d) c(a, d) = h(F(k, a), d) + o(k, 2 * a + d);
    Eigen::Matrix3d B;
    for(int a = 0; a < 3; ++a)
      for(int b = 0; b < 3; ++b) B(a, b) = blocks(k, 3 * a + b);
    G += c.transpose() * B * c;
  }
  return G;
}

/// Lagrange (Gauss) reduction of the period basis with respect to the Dirichlet
/// energy: afterwards |G_12| <= G_11 / 2 and G_11 <= G_22, so column 0 is the
/// direction of least energy (the conformally longer one). Offsets and unit
/// solutions are transformed alike (the solution is linear in the offsets).
inline void lagrange_reduce(Eigen::Matrix2d& G, Offset_matrix& o, Matrix& h)
{
  for(int guard = 0; guard < 200; ++guard) {
    if(G(0, 0) > G(1, 1)) {
      std::swap(G(0, 0), G(1, 1));
      for(Eigen::Index k = 0; k < o.rows(); ++k)
        for(int a = 0; a < 3; ++a) std::swap(o(k, 2 * a), o(k, 2 * a + 1));
      h.col(0).swap(h.col(1));
    }
    const double q = std::round(G(0, 1) / G(0, 0));
    if(q == 0) break;
    const int kq = int(q);
    for(Eigen::Index k = 0; k < o.rows(); ++k)
      for(int a = 0; a < 3; ++a) o(k, 2 * a + 1) -= kq * o(k, 2 * a);
    h.col(1) -= q * h.col(0);
    G(1, 1) = G(1, 1) - 2 * q * G(0, 1) + q * q * G(0, 0);
    G(0, 1) = G(1, 0) = G(0, 1) - q * G(0, 0);
  }
}

/// Mean |log(rho_T / rho_bar)| of the density P_T / |phi(layout_T + (0, c))|
/// for the 256 shifts c = 2 pi r m / 256; returns the best shift (lowest m on ties).
inline double best_gauge_shift(const Matrix& u, const Index_matrix& F, const Vector& population, const Torus_radii& t,
                               int samples = 256)
{
  const Eigen::Index n = u.rows();
  Vector cu(n), su(n), cv(n), sv(n);
  for(Eigen::Index i = 0; i < n; ++i) {
    cu[i] = std::cos(u(i, 0) / t.R); su[i] = std::sin(u(i, 0) / t.R);
    cv[i] = std::cos(u(i, 1) / t.r); sv[i] = std::sin(u(i, 1) / t.r);
  }
  double best = std::numeric_limits<double>::infinity(), best_c = 0;
  Matrix Y(n, 3);
  Vector area(F.rows());
  const double P_total = population.sum();
  for(int s = 0; s < samples; ++s) {
    const double c = t.period_v() * s / samples;
    const double cc = std::cos(c / t.r), sc = std::sin(c / t.r);
    for(Eigen::Index i = 0; i < n; ++i) {
      const double cosv = cv[i] * cc - sv[i] * sc, sinv = sv[i] * cc + cv[i] * sc;
      const double w = t.R + t.r * cosv;
      Y(i, 0) = w * cu[i]; Y(i, 1) = w * su[i]; Y(i, 2) = t.r * sinv;
    }
    for(Eigen::Index k = 0; k < F.rows(); ++k) area[k] = 0.5 * face_normal(Y, F, k).norm();
    const double rho_bar = P_total / area.sum();
    double e = 0;
    for(Eigen::Index k = 0; k < F.rows(); ++k) e += std::abs(std::log(population[k] / area[k] / rho_bar));
    e /= double(F.rows());
    if(e < best) { best = e; best_c = c; }
  }
  return best_c;
}

/// Periodic Linear Beltrami Solver: the periodic map w whose Beltrami
/// coefficient with respect to the source layout P0 (unrolled) approximates
/// mu, with the current offsets o and vertex `pin` fixed at `pin_value`.
/// With the exact coefficient of a fold-free map it reproduces that map.
inline bool periodic_linear_beltrami_solve(const Matrix& P0_unrolled, const Index_matrix& F_unrolled,
                                           const Index_matrix& F, const Offset_matrix& o, const Torus_radii& t,
                                           const Complex_vector& mu, int pin, const Eigen::Vector2d& pin_value,
                                           const Face_block_assembler& assembler, Spd_solver& solver, Matrix& w)
{
  const Matrix blocks = beltrami_stiffness_blocks(P0_unrolled, F_unrolled, mu);
  return periodic_quadratic_solve(blocks, F, o, t.period_u(), t.period_v(), assembler.size(), pin, pin_value, assembler,
                                  solver, w);
}

/// Result of the seamless initial parameterization.
struct Flat_torus_parameterization
{
  Matrix u;            // n x 2, in the cell
  Offset_matrix offsets;
  Eigen::Matrix2d gram; // reduced Dirichlet Gram matrix of the unit-period solutions
  bool used_uniform_weights = false;
  int base = 0;
};

/// Seamless periodic harmonic map of a closed genus-one mesh onto the flat torus
/// (R, r), from cocycles t (from cut loops or tree-cotree): unit-period
/// harmonic solutions, Lagrange reduction, scaling by the periods, orientation,
/// base vertex at (0, -pi r), gauge shift c* along v for `population`, wrap.
/// Uses cotangent weights; if that map folds, uniform weights (toroidal Tutte
/// embedding, fold-free for positive weights). Returns false on solver failure.
inline bool flat_torus_harmonic_map(const Matrix& X, const Index_matrix& F, const Halfedge_offsets& cocycles, int base,
                                    const Torus_radii& t, const Vector& population, Spd_solver& solver,
                                    Flat_torus_parameterization& result)
{
  const Eigen::Index n = X.rows(), m = F.rows();
  Offset_matrix o0;
  if(!corner_offsets_from_halfedges(cocycles, m, o0)) return false;
  const Face_block_assembler assembler(F, n);
  for(int attempt = 0; attempt < 2; ++attempt) {
    Matrix blocks;
    if(attempt == 0) blocks = cotangent_stiffness_blocks(X, F);
    else {
      blocks = Matrix::Zero(m, 9); // uniform weights: 1/2 per face side, i.e. 1 per interior edge
      for(Eigen::Index k = 0; k < m; ++k)
        for(int a = 0; a < 3; ++a) {
          const int b = (a + 1) % 3, c = (a + 2) % 3;
          blocks(k, 3 * b + c) -= 0.5; blocks(k, 3 * c + b) -= 0.5;
          blocks(k, 3 * b + b) += 0.5; blocks(k, 3 * c + c) += 0.5;
        }
    }
    Offset_matrix o = o0;
    Matrix h;
    if(!periodic_quadratic_solve(blocks, F, o, 1., 1., n, base, Eigen::Vector2d::Zero(), assembler, solver, h))
      return false;
    Eigen::Matrix2d G = periodic_gram(blocks, F, o, h);
    lagrange_reduce(G, o, h);
    Matrix u(n, 2);
    u.col(0) = t.period_u() * h.col(0);
    u.col(1) = t.period_v() * h.col(1);
    if(layout_signed_areas(unrolled_layout(u, F, o, t)).sum() < 0) {
      u.col(1) = -u.col(1);
      for(Eigen::Index k = 0; k < m; ++k)
        for(int a = 0; a < 3; ++a) o(k, 2 * a + 1) = -o(k, 2 * a + 1);
    }
    const Eigen::RowVector2d shift = Eigen::RowVector2d(0, -0.5 * t.period_v()) - u.row(base);
    u.rowwise() += shift;
    const double c = best_gauge_shift(u, F, population, t);
    u.col(1).array() += c;
    wrap_into_cell(u, F, o, t);
    result.u = u;
    result.offsets = o;
    result.gram = G;
    result.used_uniform_weights = attempt == 1;
    result.base = base;
    if(count_layout_fold_overs(unrolled_layout(u, F, o, t), 1) == 0) return true;
  }
  return true; // folded even with uniform weights (not expected): the caller repairs or reports
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_H
