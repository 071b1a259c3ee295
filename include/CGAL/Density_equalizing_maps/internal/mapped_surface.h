// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MAPPED_SURFACE_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MAPPED_SURFACE_H

// A surface together with its fold-free map onto a domain (unit sphere,
// ellipsoid, torus), on index arrays: the core of point transfer
// (point_transfer.h) and of the applications (remeshing, registration).
//
// pull back:    domain point q -> face T of the image containing q, barycentric
//               coordinates l in f(T) -> sum_a l_a x_a on the input surface;
// push forward: (T, l) on the input surface -> the domain point of sum_a l_a f_a
//               (radial projection onto the sphere or ellipsoid; phi of the
//               flat-torus layout point on the torus).
// The barycentric coordinates of the pull-back are those of the ray through q
// (sphere, ellipsoid) or of q in the layout (torus), so push forward inverts
// pull back exactly up to round-off, and conversely.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/flat_torus_point_location.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/torus_domain.h>
#include <CGAL/Density_equalizing_maps/internal/validation.h>

#include <memory>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

enum class Domain_kind { SPHERE, ELLIPSOID, TORUS };

/// The domain of a map: kind and radii ((a, b, c) of the ellipsoid, (R, r) of the torus).
struct Domain_shape
{
  Domain_kind kind = Domain_kind::SPHERE;
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();
  Torus_radii torus() const { Torus_radii t; t.R = radii[0]; t.r = radii[1]; return t; }
  long euler_characteristic() const { return kind == Domain_kind::TORUS ? 0 : 2; }
};

/// Largest relative deviation of the mapped points from the domain that is
/// accepted: the maps of the package put their vertices on the domain to
/// round-off; anything further is a different domain (wrong radii, a map of
/// another method, a mesh that is not a map at all).
constexpr double domain_tolerance = 1e-6;

/// A location on the mapped surface: face, barycentric coordinates in the
/// face's corner order, and for the torus the lattice translate of its layout.
struct Surface_point
{
  Eigen::Index face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Constant(1. / 3);
  std::array<int, 2> shift{{0, 0}};
};

class Mapped_surface
{
public:
  /// \pre X, F a closed surface (validated here, with the domain's Euler characteristic);
  /// Y the images of the vertices. Throws Invalid_input if the images are not on the
  /// domain or the map is not fold-free (exact predicates), naming the problem.
  Mapped_surface(const Matrix& X, const Index_matrix& F, const Matrix& Y, const Domain_shape& d)
    : m_X(X), m_F(F), m_domain(d)
  {
    validate_closed_surface(X, F, d.euler_characteristic(), d.kind == Domain_kind::TORUS ? 7 : 4);
    if(Y.rows() != X.rows() || Y.cols() != 3) throw Invalid_input("the map must give one 3D point per vertex");
    for(Eigen::Index i = 0; i < Y.rows(); ++i)
      if(!Y.row(i).allFinite()) throw Invalid_input("the map has a non-finite point at vertex " + std::to_string(i));
    if(d.kind == Domain_kind::TORUS) prepare_torus(Y);
    else prepare_star_shaped(Y);
  }

  const Domain_shape& domain() const { return m_domain; }
  /// Exact orientation shared by all image faces: about the origin (sphere,
  /// ellipsoid) or in the flat-torus layout (torus), +1 or -1.
  int orientation() const { return m_orientation; }
  const Matrix& positions() const { return m_X; }
  const Index_matrix& faces() const { return m_F; }

  /// The location of the domain point q (sphere, ellipsoid: of the ray
  /// through q; torus: of the torus coordinates of q), walking from `hint`
  /// (ignored if its face is negative). Face -1 if q has no location (q = 0,
  /// q on the torus axis or non-finite).
  Surface_point locate(const Eigen::Vector3d& q, const Surface_point& hint = Surface_point()) const
  {
    Surface_point s;
    if(m_domain.kind == Domain_kind::TORUS) {
      if(!q.allFinite() || (q.x() == 0 && q.y() == 0)) return s;
      return locate_flat(torus_coordinates(q, m_domain.radii[0], m_domain.radii[1]), hint);
    }
    s.face = m_sphere->locate(q, hint.face);
    if(s.face >= 0) s.barycentric = m_sphere->barycentric(s.face, q);
    return s;
  }

