// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_TOROIDAL_DENSITY_EQUALIZING_MAP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_TOROIDAL_DENSITY_EQUALIZING_MAP_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/internal/engine_parameters.h>
#include <CGAL/Density_equalizing_maps/internal/torus_domain.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <array>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// The required `torus_radii` parameter, validated.
template <class NamedParameters>
Torus_radii torus_radii_from_parameters(const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  if constexpr(is_default_parameter<NamedParameters, internal_np::torus_radii_t>::value) {
    throw Invalid_input("the named parameter torus_radii (std::array<double,2>{R, r}, R > r > 0) is required");
  } else {
    const auto radii = get_parameter(np, internal_np::torus_radii);
    Torus_radii t;
    t.R = static_cast<double>(radii[0]);
    t.r = static_cast<double>(radii[1]);
    validate_torus_radii(t.R, t.r);
    return t;
  }
}

/// Writes the 3D torus points, and the optional flat-torus coordinates and halfedge offsets.
template <class TriangleMesh, class VertexPointOutMap, class NamedParameters>
void write_toroidal_outputs(const TriangleMesh& tm, const Mesh_arrays<TriangleMesh>& a, const Matrix& u,
                            const Offset_matrix& o, const Torus_radii& t, VertexPointOutMap out,
                            const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  write_points(a, torus_images(u, t), out);
  if constexpr(!is_default_parameter<NamedParameters, internal_np::flat_torus_coordinates_t>::value) {
    auto uv = get_parameter(np, internal_np::flat_torus_coordinates);
    typedef typename boost::property_traits<decltype(uv)>::value_type Point_2;
    for(std::size_t i = 0; i < a.vertices.size(); ++i) put(uv, a.vertices[i], Point_2(u(i, 0), u(i, 1)));
  }
  if constexpr(!is_default_parameter<NamedParameters, internal_np::flat_torus_offsets_t>::value) {
    auto om = get_parameter(np, internal_np::flat_torus_offsets);
    typedef typename boost::property_traits<decltype(om)>::value_type Offset;
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    for(std::size_t k = 0; k < a.faces.size(); ++k)
      for(auto h : halfedges_around_face(halfedge(a.faces[k], tm), tm)) {
        const int s = static_cast<int>(get(vim, source(h, tm)));
        int c = 0;
        while(a.F(Eigen::Index(k), c) != s) ++c;
        const int d = (c + 1) % 3;
        put(om, h, Offset{o(Eigen::Index(k), 2 * d) - o(Eigen::Index(k), 2 * c),
                          o(Eigen::Index(k), 2 * d + 1) - o(Eigen::Index(k), 2 * c + 1)});
      }
  }
}

