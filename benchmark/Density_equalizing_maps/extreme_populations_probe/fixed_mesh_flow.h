// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FIXED_MESH_FLOW_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FIXED_MESH_FLOW_H

// The diffusion flow of Gastner and Newman on a *fixed* mesh of the domain,
// for densities of high contrast (ALGORITHMS.md section 7, "High contrast").
//
// Why: the engine's loop diffuses the density on the *moving* map and
// re-couples it to the map's areas at every step. With a contrast of 100 or
// more between regions, the region of low density must shrink by that factor
// and its faces are squeezed across the front of the diffusing density; the
// vertex velocities then differ by O(1) between neighbours, a face becomes
// flat (three corners on one great circle) and folds at any step length, and
// the cotangent operators of the next step are those of a degenerate mesh
// (benchmark/RESULTS.md, "Extreme populations (issue 14 item 2)").
//
// Here the density is diffused on the initial map R, which stays as it is
// (one good mesh, a well-conditioned system): rho(t) solves the heat equation
// on R from the initial density, and the vertices of the map move through the
// field v = -grad(rho)/rho, interpolated linearly in the face of R that
// contains them (exact point location). In the continuum this is the flow
// whose end map equalizes the density (the density of the moving map is
// rho(t) at its points). EXPERIMENT, NOT IN THE LIBRARY: measured on
// icosphere(3) with a step population of ratio 100 it stays fold-free but
// leaves the low-density region at 4.5-10 % of the sphere where 1.8 % is
// needed (re-coupled sd/mean 1.26 -> 0.27-0.53), see benchmark/RESULTS.md.

#include <CGAL/Density_equalizing_maps/internal/density_engine.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/point_location.h>

#include <algorithm>
#include <cmath>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

struct Fixed_mesh_flow_options
{
  /// run only when max/min of the initial face density exceeds this
  double contrast = 10;
  /// stop when sd/mean of the diffused density on R is below this
  double tolerance = 1e-4;
  /// first diffusion step; each next one is `growth` times longer, at most `max_time_step`
  double first_time_step = 1e-3, growth = 1.5, max_time_step = 0.5;
  /// at most this many diffusion steps
  std::size_t max_steps = 100;
  /// a vertex moves at most this fraction of R's mean edge length per step
  double max_move = 0.5;
  bool trapezoid = false;
};

struct Fixed_mesh_flow_result
{
  bool ran = false, completed = false;
  double contrast = 1;
  std::size_t diffusion_steps = 0, moves = 0, halvings = 0;
  double final_error = 0; // sd/mean of the diffused density on R at the end
  std::string message;
};

/// max/min of the face density population / area on the map x.
template <class Domain>
double density_contrast(const Domain& domain, const Matrix& x, const Vector& population)
{
  const Vector rho = population.cwiseQuotient(domain.density_area(x));
  return rho.maxCoeff() / rho.minCoeff();
}

/// The linear interpolation, at each point of p, of the vertex field V of
/// the fixed mesh R (`locator` over R), each walk started at the face found
/// for that point the last time (`face`, updated).
inline Matrix interpolate_vertex_field(const Spherical_point_locator& locator, const Index_matrix& F,
                                       const Matrix& V, const Matrix& p, std::vector<Eigen::Index>& face)
{
  Matrix out(p.rows(), 3);
  for(Eigen::Index j = 0; j < p.rows(); ++j) {
    const Eigen::Vector3d q = row3(p, j);
    Eigen::Index f = locator.locate(q, face[j]);
    if(f < 0) f = locator.locate(q);
    face[j] = f;
    const Eigen::Vector3d b = locator.barycentric(f, q);
    out.row(j) = b[0] * V.row(F(f, 0)) + b[1] * V.row(F(f, 1)) + b[2] * V.row(F(f, 2));
  }
  return out;
}

