// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELLIPSOID_DOMAIN_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELLIPSOID_DOMAIN_H

// The sphere and ellipsoid domains of the density-equalizing engine
// (ALGORITHMS.md sections 7 and 9.1). The unit sphere is the ellipsoid with
// radii (1,1,1); the ellipsoid maps to the sphere by h(x,y,z) = (x/a, y/b, z/c),
// a linear map that neither creates nor removes fold-overs, so both repair a
// folding step the same way on the sphere: local untangling, then step
// halving; the landmark flow (LSDEM) first rebuilds the step in two
// stereographic charts by the Linear Beltrami Solver. That chart repair made
// every other flow slower and worse, and LSDEM needs it: without it its
// landmark error grows with the landmark weight (benchmark/RESULTS.md,
// "Session 6").

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/density_engine.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>

#include <algorithm>
#include <map>
#include <numeric>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Normalized chordal centroid of face k.
inline Eigen::Vector3d face_direction(const Matrix& S, const Index_matrix& F, Eigen::Index k)
{
  return (row3(S, F(k, 0)) + row3(S, F(k, 1)) + row3(S, F(k, 2))).normalized();
}

/// Fold-over repair of a map onto the unit sphere with respect to a bijective
/// reference map S_ref, through stereographic charts centred at a pole face.
class Spherical_chart_repair
{
public:
  Spherical_chart_repair(const Index_matrix& F, const Matrix& S_ref, double truncation,
                         const Spd_solver& prototype)
    : m_F(F), m_S_ref(S_ref), m_truncation(truncation), m_prototype(prototype.clone())
  {
    m_cap_size = std::max<Eigen::Index>(static_cast<Eigen::Index>(std::llround(S_ref.rows() / 10.)), 3);
  }

  const Matrix& reference() const { return m_S_ref; }
  void set_reference(const Matrix& S_ref) { m_S_ref = S_ref; m_charts.clear(); }

  /// One chart check-and-repair of s (unit sphere, n x 3) around `pole`. Returns
  /// false if the chart test still sees inverted faces after the LBS repair.
  bool repair_in_chart(Matrix& s, Eigen::Index pole, std::size_t& repairs)
  {
    Chart& c = chart(pole);
    const Eigen::Matrix3d Rr = rotation_to_north_pole(face_direction(s, m_F, pole));
    const Matrix D = to_planar(north_chart(s * Rr.transpose()));
    Complex_vector mu = beltrami_coefficient(c.D0, D, c.F);
    if(!has_chart_fold(mu, c)) return true;
    for(Eigen::Index k = 0; k < mu.size(); ++k)
      if(std::norm(mu[k]) >= 1) mu[k] *= (1 - m_truncation) / std::abs(mu[k]);
    Matrix w;
    ++repairs;
    if(!linear_beltrami_solve(c.D0, c.F, mu, c.in_cap, D, *c.solver, w, &c.assembler)) return false;
    if(has_chart_fold(beltrami_coefficient(c.D0, w, c.F), c)) return false;
    s = inverse_north_chart(to_complex(w)) * Rr; // rows: R_r^T applied to each point
    return true;
  }

  /// The face whose normalized centroid is farthest from that of `pole`.
  Eigen::Index antipodal_face(const Matrix& s, Eigen::Index pole) const
  {
    const Eigen::Vector3d c = face_direction(s, m_F, pole);
    Eigen::Index best = 0;
    double best_d = -1;
    for(Eigen::Index k = 0; k < m_F.rows(); ++k) {
      const double d = (face_direction(s, m_F, k) - c).squaredNorm();
      if(d > best_d) { best_d = d; best = k; }
    }
    return best;
  }

private:
  struct Chart
  {
    Index_matrix F;              // all faces but the pole face
    Matrix D0;                   // the reference map in this chart
    std::vector<char> in_cap;    // vertices pinned by the LBS: the cap around the puncture
    std::vector<char> face_in_cap;
    Face_block_assembler assembler;
    std::unique_ptr<Spd_solver> solver;
  };

  // Faces next to the puncture are excluded from the test: there the chart's
  // orientation is not the sphere's (ALGORITHMS.md 7, Notes).
  static bool has_chart_fold(const Complex_vector& mu, const Chart& c)
  {
    for(Eigen::Index k = 0; k < mu.size(); ++k)
      if(!c.face_in_cap[k] && std::norm(mu[k]) >= 1) return true; // |mu| >= 1 without a square root
    return false;
  }

