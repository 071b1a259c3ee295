// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_POINT_LOCATION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_POINT_LOCATION_H

// Point location in the layout of a fold-free map onto the flat torus
// (flat_torus.h), walked in the universal cover: a location is a face and the
// lattice translate of its layout triangle that contains the query. The same
// randomized visibility walk and exactness rules as point_location.h; crossing
// an edge keeps the shared corners at the same integer offsets, so the two
// faces of an edge test the very same doubles.

#include <CGAL/Density_equalizing_maps/internal/flat_torus.h>
#include <CGAL/Density_equalizing_maps/internal/point_location.h>

#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

// ---------------------------------------------------------------------------
// Flat-torus point location: the layout in the universal cover
// ---------------------------------------------------------------------------

/// A face of the flat-torus layout and the lattice translate of its layout
/// triangle: the triangle with corners u_{F(k,a)} + Lambda (o_{k,a} + shift).
struct Flat_torus_location
{
  Eigen::Index face = -1;
  std::array<int, 2> shift{{0, 0}};
};

/// Point location in the layout (u, o) of a fold-free map onto the flat torus
/// (every layout triangle with exact orientation `sign`, total area one
/// period cell: a covering of degree one).
class Flat_torus_point_locator
{
public:
  Flat_torus_point_locator() = default;

  /// \pre the layout is fold-free with orientation `sign` and covers the torus once (layout_orientation()).
  Flat_torus_point_locator(const Matrix& u, const Index_matrix& F, const Offset_matrix& o, const Torus_radii& t,
                           int sign)
    : m_u(u), m_F(F), m_o(o), m_t(t), m_sign(sign >= 0 ? 1 : -1), m_max_steps(walk_step_budget(F.rows()))
  {
    const Halfedge_table he(F, u.rows());
    const Eigen::Index m = F.rows();
    m_neighbor.resize(m, 3);
    m_neighbor_shift.resize(m, 6);
    for(Eigen::Index k = 0; k < m; ++k)
      for(int a = 0; a < 3; ++a) {
        // the edge opposite corner a is the halfedge from corner b = a+1 to a+2
        const int b = (a + 1) % 3;
        const int h = he.twin[3 * k + b];
        const int g = Halfedge_table::face(h), gb = (h % 3 + 1) % 3; // vertex F(k,b) is the twin's target
        m_neighbor(k, a) = g;
        // crossing to g keeps the shared corner in place: shift_g = shift_k + o_{k,b} - o_{g,gb}
        m_neighbor_shift(k, 2 * a) = o(k, 2 * b) - o(g, 2 * gb);
        m_neighbor_shift(k, 2 * a + 1) = o(k, 2 * b + 1) - o(g, 2 * gb + 1);
      }
    fill_buckets();
  }

  const Index_matrix& faces() const { return m_F; }
  const Torus_radii& radii() const { return m_t; }

  /// q moved into the period cell [0, 2 pi R) x [-pi r, pi r).
  Eigen::Vector2d reduce_to_cell(const Eigen::Vector2d& q) const
  {
    const double pu = m_t.period_u(), pv = m_t.period_v();
    Eigen::Vector2d w(q.x() - pu * std::floor(q.x() / pu), q.y() - pv * std::floor((q.y() + 0.5 * pv) / pv));
    if(!(w.x() < pu)) w.x() -= pu;
    if(!(w.y() < 0.5 * pv)) w.y() -= pv;
    return w;
  }

  /// Layout corner a of face k translated by `shift` periods.
  Eigen::Vector2d corner(Eigen::Index k, int a, const std::array<int, 2>& shift) const
  {
    const int i = m_F(k, a);
    return Eigen::Vector2d(m_u(i, 0) + m_t.period_u() * (m_o(k, 2 * a) + shift[0]),
                           m_u(i, 1) + m_t.period_v() * (m_o(k, 2 * a + 1) + shift[1]));
  }

  /// A location near q (from the bucket grid); q in the period cell.
  Flat_torus_location start_location(const Eigen::Vector2d& q) const { return m_bucket[bucket(q)]; }

  /// Bucket side in the u direction: a previous answer further away than this is a worse start.
  double bucket_size() const { return m_t.period_u() / m_gu; }

  /// The translated layout triangle containing q (on its closure), walking
  /// from `start` (from the bucket grid if its face is negative). The walk
  /// follows q itself, not its reduction into the cell: reduce first with
  /// reduce_to_cell() if the shift should be relative to the cell.
  Flat_torus_location locate(const Eigen::Vector2d& q2, Flat_torus_location start = Flat_torus_location()) const
  {
    if(!q2.allFinite()) return Flat_torus_location();
    if(start.face < 0) {
      start = start_location(reduce_to_cell(q2));
      // the bucket is for the reduced point: translate to q's own cell
      const Eigen::Vector2d d = q2 - reduce_to_cell(q2);
      start.shift[0] += int(std::lround(d.x() / m_t.period_u()));
      start.shift[1] += int(std::lround(d.y() / m_t.period_v()));
    }
    const Epick::Point_2 q(q2.x(), q2.y());
    Flat_torus_location f = start;
    for(std::size_t step = 0; step < m_max_steps; ++step) {
      const int r = m_random.next_of_three();
      bool moved = false;
      for(int t = 0; t < 3 && !moved; ++t) {
        const int a = (r + t) % 3;
        if(side_of_edge(f, a, q) < 0) {
          f.shift[0] += m_neighbor_shift(f.face, 2 * a);
          f.shift[1] += m_neighbor_shift(f.face, 2 * a + 1);
          f.face = m_neighbor(f.face, a);
          moved = true;
        }
      }
      if(!moved) return f;
    }
    return locate_exhaustively(q2);
  }