inline void fill_toroidal_report(const Toroidal_run& run, const Torus_radii& t, Map_report& report)
{
  fill_report(run.engine, report);
  report.fold_overs = run.fold_overs;
  report.radii = {t.R, t.r};
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsTorus
/// \brief Computes the toroidal density-equalizing map (TDEM) of a closed
/// genus-one mesh lying on the torus with radii `R > r`.
///
/// The torus \f$ \phi(u,v) = ((R + r\cos\frac{v}{r})\cos\frac{u}{R},\ (R + r\cos\frac{v}{r})\sin\frac{u}{R},\ r\sin\frac{v}{r}) \f$
/// is flattened to the flat torus \f$ [0, 2\pi R) \times [-\pi r, \pi r) \f$ with periodic
/// identification. Following Yao and Choi (2025), the density (population / area of the
/// face's image on the 3D torus) diffuses implicitly on the flat torus and the vertices
/// move with the velocity \f$ -\nabla\rho/\rho \f$ until the density is uniform: faces with
/// a large population grow, others shrink. The mesh is never sliced: every vertex keeps
/// one point \f$ (u, v) \f$ and every halfedge an integer lattice offset, so there are no
/// seam copies and all operators are exactly periodic. Steps that invert a face are
/// repaired with a periodic Linear Beltrami Solver (or shortened), and the output is
/// certified with exact orientation predicates. A repair bounds the Beltrami
/// coefficient of every face by 0.9, the nearly flat faces included (the authors'
/// code truncates only the inverted ones, and the nearly flat ones then invert on the
/// next steps: twice as many repairs on rough populations).
///
/// The stopping test is sd/mean of the re-coupled vertex density (paper 002), with
/// tolerance 1e-2 by default: the paper's tables fit that value, and smaller tolerances
/// may not be reachable on rough populations (then `Map_report::termination` is
/// `Termination::MAXIMUM_ITERATIONS` and `final_error` says how far it got).
///
/// \tparam TriangleMesh a model of `FaceListGraph` (and `HalfedgeListGraph` if `flat_torus_offsets` is used)
/// \tparam VertexPointOutMap a writable vertex property map with 3D points as values
///
/// \param tm the input mesh: closed, manifold, connected, genus 1, with its vertices on the
///        torus \f$ (R, r) \f$ (within \f$ 10^{-3} r \f$) and embedded in it (no face inverted
///        in flat-torus coordinates; the faces may be oriented either way)
/// \param torus_map receives the image of each vertex on the torus
/// \param np named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{torus_radii}
///     \cgalParamDescription{the radii \f$ \{R, r\} \f$ of the torus, \f$ R > r > 0 \f$, both in [1e-100, 1e100], R / r at most 1e6 (required)}
///     \cgalParamType{`std::array<double,2>`}
///   \cgalParamNEnd
///   \cgalParamNBegin{face_population_map}
///     \cgalParamDescription{a readable face property map with the positive population of each face}
///     \cgalParamDefault{the face areas of the input}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_density_map}
///     \cgalParamDescription{alternatively, a positive density per vertex; the population of a face is its area times the mean density of its corners}
///     \cgalParamDefault{unused}
///   \cgalParamNEnd
///   \cgalParamNBegin{time_step}
///     \cgalParamDescription{the step \f$ \delta t \f$ of diffusion and advection}
///     \cgalParamType{double}
///     \cgalParamDefault{0.1}
///   \cgalParamNEnd
///   \cgalParamNBegin{stopping_tolerance}
///     \cgalParamDescription{stop when sd/mean of the re-coupled vertex density is below it}
///     \cgalParamType{double}
///     \cgalParamDefault{1e-2}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_iterations}
///     \cgalParamDescription{maximum number of iterations}
///     \cgalParamType{unsigned int}
///     \cgalParamDefault{1000}
///   \cgalParamNEnd
///   \cgalParamNBegin{progress_callback}
///     \cgalParamDescription{a callable `bool(std::size_t iteration, double error)` called once per iteration; returning `false` stops with the last bijective map (`Termination::CANCELLED`)}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{flat_torus_coordinates}
///     \cgalParamDescription{an optional writable vertex property map that receives the flat-torus point \f$ (u, v) \in [0, 2\pi R) \times [-\pi r, \pi r) \f$ of each vertex; its value type is a 2D point constructible from two doubles}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{flat_torus_offsets}
///     \cgalParamDescription{an optional writable halfedge property map that receives the integer lattice offset \f$ t_h = (t_u, t_v) \f$ of each halfedge \f$ h = (i \to j) \f$ of a face: the image of the halfedge in the flat torus is the segment from \f$ (u_i, v_i) \f$ to \f$ (u_j + 2\pi R\, t_u,\ v_j + 2\pi r\, t_v) \f$; \f$ t_{opposite(h)} = -t_h \f$ and the offsets sum to zero around every face. Value type: brace-constructible from two `int`s (e.g. `std::array<int,2>`, `std::pair<int,int>`)}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map, vertex_index_map}
///     \cgalParamDescription{as for `spherical_conformal_map()`}
///   \cgalParamNEnd
///   \cgalParamNBegin{stage_callback}
///     \cgalParamDescription{a callable `void(const std::string& stage)` called as each stage starts (validation,
///       harmonic map, south-chart LBS correction, Moebius area correction, the iterations, ...), so that a
///       progress display can name a long direct stage}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver}
///     \cgalParamDescription{a model of `SparseLinearAlgebraWithFactorTraits_d` for the SPD systems}
///     \cgalParamDefault{`Default_sparse_solver_traits` for the harmonic map, Eigen's simplicial
///       \f$ LDL^T \f$ factorization (`Eigen::SimplicialLDLT`) for the Beltrami repairs, which are
///       refactored inside the loop, and for the diffusion steps the warm-started
///       preconditioned conjugate gradients described in `spherical_density_equalizing_map()`,
///       here started from the quadratic extrapolation of the last three densities and
///       switching from Jacobi to the lagged factorization on strongly graded meshes.
///       If given, this solver is used for every system.}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 1 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre the vertices of `tm` lie on the torus of revolution of the radii `R > r > 0` given with
///      `torus_radii` (checked up to a tolerance)
/// \pre the population (`face_population_map`) or density (`vertex_density_map`), when given, is
///      positive and finite on every face or vertex (checked)
/// \returns a `Map_report`: `iterations`, `termination`, `initial_error` and `final_error`
///   (sd/mean of the re-coupled vertex density), `repairs` and `step_halvings`,
///   `fold_overs` (exact count of faces inverted in the flat-torus layout) and `radii` = {R, r}
/// \throws Invalid_input if the mesh is not a valid closed genus-one surface on the torus, if the
///   radii or the population are invalid; nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report toroidal_density_equalizing_map(const TriangleMesh& tm, VertexPointOutMap torus_map,
                                           const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  const internal::Torus_radii t = internal::torus_radii_from_parameters(np);
  const auto a = internal::closed_surface_arrays(tm, np, 0);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const internal::Engine_options options = internal::engine_options_from_parameters(np, 0.1, 1e-2, 1000);
  internal::Matrix u;
  internal::begin_stage(options.stage, "flat-torus layout of the input");
  const internal::Offset_matrix o = internal::offsets_from_torus_positions(a.input_positions(), a.F, t, u);
  std::string why;
  const int orientation = internal::layout_orientation(u, a.F, o, t, why);
  if(orientation == 0) throw Invalid_input(why);
  const auto repair_solver = internal::loop_solver_from_parameters(np);
  const auto diffusion_solver = internal::diffusion_solver_from_parameters(np, internal::toroidal_diffusion_tuning());
  const internal::Toroidal_run run = internal::run_toroidal_density_equalization(
    a.F, u, o, t, orientation, population, options, *repair_solver, diffusion_solver.get());
  Map_report report;
  internal::fill_toroidal_report(run, t, report);
  internal::write_toroidal_outputs(tm, a, run.u, run.offsets, t, torus_map, np);
  return report;
}

