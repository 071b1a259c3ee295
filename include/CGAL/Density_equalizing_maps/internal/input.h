// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_INPUT_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_INPUT_H

// What every public function does first: read the named parameters shared by
// all methods, extract the arrays and validate them.

#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/bisection_cholesky.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>
#include <CGAL/Density_equalizing_maps/internal/stages.h>
#include <CGAL/Density_equalizing_maps/internal/validation.h>

#include <CGAL/boost/graph/named_params_helper.h>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// The arrays of `tm` through the `vertex_point_map` and `vertex_index_map` of
/// `np` (CGAL's defaults otherwise), as they are: no validation, no scaling.
/// The callers that need no closed surface (measures, point transfer, the
/// globe of a cartogram) check what they need themselves.
template <class TriangleMesh, class NamedParameters>
Mesh_arrays<TriangleMesh> unvalidated_arrays(const TriangleMesh& tm, const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, tm));
  return to_arrays(tm, vpm, CGAL::get_initialized_vertex_index_map(tm, np));
}

/// The arrays of a validated closed surface of the given Euler characteristic.
template <class TriangleMesh, class NamedParameters>
Mesh_arrays<TriangleMesh> closed_surface_arrays(const TriangleMesh& tm, const NamedParameters& np, long euler)
{
  begin_stage(stage_notifier_from_parameters(np), "validation");
  Mesh_arrays<TriangleMesh> a = unvalidated_arrays(tm, np);
  normalize_scale(a); // before any length or area is computed, validation included
  validate_closed_surface(a.X, a.F, euler, euler == 2 ? 4 : 7);
  // The genus-0 methods build maps whose faces are oriented outward. For an
  // input oriented inward they work on the reversed triangles, so that the
  // output keeps the input's orientation (an orientation-preserving map, with
  // no fold-over relative to the input) instead of being its mirror image.
  if(euler == 2 && enclosed_volume_sign(a.X, a.F) < 0) a.F.col(1).swap(a.F.col(2));
  return a;
}

/// The linear solver chosen with `sparse_linear_solver` (default: Default_sparse_solver_traits).
template <class NamedParameters>
std::unique_ptr<Spd_solver> solver_from_parameters(const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef typename internal_np::Lookup_named_param_def<internal_np::sparse_linear_solver_t, NamedParameters,
                                                       Default_sparse_solver_traits>::type Traits;
  return make_spd_solver(choose_parameter<Traits>(get_parameter(np, internal_np::sparse_linear_solver)));
}

/// The simplicial LDL^T of the diffusion solver's lagged factorization
/// (CHOLMOD's when the package is built with it, else Eigen's).
#ifdef CGAL_DEM_USE_CHOLMOD
typedef CGAL::Eigen_solver_traits<Eigen::CholmodSimplicialLDLT<Sparse_matrix> > Simplicial_ldlt_traits;
#else
typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Sparse_matrix> > Simplicial_ldlt_traits;
#endif

/// The solver of the systems refactored inside an iteration loop (the
/// toroidal Beltrami repairs): the user's `sparse_linear_solver` if one is
/// given, else Eigen's simplicial LDL^T. Measured on the 3,200 unknowns of
/// tdem_torus_4 (40 repairs): CHOLMOD's supernodal factorization costs the
/// same CPU time as its simplicial one but starts OpenMP threads (it asks for
/// 4) that spin-wait between regions and stall on a loaded machine; Eigen's
/// factorization is cheaper still (0.39 -> 0.375 s CPU for the whole run).
template <class NamedParameters>
std::unique_ptr<Spd_solver> loop_solver_from_parameters(const NamedParameters& np)
{
  using CGAL::parameters::is_default_parameter;
  if constexpr(is_default_parameter<NamedParameters, internal_np::sparse_linear_solver_t>::value)
    return make_spd_solver(CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Sparse_matrix> >());
  else
    return solver_from_parameters(np);
}

/// The lagged factorization of the diffusion solver: a simplicial LDL^T below
/// `supernodal_diffusion_from` unknowns, where its triangular solves (applied
/// several times per iteration) are the cheapest, and the default supernodal
/// Cholesky factorization from there on, where the simplicial factorization
/// becomes the cost of the whole run. Measured (one thread, medians of 5
/// interleaved runs, benchmark/RESULTS.md): SDEM on a 100K-face sphere 5.5 ->
/// 2.9 s, on 1M faces 96 -> 42 s; below about 15,000 unknowns the two are
/// within the noise or the simplicial one is faster (tdem_torus_4, 3,200
/// unknowns: 0.55 against 0.71 s).
constexpr Eigen::Index supernodal_diffusion_from = 15000;

