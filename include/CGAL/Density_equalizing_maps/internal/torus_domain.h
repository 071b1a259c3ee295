// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_TORUS_DOMAIN_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_TORUS_DOMAIN_H

// The flat torus as a domain of the density-equalizing engine (TDEM, paper
// 002; ALGORITHMS.md 10.2 and 10.5). The state x is n x 2: one point (u, v)
// per vertex of the closed mesh; the per-corner lattice offsets live here and
// stay fixed during a run (no wrap inside the loop, so the engine's copies of
// x are always consistent with them; the caller wraps at the end).
//
// Diffusion, gradients, velocity and face-to-vertex averaging use the planar
// layout; only the density carries the torus geometry, through the chordal
// area of phi(layout). The velocity is planar already (tangent_part is the
// identity). A step that inverts layout triangles is repaired by the periodic
// Linear Beltrami Solver, or the step is halved.

#include <CGAL/Density_equalizing_maps/internal/density_engine.h>
#include <CGAL/Density_equalizing_maps/internal/flat_torus.h>


#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {



class Torus_domain
{
public:
  /// `u0` and `offsets` are the initial (fold-free) layout; every layout
  /// triangle must have the orientation `orientation` (+1 or -1).
  Torus_domain(const Index_matrix& F, const Matrix& u0, const Offset_matrix& offsets, const Torus_radii& radii,
               int orientation, std::unique_ptr<Spd_solver> repair_solver)
    : m_F(F), m_Fu(unrolled_faces(F.rows())), m_offsets(offsets), m_radii(radii), m_orientation(orientation),
      m_assembler(F, u0.rows()), m_repair_solver(std::move(repair_solver))
  {
    m_P0 = unrolled_layout(u0, F, offsets, radii);
    m_averaging.build(F, u0.rows());
  }

  Eigen::Index dimension() const { return 2; }
  const Index_matrix& faces() const { return m_F; }
  const Face_block_assembler& assembler() const { return m_assembler; }
  const Offset_matrix& offsets() const { return m_offsets; }
  const Torus_radii& radii() const { return m_radii; }
  int orientation() const { return m_orientation; }

  /// The layout of x with the domain's offsets (3m x 2, see flat_torus.h).
  const Matrix& layout(const Matrix& x) const { return cached(x).P; }

  Vector mass(const Matrix& x) const { return lumped_mass(cached(x).area, m_F, x.rows()); }

  /// Cotangent stiffness blocks of the layout (planar: the unrolled faces),
  /// scaled by `scale`, in storage kept across iterations.
  const Matrix& scaled_stiffness_blocks(const Matrix& x, double scale) const
  {
    cotangent_stiffness_blocks(cached(x).P, m_Fu, scale, m_blocks);
    return m_blocks;
  }

  Matrix stiffness_blocks(const Matrix& x) const { return scaled_stiffness_blocks(x, 1.); }

  /// A + dt L assembled into storage kept across iterations.
  const Sparse_matrix& diffusion_matrix(const Matrix& x, double dt, const Vector& A)
  {
    m_assembler.assemble(scaled_stiffness_blocks(x, dt), &A, m_diffusion_matrix);
    return m_diffusion_matrix;
  }

  /// Area-weighted averaging M (n x m): the pattern (column k holds the three
  /// corners of face k, sorted) is built once, only the weights change.
  const Sparse_matrix& face_to_vertex(const Matrix& x) const
  {
    m_averaging.assemble(cached(x).area, m_face_to_vertex);
    return m_face_to_vertex;
  }

  /// Gradient on the layout: corner points from the unrolled faces, values from the mesh's.
  Matrix face_gradient(const Matrix& x, const Vector& g) const
  {
    return planar_face_gradient(cached(x).P, m_Fu, m_F, g);
  }

  /// Chordal area of the image of each face on the torus (paper eq. 11); the
  /// images go to storage kept across iterations.
  Vector density_area(const Matrix& x) const
  {
    torus_images(x, m_radii, m_torus_points);
    return face_areas(m_torus_points, m_F);
  }

  Matrix tangent_part(const Matrix&, const Matrix& v) const { return v; }

  /// Faces whose exact layout orientation differs from the initial one.
  std::vector<char> flagged_faces(const Matrix& x, std::size_t& count) const
  {
    const std::vector<int> s = layout_orientations(layout(x));
    std::vector<char> flagged(s.size(), 0);
    count = 0;
    for(std::size_t k = 0; k < s.size(); ++k)
      if(s[k] != m_orientation) { flagged[k] = 1; ++count; }
    return flagged;
  }

