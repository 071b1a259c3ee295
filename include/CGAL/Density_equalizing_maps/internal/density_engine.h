// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_DENSITY_ENGINE_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_DENSITY_ENGINE_H

// The one density-equalizing loop (papers 000, 001, 002): diffuse the density
// one implicit step, move the vertices with v = -grad(rho)/rho, keep them on the
// domain, repair fold-overs, re-couple the density to the new areas.
//
// What differs between the sphere, the ellipsoid and the flat torus is the
// *domain* policy (see sphere_domain.h for the reference model):
//   Eigen::Index dimension() const;
//   const Index_matrix& faces() const;
//   const Face_block_assembler& assembler() const;
//   Vector mass(const Matrix& x) const;
//   Matrix stiffness_blocks(const Matrix& x) const;
//   Sparse_matrix face_to_vertex(const Matrix& x) const;
//   Matrix face_gradient(const Matrix& x, const Vector& g) const;
//   Vector density_area(const Matrix& x) const;
//   Matrix tangent_part(const Matrix& x, const Matrix& v) const;
//   bool advance(const Matrix& x, const Matrix& d, double dt, Matrix& x_new, Step_statistics&);
//   std::size_t fold_overs(const Matrix& x) const;
// What differs between SDEM, LSDEM and EDEQ (extra energy terms, rotations,
// radius search, stopping quantity) is the *flow* policy; Density_flow below
// is plain density equalization.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>
#include <CGAL/Density_equalizing_maps/internal/stages.h>

#include <functional>
#include <limits>
#include <sstream>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

struct Step_statistics
{
  std::size_t repairs = 0;
  std::size_t halvings = 0;
};

struct Engine_options
{
  double time_step = 0.1;
  double tolerance = 1e-3;
  std::size_t max_iterations = 200;
  /// stop on sd/mean of the re-coupled density (paper 002) instead of the
  /// diffused one (the reference code of papers 000/001)
  bool stop_on_recoupled_density = false;
  std::function<bool(std::size_t, double)> progress;
  Stage_notifier stage;
};

struct Engine_result
{
  Termination termination = Termination::MAXIMUM_ITERATIONS;
  std::size_t iterations = 0;
  double initial_error = 0, final_error = 0;
  Step_statistics steps;
  std::string message;
  /// sd/mean of the re-coupled density on the initial and on the returned map
  double initial_density_error = 0, final_density_error = 0;
  /// the iteration whose map is returned (0: the initial map); below
  /// `iterations` when a run that did not converge returns its most uniform map
  std::size_t returned_iteration = 0;
};

/// A run of a flow with `returns_most_uniform_map` that did not converge
/// returns the map of lowest re-coupled sd/mean among the initial map and the
/// accepted steps: later steps of a stalling run can make the density less
/// uniform (a step population of ratio 1e4: sd/mean 1.30 -> 1.42 after 300
/// EDEM iterations, benchmark/RESULTS.md), and the user asked for a uniform
/// density, not for the last step. Keeps a copy of the best map.
struct Most_uniform_map
{
  Matrix map;
  double density_error = std::numeric_limits<double>::infinity(), stop_error = 0;
  std::size_t iteration = 0;
  void offer(const Matrix& x, double density_err, double stop_err, std::size_t it)
  {
    if(!(density_err < density_error)) return;
    map = x;
    density_error = density_err;
    stop_error = stop_err;
    iteration = it;
  }
};

/// Says in `res.message` when a run that did not converge returns a map whose
/// density is further from uniform than the start (the caller must not
/// present it as a success).
inline void note_density_regression(Engine_result& res)
{
  if(res.termination == Termination::CONVERGED) return;
  if(!(res.final_density_error > res.initial_density_error)) return;
  std::ostringstream o;
  o << (res.message.empty() ? "" : "; ") << "the density is less uniform than at the start (sd/mean "
    << res.initial_density_error << " -> " << res.final_density_error << ")";
  res.message += o.str();
}

/// The per-iteration quantities a flow may use.
struct Flow_state
{
  const Matrix& x;
  const Vector& diffused_density;
};

/// What the engine computes on an accepted map x: the face-to-vertex
/// averaging M, the re-coupled vertex density rho = M (population / |T|), its
/// implicit diffusion step rho+ and the vertex gradient M grad rho+ (the
/// velocity is its quotient by -rho+).
struct Map_diffusion
{
  Matrix map; // x
  Sparse_matrix face_to_vertex;
  Vector density, diffused;
  Matrix vertex_gradient;
};

/// Plain density equalization: direction = tangential part of -grad(rho)/rho.
struct Density_flow
{
  /// The flow's only objective is a uniform density, so a run that does not
  /// converge returns the most uniform of its maps (a flow that also moves
  /// landmarks or radii sets this to false: there the last map is returned).
  static constexpr bool returns_most_uniform_map = true;
  void before_step(Matrix&) {}
  /// A flow that has already evaluated the diffusion on exactly this map
  /// (EDEQ's energy does) hands it over instead of the engine redoing it.
  const Map_diffusion* diffusion_on(const Matrix&) const { return nullptr; }
  void direction(const Flow_state&, Matrix&) {}
  /// the stopping quantity, given the default one (sd/mean of the density)
  double stop_measure(const Matrix&, const Matrix&, double density_error) { return density_error; }
  template <class Domain>
  void after_step(std::size_t, Matrix&, Domain&) {}
};

/// The diffusion matrix A + dt L of the implicit step on the assembler's
/// pattern, from the domain's stiffness blocks. A domain that can fill it more
/// cheaply (into storage it keeps) overloads this function.
template <class Domain>
Sparse_matrix diffusion_matrix(Domain& domain, const Matrix& x, double dt, const Vector& A)
{
  return domain.assembler().assemble(dt * domain.stiffness_blocks(x), &A);
}