/// \ingroup PkgDensityEqualizingMapsTorus
/// \brief Maps any closed genus-one mesh onto the torus with radii `R > r`, with a
/// prescribed area change (area-preserving by default).
///
/// Two homology generators are taken from `cut_edges`, or found automatically
/// (tree-cotree decomposition). A seamless periodic harmonic map onto the flat torus is
/// computed from them (cotangent weights; uniform weights if the cotangent map folds, which
/// by the toroidal Tutte theorem is an embedding), with the period basis Lagrange-reduced
/// with respect to the Dirichlet energy so that the conformally longer direction wraps
/// around \f$ 2\pi R \f$; the map is then translated along \f$ v \f$ to the position that
/// best matches the population on the 3D torus, and equalized with
/// `toroidal_density_equalizing_map()`'s flow (TDEM). Thanks to the reduction and the
/// translation search the result does not depend on which valid cut is used.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam VertexPointOutMap a writable vertex property map with 3D points as values
///
/// \param tm the input mesh: closed, manifold, connected, genus 1, no degenerate face
/// \param torus_map receives the image of each vertex on the torus
/// \param np named parameters: those of `toroidal_density_equalizing_map()` (`torus_radii` is required), plus
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{cut_edges}
///     \cgalParamDescription{edges (pairs of vertices) forming two closed loops that meet only at one base vertex where they cross; duplicates are ignored. They only fix the topology of the initial map.}
///     \cgalParamType{`std::vector<std::pair<vertex_descriptor, vertex_descriptor> >`}
///     \cgalParamDefault{loops from a tree-cotree decomposition rooted at the first vertex}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// `face_population_map` defaults to the face areas of the input, which makes the map area-preserving.
///
/// \pre `tm` is a closed, connected, manifold triangle mesh of genus 1 without degenerate faces
///      (checked: `Invalid_input` otherwise)
/// \pre the radii satisfy `R > r > 0`, and the cut edges, when given, are edges of `tm` that form
///      two generating loops (checked)
/// \returns a `Map_report` as for `toroidal_density_equalizing_map()`; `used_tutte_fallback`
///   tells whether the initial harmonic map needed uniform weights
/// \throws Invalid_input if the mesh is not a valid closed genus-one surface, if the radii, the
///   population or the cut edges are invalid (out-of-range vertex, not an edge, not two loops
///   crossing once at one base vertex); nothing is written then.
/// \throws Algorithm_failure if the initial periodic harmonic map could not be computed (a linear
///   solve failed); nothing is written then.
template <class TriangleMesh, class VertexPointOutMap,
          class NamedParameters = parameters::Default_named_parameters>
