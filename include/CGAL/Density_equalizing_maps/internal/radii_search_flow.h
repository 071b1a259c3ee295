// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_RADII_SEARCH_FLOW_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_RADII_SEARCH_FLOW_H

// EDEQ (paper 000 section 3.3, ALGORITHMS.md 9.2): the density flow on the
// ellipsoid, alternated every K iterations with a search over the radii (b, c)
// that lowers E = E_density + alpha E_BC; stops on the relative energy change.

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/ellipsoid_domain.h>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

struct Radii_search_flow
{
  /// the radii are part of the objective:
  /// a run that does not converge returns its last map (see Density_flow)
  static constexpr bool returns_most_uniform_map = false;
  const Index_matrix& F;
  Vector population;
  double alpha = 5;
  double time_step = 0.1;
  std::size_t search_period = 5;
  // diffusion on the accepted maps (a smooth sequence) and, as side systems
  // started from the current solution, on the rescaled maps of the radius search
  std::unique_ptr<Spd_solver> solver;
  Surface_operators operators; // the engine's, on the candidate maps
  Beltrami_magnitude_from_reference beltrami; // from r0, the starting map
  double energy_old = 0, energy_new = 0;
  std::size_t searches = 0;
  // the last energy evaluation on the accepted map: the engine's next step
  // needs the same operators, density, diffusion and gradient
  Map_diffusion accepted;

  Radii_search_flow(const Index_matrix& faces, const Vector& p, const Matrix& r0, double a, double dt,
                    const Spd_solver& prototype)
    : F(faces), population(p), alpha(a), time_step(dt), solver(prototype.clone()),
      operators(faces, r0.rows()), beltrami(r0, faces)
  {}

  /// E(r) = E_density(r) + E_BC(r) (the reference code's discretization):
  /// E_density = sum_i |M grad rho+|_i^2 / max(rho_V)^2, rho+ one diffusion step
  /// of the density on r; `d` receives the quantities on r. A candidate map
  /// starts its solver from `guess`, the diffused density of the accepted map
  /// it rescales.
  double density_energy(const Matrix& r, Map_diffusion& d, const Vector* guess = nullptr)
  {
    d.map = r;
    recoupled_density(operators, r, population, d.face_to_vertex, d.density);
    if(!diffusion_step(operators, r, d.face_to_vertex, d.density, time_step, *solver, d.diffused, d.vertex_gradient,
                       guess)) {
      d.map.resize(0, 3); // nothing to hand over to the engine
      return std::numeric_limits<double>::infinity();
    }
    const double m = d.density.maxCoeff();
    return d.vertex_gradient.rowwise().squaredNorm().sum() / (m * m);
  }

  /// E_BC = alpha sum_T |mu_T|^2, mu from the starting map r0 to r. No solve.
  double beltrami_energy(const Matrix& r) const { return alpha * beltrami(r).squaredNorm(); }

  double energy(const Matrix& r, Map_diffusion& d) { return density_energy(r, d) + beltrami_energy(r); }

  double energy(const Matrix& r)
  {
    Map_diffusion d;
    return energy(r, d);
  }

  /// E at the starting map (the reference of the first relative change).
  void start(const Matrix& x) { energy_old = energy(x, accepted); }

  const Map_diffusion* diffusion_on(const Matrix& x) const
  {
    return accepted.map.rows() == x.rows() && accepted.map == x ? &accepted : nullptr;
  }

  void before_step(Matrix&) {}
  void direction(const Flow_state&, Matrix&) {}

  /// Every K-th iteration: the best of the 9 radii (a, b + i delta, c + j delta),
  /// i, j in {-1, 0, 1}, delta = 0.1 * 0.9^m; a is kept (the scale is free).
  void after_step(std::size_t iteration, Matrix& x, Ellipsoid_domain& domain)
  {
    const std::size_t n = iteration - 1; // the reference's counter before its increment
    energy_new = energy(x, accepted);
    if(n < 2 || n % search_period != 0) return;
    ++searches;
    const double delta = std::max(0.1 * std::pow(0.9, double(n / search_period)), 1e-5);
    const Eigen::Vector3d r = domain.radii();
    Eigen::Vector3d best = r;
    double best_energy = energy_new;
    Map_diffusion trial, best_trial;
    const int order[9][2] = {{0, 0}, {0, -1}, {0, 1}, {-1, 0}, {1, 0}, {-1, -1}, {-1, 1}, {1, -1}, {1, 1}};
    for(const auto& o : order) {
      if(o[0] == 0 && o[1] == 0) continue;
      const Eigen::Vector3d c(r[0], r[1] + o[0] * delta, r[2] + o[1] * delta);
      if(c[1] < 0.05 * c[0] || c[2] < 0.05 * c[0]) continue;
      Matrix y = x;
      y.col(1) *= c[1] / r[1];
      y.col(2) *= c[2] / r[2];
      // E_density >= 0: a candidate whose Beltrami term alone does not beat
      // the best energy cannot win, and its diffusion solve is skipped. E_BC
      // dominates E and changes with the radii more than E_density does
      // (edeq_ellipsoid1 at the searches: E_BC 5.4e3 ... 5.8e3, E_density
      // 1e-5 ... 25), so most candidates end here (462 of 472); the choice
      // is exactly the full search's.
      const double e_bc = beltrami_energy(y);
      if(!(e_bc < best_energy)) continue;
      const double e = density_energy(y, trial, &accepted.diffused) + e_bc;
      if(e < best_energy) { best_energy = e; best = c; std::swap(trial, best_trial); }
    }
    if(best != r) {
      domain.set_radii(x, best); // x becomes the best candidate's map
      energy_new = best_energy;
      std::swap(accepted, best_trial);
    }
  }

  /// relative change of the energy
  double stop_measure(const Matrix&, const Matrix&, double)
  {
    const double change = std::abs(1 - energy_new / energy_old);
    energy_old = energy_new;
    return change;
  }
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_RADII_SEARCH_FLOW_H