  std::size_t fold_overs(const Matrix& x) const { return count_layout_fold_overs(layout(x), m_orientation); }

  /// x_new = x + dt d; if layout triangles flip, periodic LBS repair (at most
  /// `max_repair_solves` solves, |mu| truncated to 0.9, see repair()), else
  /// halve dt. Returns false if no fold-free step was found.
  template <class Statistics>
  bool advance(const Matrix& x, const Matrix& d, double dt, Matrix& x_new, Statistics& stats)
  {
    for(int halving = 0; halving <= m_max_halvings; ++halving) {
      Matrix y = x + dt * d;
      std::size_t count = 0;
      std::vector<char> flagged = flagged_faces(y, count);
      if(count == 0) { x_new.swap(y); return true; }
      for(int solve = 0; solve < m_max_repair_solves && count > 0; ++solve) {
        if(!repair(y, flagged)) break;
        ++stats.repairs;
        flagged = flagged_faces(y, count);
      }
      if(count == 0) { x_new.swap(y); return true; }
      dt *= 0.5;
      ++stats.halvings;
    }
    return false;
  }

  /// One periodic LBS solve: mu = BC(initial layout -> layout of y), with
  /// |mu| truncated to 0.9 on the flagged faces and on every face above 0.9,
  /// one vertex on no flagged face pinned where it is. The reference truncates
  /// only the flipped faces (|mu| > 1) and leaves the nearly flat ones
  /// (0.9 < |mu| <= 1) as they are, and those flip on one of the next steps:
  /// a repair that bounds every face, as the other LBS users of the package
  /// do, costs the same solve and halves the repairs (tdem_torus_4: 42 -> 19,
  /// with the same iteration count and final density; benchmark/RESULTS.md).
  bool repair(Matrix& y, const std::vector<char>& flagged)
  {
    Complex_vector mu = beltrami_coefficient(m_P0, layout(y), m_Fu);
    for(Eigen::Index k = 0; k < mu.size(); ++k)
      if(flagged[k] || !(std::abs(mu[k]) <= m_truncation)) {
        const double a = std::abs(mu[k]);
        mu[k] = a > 0 && std::isfinite(a) ? mu[k] * (m_truncation / a) : Complex(m_truncation, 0);
      }
    std::vector<char> on_flagged(static_cast<std::size_t>(y.rows()), 0);
    for(Eigen::Index k = 0; k < m_F.rows(); ++k)
      if(flagged[k])
        for(int c = 0; c < 3; ++c) on_flagged[m_F(k, c)] = 1;
    int pin = 0;
    while(pin < y.rows() && on_flagged[pin]) ++pin;
    if(pin == y.rows()) return false;
    Matrix w;
    if(!periodic_linear_beltrami_solve(m_P0, m_Fu, m_F, m_offsets, m_radii, mu, pin, y.row(pin).transpose(),
                                       m_assembler, *m_repair_solver, w))
      return false;
    y = w;
    return true;
  }

  void set_max_repair_solves(int n) { m_max_repair_solves = n; }

private:
  struct Layout_cache
  {
    Matrix x, P; // the state and its layout
    Vector area; // unsigned layout areas
  };
  /// Layout and areas of x, recomputed only when x changes (the engine asks
  /// for several operators on the same state), in place.
  const Layout_cache& cached(const Matrix& x) const
  {
    Layout_cache& c = m_cache;
    if(c.x.rows() == x.rows() && c.x.cols() == x.cols() && c.x == x) return c;
    c.x = x;
    const Eigen::Index m = m_F.rows();
    const double pu = m_radii.period_u(), pv = m_radii.period_v();
    c.P.resize(3 * m, 2);
    c.area.resize(m);
    for(Eigen::Index k = 0; k < m; ++k) {
      for(int a = 0; a < 3; ++a) {
        c.P(3 * k + a, 0) = x(m_F(k, a), 0) + pu * m_offsets(k, 2 * a);
        c.P(3 * k + a, 1) = x(m_F(k, a), 1) + pv * m_offsets(k, 2 * a + 1);
      }
      const double ax = c.P(3 * k + 1, 0) - c.P(3 * k, 0), ay = c.P(3 * k + 1, 1) - c.P(3 * k, 1);
      const double bx = c.P(3 * k + 2, 0) - c.P(3 * k, 0), by = c.P(3 * k + 2, 1) - c.P(3 * k, 1);
      c.area[k] = 0.5 * std::abs(ax * by - ay * bx);
    }
    return c;
  }