Map_report toroidal_parameterization(const TriangleMesh& tm, VertexPointOutMap torus_map,
                                     const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  const internal::Torus_radii t = internal::torus_radii_from_parameters(np);
  const auto a = internal::closed_surface_arrays(tm, np, 0);
  const internal::Vector population = internal::population_from_parameters(a, np);
  const internal::Engine_options options = internal::engine_options_from_parameters(np, 0.1, 1e-2, 1000);
  const Eigen::Index n = a.X.rows();
  const internal::Halfedge_table halfedges(a.F, n);
  internal::Halfedge_offsets cocycles;
  int base = 0;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::cut_edges_t>::value) {
    const auto& cut = get_parameter(np, internal_np::cut_edges);
    auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
    std::vector<std::pair<int, int> > pairs;
    pairs.reserve(cut.size());
    for(const auto& e : cut) {
      const auto i = get(vim, e.first), j = get(vim, e.second);
      pairs.emplace_back(i < std::size_t(n) ? int(i) : -1, j < std::size_t(n) ? int(j) : -1);
    }
    cocycles = internal::cut_edge_cocycles(a.F, halfedges, n, pairs, base);
  } else {
    cocycles = internal::tree_cotree_cocycles(a.F, halfedges, n, 0);
  }
  const auto solver = internal::solver_from_parameters(np);
  internal::begin_stage(options.stage, "periodic harmonic map onto the flat torus");
  internal::Flat_torus_parameterization initial;
  if(!internal::flat_torus_harmonic_map(a.X, a.F, cocycles, base, t, population, *solver, initial))
    throw Algorithm_failure("the initial periodic harmonic map onto the flat torus could not be computed "
                            "(linear solver failure or non-finite result)");
  const auto repair_solver = internal::loop_solver_from_parameters(np);
  const auto diffusion_solver = internal::diffusion_solver_from_parameters(np, internal::toroidal_diffusion_tuning());
  const internal::Toroidal_run run = internal::run_toroidal_density_equalization(
    a.F, initial.u, initial.offsets, t, 1, population, options, *repair_solver, diffusion_solver.get());
  Map_report report;
  internal::fill_toroidal_report(run, t, report);
  report.used_tutte_fallback = initial.used_uniform_weights;
  if(initial.used_uniform_weights)
    report.add_fallback("initial map: uniform (Tutte) weights instead of the cotangent weights (the harmonic map folded)");
  internal::write_toroidal_outputs(tm, a, run.u, run.offsets, t, torus_map, np);
  return report;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_TOROIDAL_DENSITY_EQUALIZING_MAP_H