/// From this many unknowns on, the lagged factorization is split in two
/// halves by a separator (Bisection_cholesky): with parallel loops the
/// halves are solved on two cores, and factored on two when the BLAS may be
/// called from two threads at once. The preconditioner's triangular solves
/// are most of a large flow's time (TDEM, 1M faces: 263 solves of about
/// 0.1 s). Measured on 1M faces (benchmark/RESULTS.md, "The lagged
/// factorization in two halves"): TDEM 42-44 -> 37 s with Debian's
/// single-threaded OpenBLAS, 43-44 -> 33-34 s with its multithreaded build
/// held to one thread per call. A solve on one thread costs about a quarter
/// more, hence only the largest systems. (The direct maps' systems, factored
/// once, gain nothing from it and would pass 1 KB per face at 1M faces.)
constexpr Eigen::Index bisection_diffusion_from = 200000;

inline std::unique_ptr<Spd_solver> make_lagged_diffusion_factorization()
{
#ifdef CGAL_DEM_USE_CHOLMOD
  std::unique_ptr<Spd_solver> supernodal(new Size_dispatched_spd_solver(
    make_default_spd_solver(), std::unique_ptr<Spd_solver>(new Bisection_cholesky()), bisection_diffusion_from));
  return std::unique_ptr<Spd_solver>(new Size_dispatched_spd_solver(
    make_spd_solver(Simplicial_ldlt_traits()), std::move(supernodal), supernodal_diffusion_from));
#else
  return make_spd_solver(Simplicial_ldlt_traits()); // Eigen has no supernodal factorization
#endif
}

/// The solver of the engine's diffusion systems: by default warm-started
/// preconditioned conjugate gradients (`Diffusion_pcg_solver`) whose lagged
/// factorization is `make_lagged_diffusion_factorization()` (rarely refactored
/// but applied several times per iteration); the user's `sparse_linear_solver`
/// if one is given (then `tuning` is unused).
template <class NamedParameters>
std::unique_ptr<Spd_solver> diffusion_solver_from_parameters(
  const NamedParameters& np, const Diffusion_pcg_solver::Tuning& tuning = Diffusion_pcg_solver::Tuning())
{
  using CGAL::parameters::is_default_parameter;
  if constexpr(is_default_parameter<NamedParameters, internal_np::sparse_linear_solver_t>::value) {
    std::unique_ptr<Diffusion_pcg_solver> pcg(new Diffusion_pcg_solver(make_lagged_diffusion_factorization()));
    pcg->tune(tuning);
    return pcg;
  }
  else
    return solver_from_parameters(np);
}

/// The per-face population from `face_population_map`, or from
/// `vertex_density_map` (averaged on faces, times the face area), or the face
/// area of the input (area-preserving). Validated.
template <class TriangleMesh, class NamedParameters>
Vector population_from_parameters(const Mesh_arrays<TriangleMesh>& a, const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  Vector p;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::face_population_t>::value) {
    p = read_face_values(a, get_parameter(np, internal_np::face_population));
    validate_population(p, a.F.rows());
  } else if constexpr(!is_default_parameter<NamedParameters, internal_np::vertex_density_t>::value) {
    const Vector rho = read_vertex_values(a, get_parameter(np, internal_np::vertex_density));
    for(Eigen::Index i = 0; i < rho.size(); ++i)
      if(!std::isfinite(rho[i]) || !(rho[i] > 0))
        throw Invalid_input("non-positive or non-finite vertex density at vertex " + std::to_string(i));
    const Vector area = face_areas(a.X, a.F);
    p.resize(a.F.rows());
    for(Eigen::Index k = 0; k < a.F.rows(); ++k)
      p[k] = area[k] * (rho[a.F(k, 0)] + rho[a.F(k, 1)] + rho[a.F(k, 2)]) / 3.;
  } else {
    p = face_areas(a.X, a.F);
  }
  return p;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_INPUT_H