/// Moves the fold-free map x (on the sphere or an ellipsoid centred at the
/// origin, see Ellipsoid_domain) by the Gastner-Newman flow of the density
/// population / area diffusing on the fixed mesh x itself. x stays fold-free
/// (every move is checked with exact predicates and halved if it folds).
template <class Domain>
Fixed_mesh_flow_result fixed_mesh_flow(Domain& domain, Matrix& x, const Vector& population, Spd_solver& solver,
                                       const Fixed_mesh_flow_options& opt)
{
  Fixed_mesh_flow_result res;
  res.contrast = density_contrast(domain, x, population);
  if(!(res.contrast > opt.contrast)) return res;
  res.ran = true;

  const Index_matrix& F = domain.faces();
  const Matrix R = x;
  const Eigen::Index n = R.rows();
  const Spherical_point_locator locator(R, F, 1);
  Sparse_matrix M;
  Vector rho;
  recoupled_density(domain, R, population, M, rho);
  rho /= rho.mean();
  const Vector A = domain.mass(R);
  const Matrix stiffness = domain.stiffness_blocks(R);
  double edge = 0;
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) edge += (R.row(F(k, a)) - R.row(F(k, (a + 1) % 3))).norm();
  edge /= 3. * double(F.rows());
  const double max_move = opt.max_move * edge;

  std::vector<Eigen::Index> face(static_cast<std::size_t>(n), -1);
  Matrix p = R, p_new;
  double tau = opt.first_time_step;
  double h = tau; // the last accepted move length (time)
  Matrix V_previous;
  for(; res.diffusion_steps < opt.max_steps; ++res.diffusion_steps) {
    // implicit step of the heat equation on R: (A + tau L) rho+ = A rho
    const Sparse_matrix K = domain.assembler().assemble(tau * stiffness, &A);
    Matrix rhs = A.cwiseProduct(rho), solution;
    if(!solver.factor(K) || !solver.solve(rhs, solution)) {
      res.message = "the diffusion system on the fixed mesh could not be solved";
      break;
    }
    const Vector rho_plus = solution.col(0);
    if(!(rho_plus.minCoeff() > 0)) {
      res.message = "the diffused density on the fixed mesh is not positive";
      break;
    }
    // the velocity field of this time interval, at R's vertices
    Matrix V = M * domain.face_gradient(R, rho_plus);
    for(Eigen::Index i = 0; i < n; ++i) V.row(i) /= -rho_plus[i];
    V = domain.tangent_part(R, V);
    if(opt.trapezoid) {
      if(V_previous.rows() == 0) {
        V_previous = M * domain.face_gradient(R, rho);
        for(Eigen::Index i = 0; i < n; ++i) V_previous.row(i) /= -rho[i];
        V_previous = domain.tangent_part(R, V_previous);
      }
      const Matrix V_end = V;
      V = 0.5 * (V + V_previous);
      V_previous = V_end;
    }

    // move the map's vertices through it for the time tau
    bool stuck = false;
    for(double remaining = tau; remaining > 0 && !stuck;) {
      const Matrix D = domain.tangent_part(p, interpolate_vertex_field(locator, F, V, p, face));
      const double speed = D.rowwise().norm().maxCoeff();
      h = std::min({remaining, 2 * h, speed > 0 ? max_move / speed : remaining});
      while(!domain.plain_step(p, D, h, p_new)) {
        h /= 2;
        ++res.halvings;
        if(h < 1e-12 * tau) { stuck = true; break; }
      }
      if(stuck) break;
      p.swap(p_new);
      remaining -= h;
      ++res.moves;
    }
    if(stuck) {
      res.message = "no fold-over-free move was found";
      break;
    }
    rho = rho_plus;
    res.final_error = relative_sd(rho);
#ifdef DEM_PROBE
    if(std::getenv("DEM_TRACE")) {
      const Vector a0 = domain.density_area(R), a1 = domain.density_area(p);
      const Vector d0 = population.cwiseQuotient(a0);
      const double med = std::sqrt(d0.maxCoeff() * d0.minCoeff());
      double low0 = 0, low1 = 0;
      for(Eigen::Index k = 0; k < F.rows(); ++k) if(d0[k] < med) { low0 += a0[k]; low1 += a1[k]; }
      const Vector d1 = population.cwiseQuotient(a1);
      std::cerr << "  pre step " << res.diffusion_steps << " tau " << tau << " moves " << res.moves << " err(R) " << res.final_error
                << " Vmax " << V.rowwise().norm().maxCoeff() << " low area " << low0 / a0.sum() << " -> " << low1 / a1.sum()
                << " face sd/mean " << relative_sd(d1) << " rho+ range " << rho_plus.minCoeff() << " " << rho_plus.maxCoeff() << "\n";
    }
#endif
    if(res.final_error < opt.tolerance) { res.completed = true; ++res.diffusion_steps; break; }
    tau = std::min(opt.max_time_step, tau * opt.growth);
  }
  x = p;
  return res;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FIXED_MESH_FLOW_H