  /// Torus only: the location of the flat-torus point w (any translate).
  Surface_point locate_flat(const Eigen::Vector2d& w, const Surface_point& hint = Surface_point()) const
  {
    Surface_point s;
    // the translate of w nearest to the hint's triangle (a walk from the hint
    // then stays short across the seams of the period cell), else the one in the cell
    Eigen::Vector2d c = m_torus->reduce_to_cell(w);
    if(hint.face >= 0) {
      const Eigen::Vector2d p0 = m_torus->corner(hint.face, 0, hint.shift);
      const Torus_radii& t = m_torus->radii();
      c.x() += t.period_u() * std::round((p0.x() - c.x()) / t.period_u());
      c.y() += t.period_v() * std::round((p0.y() - c.y()) / t.period_v());
    }
    Flat_torus_location start;
    start.face = hint.face;
    start.shift = hint.shift;
    const Flat_torus_location f = m_torus->locate(c, start);
    s.face = f.face;
    s.shift = f.shift;
    if(f.face >= 0) s.barycentric = m_torus->barycentric(f, c);
    return s;
  }

  /// A good hint for q given the previous query and its answer: the previous
  /// answer if q is within a bucket of it, else none (the bucket grid starts).
  Surface_point hint_after(const Eigen::Vector3d& previous_query, const Surface_point& previous_answer,
                           const Eigen::Vector3d& q) const
  {
    if(previous_answer.face < 0) return Surface_point();
    double reach;
    // one bucket, at the shortest 3D scale of the domain (the inner equator of the torus)
    if(m_domain.kind == Domain_kind::TORUS)
      reach = m_torus->bucket_size() * (m_domain.radii[0] - m_domain.radii[1]) / m_domain.radii[0];
    else reach = m_sphere->bucket_angle() * m_domain.radii.minCoeff();
    return (q - previous_query).norm() < reach ? previous_answer : Surface_point();
  }

  /// The point of the input surface at s.
  Eigen::Vector3d surface_point(const Surface_point& s) const
  {
    const Eigen::Vector3d& l = s.barycentric;
    return l[0] * row_vector3(m_X, m_F(s.face, 0)) + l[1] * row_vector3(m_X, m_F(s.face, 1)) +
           l[2] * row_vector3(m_X, m_F(s.face, 2));
  }

  /// The domain point of s (push forward).
  Eigen::Vector3d domain_point(const Surface_point& s) const
  {
    const Eigen::Vector3d& l = s.barycentric;
    if(m_domain.kind == Domain_kind::TORUS) {
      Eigen::Vector2d w = Eigen::Vector2d::Zero();
      for(int a = 0; a < 3; ++a) w += l[a] * m_torus->corner(s.face, a, {{0, 0}});
      return torus_point(w.x(), w.y(), m_domain.radii[0], m_domain.radii[1]);
    }
    Eigen::Vector3d y = Eigen::Vector3d::Zero();
    for(int a = 0; a < 3; ++a) y += l[a] * m_sphere->corner(s.face, a);
    return y / ellipsoid_level(y, m_domain.radii);
  }