  mutable Layout_cache m_cache;
  // per-iteration storage, reused
  mutable Matrix m_blocks, m_torus_points;
  Face_to_vertex_assembler m_averaging;
  mutable Sparse_matrix m_face_to_vertex;
  Sparse_matrix m_diffusion_matrix;
  Index_matrix m_F, m_Fu;
  Offset_matrix m_offsets;
  Torus_radii m_radii;
  int m_orientation;
  Face_block_assembler m_assembler;
  std::unique_ptr<Spd_solver> m_repair_solver;
  Matrix m_P0;
  int m_max_repair_solves = 5;
  int m_max_halvings = 20;
  double m_truncation = 0.9;
};

/// The engine's diffusion matrix, filled in the domain's own storage.
inline const Sparse_matrix& diffusion_matrix(Torus_domain& domain, const Matrix& x, double dt, const Vector& A)
{
  return domain.diffusion_matrix(x, dt, A);
}

/// How the default diffusion solver treats TDEM's systems: the torus domain
/// assembles them with a Face_block_assembler (exactly symmetric, so fused
/// Jacobi steps apply); the density evolves smoothly between repairs
/// (quadratic extrapolation: tdem_torus_5_1 21 -> 12 CG steps per solve);
/// rough populations grade the mesh so strongly that Jacobi needs ~70 steps
/// (tdem_torus_4) where the lagged factorization needs ~7. On 3,200 unknowns
/// a refactorization costs about 25 of those steps; refactoring after 8
/// instead of 12 was the fastest (tdem_torus_4: 0.272 -> 0.260 s; 6, 10
/// and 16: 0.267, 0.261, 0.295 s).
inline Diffusion_pcg_solver::Tuning toroidal_diffusion_tuning()
{
  Diffusion_pcg_solver::Tuning t;
  t.fused_jacobi = true;
  t.quadratic_extrapolation = true;
  t.jacobi_step_limit = 40;
  t.refactor_steps = 8;
  return t;
}

/// Outcome of a TDEM run on the flat torus.
struct Toroidal_run
{
  Engine_result engine;
  std::size_t fold_overs = 0;
  Matrix u;              // final flat-torus coordinates, wrapped into the cell
  Offset_matrix offsets; // matching corner offsets
};

/// Orientation (+1 / -1) of a flat-torus layout that covers the torus once with
/// every triangle oriented alike; 0 otherwise (`what` then says why).
inline int layout_orientation(const Matrix& u, const Index_matrix& F, const Offset_matrix& o, const Torus_radii& t,
                              std::string& what)
{
  const Matrix P = unrolled_layout(u, F, o, t);
  const double total = layout_signed_areas(P).sum();
  if(!(std::abs(std::abs(total) - t.cell_area()) <= 1e-6 * t.cell_area())) {
    what = "the mesh does not cover the torus exactly once (total signed flat-torus area " + std::to_string(total) +
           ", period cell area " + std::to_string(t.cell_area()) + ")";
    return 0;
  }
  const int s = total > 0 ? 1 : -1;
  const std::size_t folds = count_layout_fold_overs(P, s);
  if(folds > 0) {
    what = "the mesh is not embedded in the torus: " + std::to_string(folds) +
           " faces are inverted or degenerate in flat-torus coordinates";
    return 0;
  }
  return s;
}

/// TDEM (paper 002) on the flat torus with the engine of density_engine.h:
/// stops on sd/mean of the re-coupled vertex density; the result is wrapped
/// into the cell [0, 2 pi R) x [-pi r, pi r).
inline Toroidal_run run_toroidal_density_equalization(const Index_matrix& F, const Matrix& u0, const Offset_matrix& o0,
                                                      const Torus_radii& t, int orientation, const Vector& population,
                                                      Engine_options options, Spd_solver& solver,
                                                      Spd_solver* diffusion_solver = nullptr)
{
  Toroidal_run run;
  run.u = u0;
  Torus_domain domain(F, u0, o0, t, orientation, solver.clone());
  Density_flow flow;
  options.stop_on_recoupled_density = true;
  run.engine = run_density_equalization(domain, flow, run.u, population, options,
                                        diffusion_solver ? *diffusion_solver : solver);
  run.offsets = o0;
  wrap_into_cell(run.u, F, run.offsets, t);
  // certify the output as written (after the wrap), with exact predicates
  run.fold_overs = count_layout_fold_overs(unrolled_layout(run.u, F, run.offsets, t), orientation);
  return run;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_TORUS_DOMAIN_H