  Chart& chart(Eigen::Index pole)
  {
    auto it = m_charts.find(pole);
    if(it != m_charts.end()) return it->second;
    if(m_charts.size() > 8) m_charts.clear(); // south poles move; keep the cache small
    Chart c;
    const Eigen::Index n = m_S_ref.rows();
    c.F.resize(m_F.rows() - 1, 3);
    for(Eigen::Index k = 0, j = 0; k < m_F.rows(); ++k)
      if(k != pole) c.F.row(j++) = m_F.row(k);
    const Eigen::Matrix3d Rs = rotation_to_north_pole(face_direction(m_S_ref, m_F, pole));
    const Matrix SS = m_S_ref * Rs.transpose();
    c.D0 = to_planar(north_chart(SS));
    std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(order.begin(), order.begin() + m_cap_size, order.end(),
                      [&](Eigen::Index i, Eigen::Index j) { return SS(i, 2) > SS(j, 2); });
    c.in_cap.assign(static_cast<std::size_t>(n), 0);
    for(Eigen::Index i = 0; i < m_cap_size; ++i) c.in_cap[order[i]] = 1;
    for(int a = 0; a < 3; ++a) c.in_cap[m_F(pole, a)] = 1;
    c.face_in_cap.assign(static_cast<std::size_t>(c.F.rows()), 0);
    for(Eigen::Index k = 0; k < c.F.rows(); ++k)
      c.face_in_cap[k] = c.in_cap[c.F(k, 0)] || c.in_cap[c.F(k, 1)] || c.in_cap[c.F(k, 2)];
    c.assembler.build(c.F, n);
    c.solver = m_prototype->clone();
    return m_charts.emplace(pole, std::move(c)).first->second;
  }

  const Index_matrix& m_F;
  Matrix m_S_ref;
  double m_truncation;
  std::unique_ptr<Spd_solver> m_prototype;
  Eigen::Index m_cap_size;
  std::map<Eigen::Index, Chart> m_charts;
};

/// Moves the corners of the faces that the exact test flags towards the
/// spherical centroid of their neighbours, a few rounds. The chart tests are
/// blind to folded slivers whose corners lie almost on one great circle; this
/// local untangling makes the map pass the exact test. Returns true on success.
inline bool untangle_on_sphere(Matrix& s, const Index_matrix& F, const std::vector<std::vector<Eigen::Index> >& vertex_faces)
{
  std::vector<Eigen::Index> flipped = inverted_faces_about_center(s, F);
  for(int round = 0; round < 20 && !flipped.empty(); ++round) {
    std::vector<Eigen::Index> moved;
    for(Eigen::Index k : flipped)
      for(int a = 0; a < 3; ++a) moved.push_back(F(k, a));
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    for(Eigen::Index v : moved) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for(Eigen::Index k : vertex_faces[v])
        for(int a = 0; a < 3; ++a)
          if(F(k, a) != v) c += row3(s, F(k, a));
      s.row(v) = c.normalized().transpose();
    }
    flipped = inverted_faces_about_center(s, F);
  }
  return flipped.empty();
}

inline std::vector<std::vector<Eigen::Index> > vertex_face_incidence(const Index_matrix& F, Eigen::Index n)
{
  std::vector<std::vector<Eigen::Index> > vf(static_cast<std::size_t>(n));
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) vf[F(k, a)].push_back(k);
  return vf;
}

/// The operators the density-equalizing engine needs on a triangle mesh in
/// R^3 (the map's own triangles): lumped mass, cotangent stiffness, area
/// averaging, gradient, density area. The face areas of the last map asked
/// about are kept: the engine (and EDEQ's energy) ask for several of these on
/// the same map.
class Surface_operators
{
public:
  Surface_operators(const Index_matrix& F, Eigen::Index n) : m_F(F), m_assembler(F, n), m_averaging(F, n) {}

  const Index_matrix& faces() const { return m_F; }
  const Face_block_assembler& assembler() const { return m_assembler; }

  Vector mass(const Matrix& x) const { return lumped_mass(areas(x), m_F, x.rows()); }
  Matrix stiffness_blocks(const Matrix& x) const { return cotangent_stiffness_blocks(x, m_F); }
  Sparse_matrix face_to_vertex(const Matrix& x) const { return m_averaging.assemble(areas(x)); }
  Matrix face_gradient(const Matrix& x, const Vector& g) const { return internal::face_gradient(x, m_F, g); }
  const Vector& density_area(const Matrix& x) const { return areas(x); }

private:
  const Vector& areas(const Matrix& x) const
  {
    if(m_area_map.rows() != x.rows() || m_area_map.cols() != x.cols() || m_area_map != x) {
      m_area_map = x;
      m_area = face_areas(x, m_F);
    }
    return m_area;
  }

  const Index_matrix& m_F;
  Face_block_assembler m_assembler;
  Face_to_vertex_assembler m_averaging;
  mutable Matrix m_area_map; // the map whose face areas m_area holds
  mutable Vector m_area;
};