/// The re-coupled density on the map x: the face-to-vertex averaging M and
/// the vertex density rho = M (population / |T|), |T| the domain's density area.
template <class Domain>
void recoupled_density(const Domain& domain, const Matrix& x, const Vector& population, Sparse_matrix& M, Vector& rho)
{
  M = domain.face_to_vertex(x);
  rho = densities(population, domain.density_area(x), M).vertex;
}

/// One implicit diffusion step (A + dt L) rho+ = A rho on the map x, and the
/// vertex gradient M grad rho+ (the velocity is its quotient by -rho+). A
/// `guess` makes it a side solve started there (see Spd_solver::solve).
/// Returns false if the system could not be solved.
template <class Domain>
bool diffusion_step(Domain& domain, const Matrix& x, const Sparse_matrix& M, const Vector& rho, double dt,
                    Spd_solver& solver, Vector& rho_plus, Matrix& vertex_gradient, const Vector* guess = nullptr)
{
  const Vector A = domain.mass(x);
  const Sparse_matrix& K = diffusion_matrix(domain, x, dt, A);
  Matrix rhs = A.cwiseProduct(rho), solution;
  if(!solver.factor(K) || !(guess ? solver.solve(rhs, solution, Matrix(*guess)) : solver.solve(rhs, solution)))
    return false;
  rho_plus = solution.col(0);
  vertex_gradient = M * domain.face_gradient(x, rho_plus);
  return true;
}

/// Runs the loop on `x` (the initial map on the domain; on return the last
/// accepted, fold-over-free map).
template <class Domain, class Flow>
Engine_result run_density_equalization(Domain& domain, Flow& flow, Matrix& x, const Vector& population,
                                       const Engine_options& opt, Spd_solver& solver)
{
  const Index_matrix& F = domain.faces();
  const Eigen::Index n = x.rows();
  Engine_result res;

  // M is needed for the re-coupled density and, on the same map, for the
  // next velocity: compute it once per accepted map. (Flows' before_step
  // hooks are isometries of the domain, which leave M unchanged.)
  Sparse_matrix M;
  Vector rho;
  auto recouple = [&]() {
    if(const Map_diffusion* known = flow.diffusion_on(x)) {
      M = known->face_to_vertex;
      rho = known->density;
    } else {
      recoupled_density(domain, x, population, M, rho);
    }
  };
  recouple();
  res.initial_error = relative_sd(rho);
  res.initial_density_error = res.final_density_error = res.initial_error;
  double error = res.initial_error;
  res.final_error = error;
  if(error < opt.tolerance) { res.termination = Termination::CONVERGED; return res; }
  Most_uniform_map best;
  if(Flow::returns_most_uniform_map) best.offer(x, res.initial_density_error, error, 0);

  const double dt = opt.time_step;
  Matrix x_new;
  begin_stage(opt.stage, "density-equalizing iterations");
  while(true) {
    if(res.iterations >= opt.max_iterations) { res.termination = Termination::MAXIMUM_ITERATIONS; break; }
    const Matrix x_previous = x;
    flow.before_step(x);

    // implicit diffusion step (A + dt L) rho+ = A rho on the fixed pattern,
    // then the velocity -grad(rho+)/rho+ at the vertices, tangential part
    Vector rho_plus;
    Matrix v;
    if(const Map_diffusion* known = flow.diffusion_on(x)) {
      rho_plus = known->diffused;
      v = known->vertex_gradient;
    } else if(!diffusion_step(domain, x, M, rho, dt, solver, rho_plus, v)) {
      res.termination = Termination::STALLED;
      res.message = "the diffusion system could not be solved";
      x = x_previous;
      break;
    }
    for(Eigen::Index i = 0; i < n; ++i) v.row(i) /= -rho_plus[i];
    Matrix d = domain.tangent_part(x, v);
    flow.direction(Flow_state{x, rho_plus}, d);

    if(!domain.advance(x, d, dt, x_new, res.steps)) {
      res.termination = Termination::STALLED;
      res.message = "no fold-over-free step was found at iteration " + std::to_string(res.iterations + 1);
      x = x_previous;
      break;
    }
    x.swap(x_new);
    ++res.iterations;
    flow.after_step(res.iterations, x, domain);
    recouple();
    res.final_density_error = relative_sd(rho);
    error = flow.stop_measure(x_previous, x, opt.stop_on_recoupled_density ? relative_sd(rho) : relative_sd(rho_plus));
    res.final_error = error;
    res.returned_iteration = res.iterations;
    if(opt.progress && !opt.progress(res.iterations, error)) { res.termination = Termination::CANCELLED; break; }
    if(error < opt.tolerance) { res.termination = Termination::CONVERGED; break; }
    if(Flow::returns_most_uniform_map) best.offer(x, res.final_density_error, error, res.iterations);
  }
  if(Flow::returns_most_uniform_map && (res.termination == Termination::MAXIMUM_ITERATIONS ||
                                        res.termination == Termination::STALLED) &&
     best.density_error < res.final_density_error) {
    std::ostringstream o;
    o << (res.message.empty() ? "" : "; ") << "the most uniform map, that of iteration " << best.iteration << " of "
      << res.iterations << " (sd/mean of the density " << best.density_error << " where the last map has "
      << res.final_density_error << "), is returned";
    res.message += o.str();
    x = best.map;
    res.final_density_error = best.density_error;
    res.final_error = best.stop_error;
    res.returned_iteration = best.iteration;
  } else if(res.termination == Termination::STALLED && !res.message.empty() && res.message[0] == 'n') {
    res.message += "; the last bijective map is returned";
  }
  note_density_regression(res);
  return res;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_DENSITY_ENGINE_H