  /// Barycentric coordinates of q in the translated layout triangle `f`.
  Eigen::Vector3d barycentric(const Flat_torus_location& f, const Eigen::Vector2d& q) const
  {
    const Eigen::Vector2d p[3] = {corner(f.face, 0, f.shift), corner(f.face, 1, f.shift), corner(f.face, 2, f.shift)};
    Eigen::Vector3d l;
    for(int a = 0; a < 3; ++a) l[a] = m_sign * signed_area2(q, p[(a + 1) % 3], p[(a + 2) % 3]);
    return normalized_barycentric(l);
  }

private:
  static double signed_area2(const Eigen::Vector2d& x, const Eigen::Vector2d& y, const Eigen::Vector2d& z)
  {
    return (y.x() - x.x()) * (z.y() - x.y()) - (y.y() - x.y()) * (z.x() - x.x());
  }

  int side_of_edge(const Flat_torus_location& f, int a, const Epick::Point_2& q) const
  {
    const Eigen::Vector2d b = corner(f.face, (a + 1) % 3, f.shift), c = corner(f.face, (a + 2) % 3, f.shift);
    return m_sign * static_cast<int>(CGAL::orientation(Epick::Point_2(b.x(), b.y()), Epick::Point_2(c.x(), c.y()), q));
  }

  bool contains(const Flat_torus_location& f, const Epick::Point_2& q) const
  {
    return side_of_edge(f, 0, q) >= 0 && side_of_edge(f, 1, q) >= 0 && side_of_edge(f, 2, q) >= 0;
  }

  /// Every face, in the translates whose corner 0 is within one period of q
  /// (a layout triangle spans less than a third of a period, flat_torus.h).
  Flat_torus_location locate_exhaustively(const Eigen::Vector2d& q2) const
  {
    const Epick::Point_2 q(q2.x(), q2.y());
    for(Eigen::Index k = 0; k < m_F.rows(); ++k) {
      const Eigen::Vector2d p0 = corner(k, 0, {{0, 0}});
      const int su = int(std::lround((q2.x() - p0.x()) / m_t.period_u()));
      const int sv = int(std::lround((q2.y() - p0.y()) / m_t.period_v()));
      for(int du = -1; du <= 1; ++du)
        for(int dv = -1; dv <= 1; ++dv) {
          Flat_torus_location f;
          f.face = k;
          f.shift = {{su + du, sv + dv}};
          if(contains(f, q)) return f;
        }
    }
    return Flat_torus_location();
  }

  std::size_t bucket(const Eigen::Vector2d& q) const
  {
    const double su = q.x() / m_t.period_u(), sv = q.y() / m_t.period_v() + 0.5; // in [0, 1)
    const int i = std::min(std::max(int(su * m_gu), 0), m_gu - 1);
    const int j = std::min(std::max(int(sv * m_gv), 0), m_gv - 1);
    return static_cast<std::size_t>(j * m_gu + i);
  }

  /// About one bucket per two faces, cells of the aspect of the period cell;
  /// each stores the location of its centre, walked from the previous one.
  void fill_buckets()
  {
    const double cells = std::max(1., m_F.rows() / 2.), aspect = m_t.R / m_t.r;
    m_gv = std::max(1, int(std::round(std::sqrt(cells / aspect))));
    m_gu = std::max(1, int(std::round(cells / m_gv)));
    m_bucket.assign(static_cast<std::size_t>(m_gu) * m_gv, Flat_torus_location());
    Flat_torus_location f;
    f.face = 0;
    // start in the translate of face 0 nearest to the cell
    const Eigen::Vector2d p0 = corner(0, 0, {{0, 0}}), c0 = reduce_to_cell(p0);
    f.shift = {{int(std::lround((c0.x() - p0.x()) / m_t.period_u())),
                int(std::lround((c0.y() - p0.y()) / m_t.period_v()))}};
    for(int j = 0; j < m_gv; ++j)
      for(int i = 0; i < m_gu; ++i) {
        const Eigen::Vector2d c((i + 0.5) * m_t.period_u() / m_gu, ((j + 0.5) / m_gv - 0.5) * m_t.period_v());
        const Flat_torus_location found = locate(c, f);
        if(found.face >= 0) f = found;
        m_bucket[static_cast<std::size_t>(j * m_gu + i)] = f;
      }
  }

  Matrix m_u;
  Index_matrix m_F;
  Offset_matrix m_o;
  Torus_radii m_t;
  int m_sign = 1;
  std::size_t m_max_steps = 1000;
  Face_neighbor_matrix m_neighbor;
  Eigen::Matrix<int, Eigen::Dynamic, 6, Eigen::RowMajor> m_neighbor_shift;
  int m_gu = 1, m_gv = 1;
  std::vector<Flat_torus_location> m_bucket;
  mutable Walk_random m_random;
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FLAT_TORUS_POINT_LOCATION_H