/// Domain policy for the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (the unit
/// sphere when a = b = c = 1). Coordinates are 3D points on the domain; the
/// engine's operators are those of the map's triangles (Surface_operators).
class Ellipsoid_domain : public Surface_operators
{
public:
  /// `initial` is the bijective starting map on this ellipsoid; it is the
  /// reference of the chart repair, which runs only if `chart_repair` is true
  /// (the landmark flow; `truncation` is its |mu| truncation).
  Ellipsoid_domain(const Index_matrix& F, const Matrix& initial, const Eigen::Vector3d& radii, double truncation,
                   const Spd_solver& prototype, bool chart_repair = false)
    : Surface_operators(F, initial.rows()), m_F(F), m_radii(radii),
      m_repair(F, to_unit_sphere(initial, radii), truncation, prototype),
      m_vertex_faces(vertex_face_incidence(F, initial.rows())), m_chart_repair(chart_repair)
  {
    m_pole = most_regular_one_ring_face(m_repair.reference(), F);
  }

  Eigen::Index dimension() const { return 3; }
  const Eigen::Vector3d& radii() const { return m_radii; }
  Eigen::Index pole_face() const { return m_pole; }

  /// Removes the component along the outward normal (x/a^2, y/b^2, z/c^2).
  Matrix tangent_part(const Matrix& x, const Matrix& v) const
  {
    Matrix t = v;
    const Eigen::Vector3d inv2 = m_radii.cwiseProduct(m_radii).cwiseInverse();
    for(Eigen::Index i = 0; i < x.rows(); ++i) {
      const Eigen::Vector3d nrm = row3(x, i).cwiseProduct(inv2).normalized();
      t.row(i) -= (t.row(i).dot(nrm.transpose())) * nrm.transpose();
    }
    return t;
  }

  /// x_new = x + dt d on the domain. A step that folds (exact test) is
  /// repaired in two stereographic charts (LBS, only with `chart_repair`) and
  /// untangled (counted in `stats.repairs`); if that fails, dt is halved. A
  /// step that does not fold is taken as it is: the chart test
  /// also flags faces that are not inverted (a thin face whose circumcircle
  /// encloses the chart's projection point has the opposite orientation in the
  /// chart), and repairing those steps only slowed the flows down
  /// (benchmark/RESULTS.md, "Repairs and fallbacks").
  bool advance(const Matrix& x, const Matrix& d, double dt, Matrix& x_new, Step_statistics& stats)
  {
    for(; dt >= 1e-10; dt /= 2) {
      Matrix s = to_unit_sphere(x + dt * d, m_radii);
      bool ok = true;
      if(!inverted_faces_about_center(s, m_F).empty()) {
        if(m_chart_repair) {
          const Eigen::Index south = m_repair.antipodal_face(s, m_pole);
          ok = m_repair.repair_in_chart(s, m_pole, stats.repairs) && m_repair.repair_in_chart(s, south, stats.repairs);
        }
        if(ok && !inverted_faces_about_center(s, m_F).empty()) {
          ok = untangle_on_sphere(s, m_F, m_vertex_faces);
          ++stats.repairs;
        }
      }
      if(ok) {
        x_new = from_unit_sphere(s, m_radii);
        if(count_inverted_faces_about_center(x_new, m_F) == 0) return true;
      }
      ++stats.halvings;
    }
    return false;
  }

  std::size_t fold_overs(const Matrix& x) const { return count_inverted_faces_about_center(x, m_F); }

  /// Changes the radii (EDEQ): x is rescaled axis-wise onto the new ellipsoid;
  /// the repair reference, a map to the unit sphere, is unchanged.
  void set_radii(Matrix& x, const Eigen::Vector3d& radii)
  {
    for(int c = 0; c < 3; ++c) x.col(c) *= radii[c] / m_radii[c];
    m_radii = radii;
  }

  static Matrix to_unit_sphere(const Matrix& x, const Eigen::Vector3d& radii)
  {
    Matrix s = x;
    for(int c = 0; c < 3; ++c) s.col(c) /= radii[c];
    normalize_rows(s);
    return s;
  }
  static Matrix from_unit_sphere(const Matrix& s, const Eigen::Vector3d& radii)
  {
    Matrix x = s;
    for(int c = 0; c < 3; ++c) x.col(c) *= radii[c];
    return x;
  }

private:
  const Index_matrix& m_F;
  Eigen::Vector3d m_radii;
  Spherical_chart_repair m_repair;
  std::vector<std::vector<Eigen::Index> > m_vertex_faces;
  bool m_chart_repair;
  Eigen::Index m_pole = 0;
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELLIPSOID_DOMAIN_H
