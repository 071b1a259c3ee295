// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_REMESHING_H
#define CGAL_DENSITY_EQUALIZING_MAPS_REMESHING_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/point_transfer.h>
#include <CGAL/Density_equalizing_maps/internal/uniform_domain_mesh.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsRemeshing
/// What `remesh_through_map()` built.
struct Remeshing_report
{
  std::size_t vertices = 0; ///< vertices of the remeshed surface (those of the domain mesh)
  std::size_t faces = 0;    ///< faces of the remeshed surface
  /// \f$ \delta_{size} \f$ and \f$ \delta_{shape} \f$ of the remeshed surface (see `mesh_uniformity()`)
  double delta_size = 0, delta_shape = 0;
  /// the same measures of the domain mesh that was pulled back
  double domain_delta_size = 0, domain_delta_shape = 0;
};

namespace internal {

/// The uniform mesh of a domain with about n vertices; on the torus the
/// valence-6 lattice or the relaxed mesh.
inline Triangle_arrays uniform_domain_mesh(const Domain_shape& d, Eigen::Index n, bool lattice = true)
{
  if(d.kind == Domain_kind::TORUS)
    return lattice ? uniform_torus_mesh(n, d.radii[0], d.radii[1]) : relaxed_torus_mesh(n, d.radii[0], d.radii[1]);
  return uniform_ellipsoid_mesh(n, d.kind == Domain_kind::SPHERE ? Eigen::Vector3d::Ones().eval() : d.radii);
}

inline void check_requested_vertices(std::size_t n)
{
  if(n < 12)
    throw Invalid_input("at least 12 vertices must be requested for a remeshed surface (got " + std::to_string(n) + ")");
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsRemeshing
/// \brief Builds a near-uniform triangle mesh of a domain: the unit sphere, an
/// ellipsoid or a torus.
///
/// Sphere and ellipsoid, coarse to fine: a mesh of about 300 vertices (the
/// icosahedral geodesic sphere completed by edge splits, mapped to the ellipsoid by
/// \f$ (x, y, z) \mapsto (a x, b y, c z) \f$) is relaxed by DistMesh (repulsive edge
/// springs, projection onto the surface, intrinsic Delaunay edge flips), then refined
/// by one to three levels of face subdivision (each face split into \f$ k^2 \f$,
/// \f$ k \le 6 \f$), each followed by a few local DistMesh steps; every face stays
/// positively oriented about the origin (exact). On the unit sphere, the geodesic
/// sphere of frequency \f$ f \f$ itself when its \f$ 10 f^2 + 2 \f$ vertices are
/// within 1 % of `number_of_vertices` (\f$ f \le 100 \f$).
/// Measured for 100 to 100,000 vertices on the sphere and the ellipsoids 1:1:2, 1:2:3
/// and 1:1:5: \f$ \delta_{shape} \le 0.046 \f$ and \f$ \delta_{size} \le 0.67 \f$
/// (see `mesh_uniformity()`).
///
/// Torus, two meshes (named parameter `torus_lattice`):
/// - the lattice (default): \f$ n_u \times n_v \f$ vertices, all of valence 6, rows
///   spaced so that \f$ \delta_{size} \le 0.69 \f$ with the most regular shapes that
///   allows; a grid-like mesh, but on a torus with \f$ R / r = 3 \f$ equal sizes and
///   equilateral shapes exclude each other in a valence-6 lattice (\f$ \delta_{shape} \f$
///   0.072 at \f$ \delta_{size} \f$ 0.69);
/// - the relaxed mesh (`torus_lattice(false)`): that lattice, coarse, relaxed by DistMesh in
///   the flat-torus coordinates and refined as on the ellipsoid; its edge flips create
///   vertices of valence 5 and 7, and it reaches \f$ \delta_{shape} \le 0.042 \f$ at
///   \f$ \delta_{size} \le 0.5 \f$ on the torus (3, 1) (measured, 100 to 100,000 vertices).
///
/// The vertex count is within 1 % of `number_of_vertices` for \f$ n \ge 100 \f$.
///
/// \tparam Domain `Unit_sphere_domain`, `Ellipsoid_domain` or `Torus_domain`
/// \tparam PolygonMesh a model of `MutableFaceGraph`
/// \param domain the domain with its radii
/// \param number_of_vertices the number of vertices wanted (at least 12; 16 for the torus)
/// \param out receives the mesh (its previous content is removed), faces oriented outward
/// \param np optional named parameters:
///   `torus_lattice(bool)`: on the torus, `true` (default) for the valence-6 lattice,
///   `false` for the relaxed mesh; ignored on the sphere and the ellipsoids
/// \throws Invalid_input if the radii are invalid or too few vertices are requested; `out` is unchanged then
template <class Domain, class PolygonMesh, class NamedParameters = parameters::Default_named_parameters>
void uniform_domain_mesh(const Domain& domain, std::size_t number_of_vertices, PolygonMesh& out,
                         const NamedParameters& np = parameters::default_values())
{
  internal::check_requested_vertices(number_of_vertices);
  const bool lattice = parameters::choose_parameter(parameters::get_parameter(np, internal_np::torus_lattice), true);
  const internal::Triangle_arrays t =
    internal::uniform_domain_mesh(internal::domain_shape(domain), Eigen::Index(number_of_vertices), lattice);
  internal::write_triangle_mesh(t.X, t.F, out);
}

/// \ingroup PkgDensityEqualizingMapsRemeshing
/// \brief Remeshes a closed surface through its map onto a domain: a near-uniform mesh of
/// the domain is pulled back to the surface.
///
/// The domain mesh is `uniform_domain_mesh()` with `number_of_vertices` vertices; each
/// of its vertices is located in the image of the map with exact predicates and replaced
/// by the corresponding point of the input surface (see `Point_transfer`). The result has
/// the connectivity of the domain mesh, hence the genus of the domain, and every vertex
/// on a face of the input. Its triangles have the sizes that the map gives to the domain
/// mesh's triangles on the way back:
/// - through a conformal map (`spherical_conformal_map()`, `ellipsoidal_conformal_map()`)
///   the shapes stay regular but the sizes follow the map's area distortion;
/// - through an area-preserving density-equalizing map (`spherical_density_equalizing_map()`,
///   `ellipsoidal_density_equalizing_map()`, `toroidal_parameterization()` with the default
///   population) the sizes become uniform on the surface;
/// - through a density-equalizing map with a population, a region of the surface gets a
///   share of the vertices proportional to its population (adaptive remeshing): density
///   equalization enlarges a region's image in proportion to its population, and the
///   domain mesh is uniform there.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam MappedPointMap a model of `ReadablePropertyMap` from vertices to 3D points
/// \tparam Domain `Unit_sphere_domain`, `Ellipsoid_domain` or `Torus_domain`
/// \tparam PolygonMesh a model of `MutableFaceGraph` (may not be the type of `tm`)
///
/// \param tm the input mesh: closed, manifold, connected, genus 0 (sphere, ellipsoid) or 1 (torus)
/// \param mapped the image of every vertex on `domain` (the output of one of the maps)
/// \param domain the domain of the map, with its radii
/// \param number_of_vertices the number of vertices of the result (within 1 %, see
///        `uniform_domain_mesh()`); at least 12
/// \param out receives the remeshed surface (previous content removed); it must not be `tm`
/// \param np optional named parameters: `vertex_point_map` and `vertex_index_map` of `tm`,
///        as for `Point_transfer`; `torus_lattice(bool)` as for `uniform_domain_mesh()`
///        (default `true`: through a toroidal map every vertex of the result has valence 6)
///
/// \pre `mapped` is a fold-free map onto `domain`: checked
/// \returns the size of the result and the uniformity measures of the result and of the domain mesh
/// \throws Invalid_input if fewer than 12 vertices are requested, if `tm` is not a valid closed
///   surface of the domain's genus, if the mapped points are not on `domain`, or if the map
///   folds (exact count); `out` is unchanged then.
template <class TriangleMesh, class MappedPointMap, class Domain, class PolygonMesh,
          class NamedParameters = parameters::Default_named_parameters>
Remeshing_report remesh_through_map(const TriangleMesh& tm, MappedPointMap mapped, const Domain& domain,
                                    std::size_t number_of_vertices, PolygonMesh& out,
                                    const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  internal::check_requested_vertices(number_of_vertices);
  const internal::Domain_shape shape = internal::domain_shape(domain);
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, tm));
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  const auto a = internal::to_arrays(tm, vpm, vim);
  const internal::Mapped_surface surface(a.X, a.F, internal::read_points(a, mapped), shape);
  const bool lattice = choose_parameter(get_parameter(np, internal_np::torus_lattice), true);
  internal::Triangle_arrays d = internal::uniform_domain_mesh(shape, Eigen::Index(number_of_vertices), lattice);
  // the domain mesh is oriented outward; pulled back through a map whose images
  // are oriented the other way it would reverse the input's orientation
  if(surface.orientation() < 0) d.F.col(1).swap(d.F.col(2));
  std::size_t unlocated = 0;
  const internal::Matrix Y = surface.pull_back_mesh_vertices(d.X, d.F, unlocated);
  if(unlocated > 0) // impossible for a validated fold-free map: never return a partial mesh
    throw std::logic_error("remesh_through_map: " + std::to_string(unlocated) + " domain vertices were not located");
  Remeshing_report r;
  r.vertices = std::size_t(Y.rows());
  r.faces = std::size_t(d.F.rows());
  const internal::Mesh_uniformity q = internal::mesh_uniformity(Y, d.F), qd = internal::mesh_uniformity(d.X, d.F);
  r.delta_size = q.delta_size;
  r.delta_shape = q.delta_shape;
  r.domain_delta_size = qd.delta_size;
  r.domain_delta_shape = qd.delta_shape;
  internal::write_triangle_mesh(Y, d.F, out);
  return r;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_REMESHING_H