  /// Pull back of many domain points (rows of Q), in the given order; each walk
  /// starts from the previous answer when it is close. Rows without location
  /// are NaN; `unlocated` counts them.
  Matrix pull_back(const Matrix& Q, std::size_t& unlocated) const
  {
    Matrix out(Q.rows(), 3);
    unlocated = 0;
    Surface_point last;
    Eigen::Vector3d last_q = Eigen::Vector3d::Zero();
    for(Eigen::Index i = 0; i < Q.rows(); ++i) {
      const Eigen::Vector3d q = row_vector3(Q, i);
      const Surface_point s = locate(q, hint_after(last_q, last, q));
      if(s.face < 0) { out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN()); ++unlocated; continue; }
      out.row(i) = surface_point(s).transpose();
      last = s;
      last_q = q;
    }
    return out;
  }

  /// Pull back of the vertices Q of a mesh with faces G (a domain mesh):
  /// visited breadth-first, each walk starting at the location of the
  /// vertex's parent, a neighbour on the domain. Rows without location are NaN.
  Matrix pull_back_mesh_vertices(const Matrix& Q, const Index_matrix& G, std::size_t& unlocated) const
  {
    std::vector<Eigen::Index> order, parent;
    breadth_first_vertex_order(G, Q.rows(), order, parent);
    std::vector<Surface_point> located(static_cast<std::size_t>(Q.rows()));
    Matrix out(Q.rows(), 3);
    unlocated = 0;
    for(const Eigen::Index i : order) {
      const Surface_point hint = parent[i] >= 0 ? located[parent[i]] : Surface_point();
      const Surface_point s = locate(row_vector3(Q, i), hint);
      located[i] = s;
      if(s.face < 0) { out.row(i).setConstant(std::numeric_limits<double>::quiet_NaN()); ++unlocated; continue; }
      out.row(i) = surface_point(s).transpose();
    }
    return out;
  }

private:
  void prepare_star_shaped(const Matrix& Y)
  {
    if(m_domain.kind == Domain_kind::SPHERE) m_domain.radii = Eigen::Vector3d::Ones();
    const double deviation = max_ellipsoid_deviation(Y, m_domain.radii);
    if(!(deviation <= domain_tolerance))
      throw Invalid_input(std::string("the map is not onto the ") +
                          (m_domain.kind == Domain_kind::SPHERE ? "unit sphere" : "ellipsoid with the given radii") +
                          " (relative deviation " + std::to_string(deviation) + ")");
    const int sign = enclosed_volume_sign(m_X, m_F);
    const std::size_t folds = count_fold_overs_about_center(Y, m_F, sign, Eigen::Vector3d::Zero());
    if(folds > 0)
      throw Invalid_input("the map is not fold-free: " + std::to_string(folds) +
                          " faces are inverted or degenerate on the domain (exact predicates)");
    m_orientation = sign;
    m_sphere.reset(new Spherical_point_locator(Y, m_F, sign));
  }

  void prepare_torus(const Matrix& Y)
  {
    const Torus_radii t = m_domain.torus();
    validate_torus_radii(t.R, t.r);
    for(Eigen::Index i = 0; i < Y.rows(); ++i) {
      const Eigen::Vector3d p = row_vector3(Y, i);
      const double d = std::hypot(std::hypot(p.x(), p.y()) - t.R, p.z());
      if(!(std::abs(d - t.r) <= domain_tolerance * t.R))
        throw Invalid_input("the map is not onto the torus with R = " + std::to_string(t.R) + ", r = " +
                            std::to_string(t.r) + " (vertex " + std::to_string(i) + " is at distance " +
                            std::to_string(d) + " from the tube axis)");
    }
    Matrix u;
    const Offset_matrix o = offsets_from_torus_positions(Y, m_F, t, u);
    std::string why;
    const int sign = layout_orientation(u, m_F, o, t, why);
    if(sign == 0) throw Invalid_input("the map is not fold-free: " + why);
    m_orientation = sign;
    m_torus.reset(new Flat_torus_point_locator(u, m_F, o, t, sign));
  }

  Matrix m_X;
  Index_matrix m_F;
  Domain_shape m_domain;
  int m_orientation = 1;
  std::shared_ptr<const Spherical_point_locator> m_sphere;
  std::shared_ptr<const Flat_torus_point_locator> m_torus;
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MAPPED_SURFACE_H
