// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_GLOBE_CARTOGRAM_H
#define CGAL_DENSITY_EQUALIZING_MAPS_GLOBE_CARTOGRAM_H

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/parameters.h>
#include <CGAL/Density_equalizing_maps/point_transfer.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/internal/region_area_correction.h>
#include <CGAL/Density_equalizing_maps/internal/spherical_regions.h>
#include <CGAL/Density_equalizing_maps/internal/uniform_domain_mesh.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <boost/property_map/function_property_map.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsCartogram
/// The population of the faces of a globe mesh from regions and their values
/// (`face_populations_from_regions()`). Faces are in the order of `faces(tm)`.
struct Region_populations
{
  /// per face: the regions it meets, each with the fraction of the face's area it covers
  std::vector<std::vector<std::pair<std::size_t, double> > > face_parts;
  std::vector<double> face_area;       ///< area of each (flat) face
  std::vector<double> face_population; ///< the population of each face
  std::vector<double> region_area;     ///< area of each region on the mesh (sum of its parts)
  double land_area = 0;                ///< sum of `region_area`
  double sea_area = 0;                 ///< area of the parts of faces no region covers
  double sea_density = 0;              ///< the population per unit area given to the sea
  double mean_land_density = 0;        ///< total value / `land_area`
  double overlapping_area = 0;         ///< area covered by more than one region (0 for a clean input)
  /// (face, polygon) overlaps that were asked exact but sampled instead, because a ring edge
  /// runs along an edge of the face (`overlap_subdivision(0)`; 0 when every overlap is exact)
  std::size_t sampled_overlaps = 0;
};

/// \ingroup PkgDensityEqualizingMapsCartogram
/// The result of `globe_cartogram()`, per region in the order of the input regions.
struct Globe_cartogram_report
{
  std::vector<double> value_share;    ///< value / total value
  /// area / land area on the deformed globe, of the region's boundary carried through the map
  /// (`push_forward_region_boundaries()`, measured as spherical polygons)
  std::vector<double> area_share;
  std::vector<double> relative_error; ///< |area_share / value_share - 1|
  std::vector<double> faces_covered;  ///< area of the region in faces (sum of its fractions of faces)
  std::vector<std::size_t> too_small; ///< regions covering fewer than `minimum_faces` faces (not held to the tolerance)
  double minimum_faces = 50;          ///< the size below which a region is too small for the mesh
  double max_relative_error = 0;      ///< over the regions that are not too small
  double mean_relative_error = 0;     ///< over the regions that are not too small
  /// `max_relative_error` measured on the mesh (covered fractions of the faces times their
  /// deformed flat areas), what the passes and the correction work with; it differs from the
  /// polygons' by the radial projection of the deformed faces (a few tenths of a per cent
  /// where a region is shrunk a thousandfold)
  double max_relative_error_on_mesh = 0;
  double sea_area_share = 0;          ///< sea area / globe area on the deformed globe
  double sea_target_share = 0;        ///< the sea's share of the total population
  std::size_t passes = 0;             ///< density-equalizing passes run
  std::vector<double> max_error_after_pass; ///< `max_relative_error` after each pass
  /// `max_relative_error` after the passes, before the region-area correction
  double max_error_before_correction = 0;
  /// iterations of the region-area correction (0: the passes reached the tolerance)
  std::size_t correction_iterations = 0;
  std::string correction_message;     ///< why the correction stopped short of the tolerance, if it did
  bool converged = false;             ///< every region not too small is within the tolerance
  std::size_t fold_overs = 0;         ///< exact fold-over count of the final map (0)
  Map_report last_pass;               ///< the report of the last pass
  Region_populations populations;     ///< the populations of the input globe
  /// A coarser globe the cartogram was computed on first (see `coarse_globe_vertices`).
  struct Coarse_globe
  {
    std::size_t vertices = 0;              ///< its vertices
    std::size_t correction_iterations = 0; ///< of its region-area correction
    /// its largest relative area error, on its mesh, over the regions held on the finest globe
    double max_relative_error_on_mesh = 0;
  };
  /// the coarse globes, coarsest first (empty: the passes ran on this globe); the passes'
  /// fields above (`passes`, `max_error_after_pass`, `last_pass`) are then the coarsest globe's
  std::vector<Coarse_globe> coarse_globes;
  /// why the coarse globes' map was not used, if it was not (it had to turn a face of this globe over)
  std::string coarse_globe_message;
};

namespace internal {

template <class TriangleMesh, class NamedParameters>
Mesh_arrays<TriangleMesh> globe_arrays(const TriangleMesh& tm, const NamedParameters& np)
{
  Mesh_arrays<TriangleMesh> a = unvalidated_arrays(tm, np); // a sphere, not a surface to validate
  for(Eigen::Index i = 0; i < a.X.rows(); ++i) {
    const double r = a.X.row(i).norm();
    if(!(std::abs(r - 1) < 1e-6))
      throw Invalid_input("vertex " + std::to_string(i) + " of the globe mesh is not on the unit sphere (norm " +
                          std::to_string(r) + ")");
  }
  return a;
}

inline double mean_edge_length(const Matrix& X, const Index_matrix& F)
{
  double sum = 0;
  for(Eigen::Index f = 0; f < F.rows(); ++f)
    for(int j = 0; j < 3; ++j) sum += (X.row(F(f, j)) - X.row(F(f, (j + 1) % 3))).norm();
  return sum / double(3 * F.rows());
}

inline std::vector<double> flat_face_areas(const Matrix& X, const Index_matrix& F)
{
  std::vector<double> A(std::size_t(F.rows()));
  for(Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = X.row(F(f, 0)).transpose(), b = X.row(F(f, 1)).transpose(), c = X.row(F(f, 2)).transpose();
    A[std::size_t(f)] = 0.5 * (b - a).cross(c - a).norm();
  }
  return A;
}

/// Area of each region and of the sea for the face areas A (`part_areas()`, the sea last).
inline void region_areas(const std::vector<std::vector<std::pair<std::size_t, double> > >& parts,
                         const std::vector<double>& A, std::size_t regions, std::vector<double>& area, double& sea)
{
  const Vector a = part_areas(parts, Eigen::Map<const Vector>(A.data(), Eigen::Index(A.size())), regions);
  area.assign(a.data(), a.data() + regions);
  sea = a[Eigen::Index(regions)];
}

/// Face populations for per-region densities (and the sea's), with a floor
/// that keeps every face population positive (regions of value 0).
inline std::vector<double> populations_for_densities(const std::vector<std::vector<std::pair<std::size_t, double> > >& parts,
                                                     const std::vector<double>& A, const std::vector<double>& density,
                                                     double sea_density)
{
  std::vector<double> P(parts.size());
  double total = 0, area = 0;
  for(std::size_t f = 0; f < parts.size(); ++f) {
    double covered = 0, d = 0;
    for(const auto& p : parts[f]) {
      d += p.second * density[p.first];
      covered += p.second;
    }
    d += std::max(0., 1 - covered) * sea_density;
    P[f] = d * A[f];
    total += P[f];
    area += A[f];
  }
  const double floor = 1e-9 * total / area;
  for(std::size_t f = 0; f < P.size(); ++f) P[f] = std::max(P[f], floor * A[f]);
  return P;
}

inline void check_values(const std::vector<Spherical_region>& regions, const std::vector<double>& values)
{
  if(regions.empty()) throw Invalid_input("no regions given");
  if(values.size() != regions.size())
    throw Invalid_input(std::to_string(values.size()) + " values for " + std::to_string(regions.size()) + " regions");
  double total = 0;
  for(std::size_t r = 0; r < values.size(); ++r) {
    if(!(values[r] >= 0) || !std::isfinite(values[r]))
      throw Invalid_input("region \"" + regions[r].id + "\": the value " + std::to_string(values[r]) +
                          " is not a non-negative number");
    total += values[r];
  }
  if(!(total > 0)) throw Invalid_input("the values sum to 0");
}

template <class TriangleMesh, class NamedParameters>
Region_populations region_populations(const Mesh_arrays<TriangleMesh>& a, const std::vector<Spherical_region>& regions,
                                      const std::vector<double>& values, const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  check_values(regions, values);
  const int subdivision = choose_parameter(get_parameter(np, internal_np::overlap_subdivision), 0);
  if(subdivision < 0 || subdivision > 64) throw Invalid_input("overlap_subdivision must be in [0, 64]");
  Region_populations out;
  Face_region_overlaps o = face_region_overlaps(a.X, a.F, regions, subdivision);
  out.face_parts = std::move(o.parts);
  out.face_area = flat_face_areas(a.X, a.F);
  const double mean_face = std::accumulate(out.face_area.begin(), out.face_area.end(), 0.) / double(out.face_area.size());
  out.overlapping_area = o.overlapping_fraction * mean_face;
  out.sampled_overlaps = o.sampled_overlaps;
  region_areas(out.face_parts, out.face_area, regions.size(), out.region_area, out.sea_area);
  out.land_area = std::accumulate(out.region_area.begin(), out.region_area.end(), 0.);
  if(!(out.land_area > 0)) throw Invalid_input("the regions cover no part of the globe mesh");
  const double total = std::accumulate(values.begin(), values.end(), 0.);
  out.mean_land_density = total / out.land_area;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::sea_density_t>::value) {
    out.sea_density = get_parameter(np, internal_np::sea_density);
    if(!(out.sea_density > 0) || !std::isfinite(out.sea_density))
      throw Invalid_input("the sea density must be positive and finite");
  } else {
    out.sea_density = out.mean_land_density;
  }
  std::vector<double> density(regions.size());
  for(std::size_t r = 0; r < regions.size(); ++r)
    density[r] = out.region_area[r] > 0 ? values[r] / out.region_area[r] : 0;
  out.face_population = populations_for_densities(out.face_parts, out.face_area, density, out.sea_density);
  return out;
}

/// A point of a region's boundary on the globe mesh: its direction and its location.
struct Located_boundary_point
{
  Eigen::Vector3d x;
  Surface_point at;
};

/// The two vertices that faces f and g share, if they share an edge.
inline bool shared_edge(const Index_matrix& F, Eigen::Index f, Eigen::Index g, Eigen::Index& u, Eigen::Index& v)
{
  int common = 0;
  for(int a = 0; a < 3; ++a)
    for(int b = 0; b < 3; ++b)
      if(F(f, a) == F(g, b)) (common++ == 0 ? u : v) = F(f, a);
  return common == 2;
}

/// Appends to `out` the points strictly between x and y where the great-circle arc
/// x -> y crosses edges of the globe mesh, in order along the arc.
///
/// Why: the map is linear on each flat face, and a great-circle arc is a straight
/// segment on a flat face seen from the centre, so the exact image of the arc is the
/// chain of great-circle arcs between the images of its edge crossings; pushing only
/// evenly spaced points forward cuts the corners of that chain, and on the faces that a
/// cartogram shears most (next to a region shrunk a thousandfold) those corners are
/// several percent of a small region's area. Where x and y lie in faces sharing an edge,
/// the crossing is where the arc meets that edge's great circle; elsewhere (the arc
/// skips a face or passes next to a vertex) the arc is bisected, down to arcs of
/// 1e-12 radians, below which a missed corner is far below round-off of the areas.
inline void append_edge_crossings(const Mapped_surface& globe, const Located_boundary_point& x,
                                  const Located_boundary_point& y, std::vector<Located_boundary_point>& out,
                                  int depth = 0)
{
  if(x.at.face == y.at.face) return;
  const Matrix& X = globe.positions();
  const Eigen::Vector3d n = x.x.cross(y.x);
  Eigen::Index u = 0, v = 0;
  if(shared_edge(globe.faces(), x.at.face, y.at.face, u, v)) {
    const Eigen::Vector3d m = Eigen::Vector3d(X.row(u)).cross(Eigen::Vector3d(X.row(v)));
    // the arc runs along the edge (a vertex snapped onto each end): the edge is its own image
    if(n.normalized().cross(m.normalized()).norm() < 1e-9) return;
    Eigen::Vector3d z = n.cross(m);
    if(z.dot(x.x + y.x) < 0) z = -z;
    const double length = z.norm();
    if(length > 0 && x.x.cross(z).dot(n) >= 0 && z.cross(y.x).dot(n) >= 0) {
      z /= length;
      out.push_back({z, globe.locate(z, x.at)});
      return;
    }
  }
  if(depth >= 40 || n.norm() < 1e-12) return;
  Located_boundary_point mid;
  mid.x = (x.x + y.x).normalized();
  mid.at = globe.locate(mid.x, x.at);
  append_edge_crossings(globe, x, mid, out, depth + 1);
  out.push_back(mid);
  append_edge_crossings(globe, mid, y, out, depth + 1);
}

/// The boundary points of the great-circle arc a -> b on the globe mesh, a included and
/// b excluded: points at most `step` apart and every crossing with a mesh edge. They
/// are computed from the lexicographically smaller end, so that an edge shared by two
/// rings, traversed in opposite directions, gets exactly the same points.
inline void trace_arc(const Mapped_surface& globe, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double step,
                      std::vector<Located_boundary_point>& out)
{
  const bool forward = std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  std::vector<Eigen::Vector3d> even;
  densify_arc(forward ? a : b, forward ? b : a, step, even);
  even.push_back(forward ? b : a);
  std::vector<Located_boundary_point> chain;
  Located_boundary_point previous{even[0], globe.locate(even[0], out.empty() ? Surface_point() : out.back().at)};
  chain.push_back(previous);
  for(std::size_t k = 1; k < even.size(); ++k) {
    const Located_boundary_point next{even[k], globe.locate(even[k], previous.at)};
    append_edge_crossings(globe, previous, next, chain);
    chain.push_back(next);
    previous = next;
  }
  // b belongs to the next arc
  if(forward) out.insert(out.end(), chain.begin(), chain.end() - 1);
  else out.insert(out.end(), chain.rbegin(), chain.rend() - 1);
}

/// The regions' rings densified (points at most `step` apart and every crossing with an
/// edge of `globe`) and pushed forward from `globe` to `image` (the same mesh, mapped).
inline std::vector<Spherical_region> push_forward_regions(const Mapped_surface& globe, const Mapped_surface& image,
                                                          const std::vector<Spherical_region>& regions, double step)
{
  std::vector<Spherical_region> out;
  out.reserve(regions.size());
  for(std::size_t r = 0; r < regions.size(); ++r) {
    Spherical_region d;
    d.id = regions[r].id;
    for(std::size_t p = 0; p < regions[r].polygons.size(); ++p) {
      // validated rings (repeated points removed)
      const std::vector<Spherical_ring> rings =
        polygon_rings(regions[r].polygons[p], "region \"" + regions[r].id + "\", polygon " + std::to_string(p));
      Spherical_polygon q;
      for(const Spherical_ring& ring : rings) {
        std::vector<Located_boundary_point> dense;
        for(std::size_t i = 0; i < ring.size(); ++i) trace_arc(globe, ring.vertex(i), ring.next_vertex(i), step, dense);
        std::vector<Lon_lat> moved;
        moved.reserve(dense.size());
        for(const Located_boundary_point& x : dense) moved.push_back(lon_lat(image.domain_point(x.at)));
        q.rings.push_back(std::move(moved));
      }
      d.polygons.push_back(std::move(q));
    }
    out.push_back(std::move(d));
  }
  return out;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief Computes the population of each face of a globe mesh from regions of the
/// globe and one value per region.
///
/// A face shared by several regions gets the population of the parts it covers: region
/// \f$ r \f$ of value \f$ v_r \f$ and area \f$ A_r \f$ on the mesh contributes
/// \f$ v_r \, |T \cap r| / A_r \f$ to face \f$ T \f$, where \f$ |T \cap r| \f$ is the area of
/// the overlap (computed on the sphere, great-circle edges, see below); the part of
/// \f$ T \f$ that no region covers (the sea) gets the sea density times its area.
///
/// Overlaps (default, \f$ s \f$ = `overlap_subdivision` = 0): exact to round-off on the
/// flat faces. Seen from the centre, each ring arc is the chord between its ends, so
/// clipping it to a face's cone is linear in the chord's parameter; the clipped pieces,
/// projected onto the face's plane, and the face's edges on the covered side (classified
/// by the crossing parity of great-circle arcs from the face's centroid, with CGAL's exact
/// orientation predicate) bound the covered part, whose area the shoelace formula gives.
/// Faces away from boundaries are classified whole. With \f$ s \geq 1 \f$ faces near a
/// boundary are sampled instead, with the centroids of \f$ s^2 \f$ congruent sub-triangles
/// (errors of about \f$ 10^{-3} \f$ of a region's area with \f$ s = 8 \f$). Exact overlaps
/// count every sliver of a region in the faces along its border; a face that holds a thin
/// sliver of a region that the cartogram must shrink a thousandfold has to shrink with it,
/// so snap the globe to the borders first (`snap_globe_to_region_borders()`).
/// The mesh, the rings crossing the antimeridian and the rings around a pole are all
/// handled on the sphere in 3D; no projection is involved.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \param tm a closed triangle mesh with its vertices on the unit sphere (the globe)
/// \param regions the regions (each ring encloses its smaller side, see `Spherical_polygon`)
/// \param values one non-negative value per region (population, GDP, ...)
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{sea_density}
///     \cgalParamDescription{the population per unit area of the parts of the globe outside every region}
///     \cgalParamType{double}
///     \cgalParamDefault{the mean land density (total value / land area), so that the sea keeps its area}
///   \cgalParamNEnd
///   \cgalParamNBegin{overlap_subdivision}
///     \cgalParamDescription{0 for exact overlaps; \f$ s \geq 1 \f$: faces near a boundary are sampled with \f$ s^2 \f$ sub-triangles}
///     \cgalParamType{int}
///     \cgalParamDefault{0 (exact)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map, vertex_index_map}
///     \cgalParamDescription{as for `spherical_density_equalizing_map()`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre the vertices of `tm` are on the unit sphere (checked, within 1e-6)
/// \pre `values.size() == regions.size()`, every value is finite and non-negative and their sum is
///      positive (checked)
/// \returns the face populations (in the order of `faces(tm)`), with the overlaps and areas they come from
/// \throws Invalid_input on a violated precondition or an invalid ring (fewer than 3 distinct
///   positions, antipodal consecutive positions), naming the region
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Region_populations face_populations_from_regions(const TriangleMesh& tm, const std::vector<Spherical_region>& regions,
                                                 const std::vector<double>& values,
                                                 const NamedParameters& np = parameters::default_values())
{
  return internal::region_populations(internal::globe_arrays(tm, np), regions, values, np);
}

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief Carries region boundaries through a map of a globe mesh onto the sphere.
///
/// Each ring edge is first densified along its great circle, with points at most
/// `boundary_step` apart and a point at every crossing with an edge of the globe mesh `tm`
/// (the same points for an edge shared by two rings, so that shared borders stay shared),
/// then every point is located on `tm` and pushed forward through the map as
/// `Point_transfer` does. As the map is linear on each face of `tm`, the great-circle arcs
/// between the pushed points are the exact image of the ring (up to the radial
/// projection of each flat face onto the sphere), however strongly the map shears a face. The rings keep their order of vertices,
/// hence their orientation; a fold-free map keeps disjoint regions disjoint.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeGraph`
/// \tparam MappedPointMap a readable vertex property map with the image of each vertex on the unit sphere
/// \param tm the globe mesh (vertices on the unit sphere)
/// \param mapped the map of `tm` onto the sphere (for instance the output of `globe_cartogram()`)
/// \param regions the regions on the globe of `tm`
/// \param np optional named parameters:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{boundary_step}
///     \cgalParamDescription{the largest angle (radians) between consecutive points of a densified ring}
///     \cgalParamType{double}
///     \cgalParamDefault{half the mean edge length of `tm`}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_point_map, vertex_index_map}
///     \cgalParamDescription{as for `Point_transfer`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre `tm` is a closed genus-0 mesh on the unit sphere and `mapped` a fold-free map of it onto the unit sphere (checked)
/// \returns the regions with their rings densified and carried through the map (same ids, same
///   polygons and rings, in the same order)
/// \throws Invalid_input on a violated precondition or an invalid ring
template <class TriangleMesh, class MappedPointMap, class NamedParameters = parameters::Default_named_parameters>
std::vector<Spherical_region> push_forward_region_boundaries(const TriangleMesh& tm, MappedPointMap mapped,
                                                             const std::vector<Spherical_region>& regions,
                                                             const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  typedef CGAL::Simple_cartesian<double>::Point_3 Point;
  const internal::Mesh_arrays<TriangleMesh> a = internal::globe_arrays(tm, np);
  const double mean_edge = internal::mean_edge_length(a.X, a.F);
  const double step = choose_parameter(get_parameter(np, internal_np::boundary_step), 0.5 * mean_edge);
  if(!(step > 0)) throw Invalid_input("boundary_step must be positive");
  auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_const_property_map(vertex_point, tm));
  const Point_transfer<TriangleMesh, Unit_sphere_domain, Point> globe_transfer(tm, vpm, Unit_sphere_domain(), np);
  const Point_transfer<TriangleMesh, Unit_sphere_domain, Point> image_transfer(tm, mapped, Unit_sphere_domain(), np);
  return internal::push_forward_regions(globe_transfer.mapped_surface(), image_transfer.mapped_surface(), regions, step);
}

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief Moves the vertices of a globe mesh that lie near a region border onto the border.
///
/// A border that passes close to a vertex cuts thin slivers off the faces around it. With
/// exact overlaps (`overlap_subdivision(0)`, the default of `globe_cartogram()`) every sliver
/// counts: a face holding a sliver of a region that the cartogram must shrink a
/// thousandfold (the world's Antarctica in a population cartogram) must shrink with it,
/// though the rest of it is sea, and the region-area correction stalls there. Moved onto
/// the border, the vertex leaves those faces out of the region. Call it on the globe
/// before `globe_cartogram()`; `dem cartogram` does.
///
/// Each vertex within `reach` mean edge lengths of a border moves to the border's nearest
/// point, unless that would turn over or flatten one of its faces (exact orientation about
/// the centre); the vertices stay on the unit sphere.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeGraph`
/// \param tm the globe mesh (vertices on the unit sphere), modified
/// \param regions the regions
/// \param reach the largest distance moved, in mean edge lengths of `tm` (default 0.45)
/// \param np optional named parameters: `vertex_point_map` (readable and writable), `vertex_index_map`
/// \returns the number of vertices moved
/// \throws Invalid_input if a vertex is not on the unit sphere or a ring is invalid
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
std::size_t snap_globe_to_region_borders(TriangleMesh& tm, const std::vector<Spherical_region>& regions,
                                         double reach = 0.45, const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  internal::Mesh_arrays<TriangleMesh> a = internal::globe_arrays(tm, np);
  if(!(reach >= 0 && reach < 0.5)) throw Invalid_input("the snapping reach must be in [0, 0.5) edge lengths");
  const double mean_edge = internal::mean_edge_length(a.X, a.F);
  const std::size_t moved = internal::snap_vertices_to_borders(a.X, a.F, regions, reach * mean_edge);
  auto vpm = choose_parameter(get_parameter(np, internal_np::vertex_point), get_property_map(vertex_point, tm));
  internal::write_points(a, a.X, vpm);
  return moved;
}

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief The areas of regions carried through a map of the globe, measured as spherical
/// polygons: for each polygon, the area its exterior ring encloses minus its holes'.
///
/// A ring of `pushed` encloses the side that corresponds to the side its ring of `regions`
/// encloses (a fold-free map keeps the winding), which may be the larger side once the map
/// has grown the region. The report of `globe_cartogram()` measures areas on the mesh
/// (covered fractions of the faces times their deformed areas); with sampled overlaps the
/// two part where the map shrinks a region by orders of magnitude, and these are the areas
/// a reader of the output polygons sees.
///
/// \param regions the regions, as given to `push_forward_region_boundaries()`
/// \param pushed its output for them (same polygons and rings)
/// \returns the area of each region of `pushed` on the unit sphere
/// \throws Invalid_input if the two do not have the same polygons and rings, or on an invalid ring of `regions`
inline std::vector<double> pushed_forward_region_areas(const std::vector<Spherical_region>& regions,
                                                       const std::vector<Spherical_region>& pushed)
{
  const double four_pi = 4 * 3.14159265358979323846;
  if(pushed.size() != regions.size()) throw Invalid_input("pushed_forward_region_areas: the two lists of regions differ");
  std::vector<double> area(regions.size(), 0.);
  for(std::size_t r = 0; r < regions.size(); ++r) {
    if(pushed[r].polygons.size() != regions[r].polygons.size())
      throw Invalid_input("pushed_forward_region_areas: region \"" + regions[r].id + "\" has other polygons");
    for(std::size_t p = 0; p < regions[r].polygons.size(); ++p) {
      const std::vector<internal::Spherical_ring> rings =
        internal::polygon_rings(regions[r].polygons[p], "region \"" + regions[r].id + "\", polygon " + std::to_string(p));
      if(pushed[r].polygons[p].rings.size() != rings.size())
        throw Invalid_input("pushed_forward_region_areas: region \"" + regions[r].id + "\" has other rings");
      for(std::size_t k = 0; k < rings.size(); ++k) {
        const double left = internal::area_to_the_left(pushed[r].polygons[p].rings[k]);
        area[r] += (k == 0 ? 1 : -1) * (rings[k].left_is_inside() ? left : four_pi - left);
      }
    }
  }
  return area;
}

namespace internal {

/// A globe mesh and its map onto the sphere: the coarse cartogram a finer one starts from.
struct Globe_map
{
  Matrix X, Y;
  Index_matrix F;
};

/// The prolongation from a coarse globe (Xc, Fc) to the vertices X of a finer one:
/// row i holds the barycentric coordinates of X_i in its face of the coarse globe.
inline Sparse_matrix globe_prolongation(const Matrix& Xc, const Index_matrix& Fc, const Matrix& X)
{
  const Mapped_surface coarse(Xc, Fc, Xc, domain_shape(Unit_sphere_domain()));
  std::vector<Eigen::Triplet<double> > t;
  t.reserve(3 * std::size_t(X.rows()));
  Surface_point last;
  Eigen::Vector3d last_q = Eigen::Vector3d::Zero();
  for(Eigen::Index i = 0; i < X.rows(); ++i) {
    const Eigen::Vector3d q = row_vector3(X, i);
    const Surface_point s = coarse.locate(q, coarse.hint_after(last_q, last, q));
    if(s.face < 0) throw Algorithm_failure("vertex " + std::to_string(i) + " of the globe has no location on the coarse globe");
    for(int c = 0; c < 3; ++c) t.emplace_back(i, Fc(s.face, c), s.barycentric[c]);
    last = s;
    last_q = q;
  }
  Sparse_matrix P(X.rows(), Xc.rows());
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

/// The map P Yc of the finer globe, back on the unit sphere.
inline Matrix prolonged_map(const Sparse_matrix& P, const Matrix& Yc)
{
  Matrix Y = P * Yc;
  Y.rowwise().normalize();
  return Y;
}

/// The vertex count of the geodesic sphere of frequency f.
inline std::size_t geodesic_sphere_vertices(int f) { return 10 * std::size_t(f) * std::size_t(f) + 2; }

/// The default reach of `snap_globe_to_region_borders()`, in mean edge lengths.
constexpr double default_snapping_reach = 0.45;

/// The globes of a coarse-to-fine cartogram, coarsest first: the geodesic
/// sphere of frequency f0 with its vertices near a border snapped onto it,
/// then `subdivisions` midpoint subdivisions of it. Each globe's faces lie
/// inside (seen from the centre) those of the globe before, so that a fold-free
/// map of one is carried to the next fold-free, face by face.
inline std::vector<Triangle_arrays> cartogram_globe_levels(const std::vector<Spherical_region>& regions, int f0,
                                                           int subdivisions, std::size_t* snapped = nullptr)
{
  std::vector<Triangle_arrays> g(1, geodesic_sphere(f0));
  const std::size_t moved =
    snap_vertices_to_borders(g[0].X, g[0].F, regions, default_snapping_reach * mean_edge_length(g[0].X, g[0].F));
  if(snapped) *snapped = moved;
  for(int k = 0; k < subdivisions; ++k) g.push_back(midpoint_subdivision_on_sphere(g.back()));
  return g;
}

/// Whether (X, F) is the mesh m: the same points (to 1e-12) and the same faces
/// (each up to a rotation of its corners).
inline bool same_triangle_mesh(const Triangle_arrays& m, const Matrix& X, const Index_matrix& F)
{
  if(m.X.rows() != X.rows() || m.F.rows() != F.rows() || !((m.X - X).cwiseAbs().maxCoeff() < 1e-12)) return false;
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    int r = 0;
    while(r < 3 && m.F(k, r) != F(k, 0)) ++r;
    if(r == 3 || m.F(k, (r + 1) % 3) != F(k, 1) || m.F(k, (r + 2) % 3) != F(k, 2)) return false;
  }
  return true;
}

/// The cartogram on the globe `tm` (the body of `globe_cartogram()`), from the
/// passes, or from the map of a coarser globe (`start`) carried to `tm`. The
/// regions held to the tolerance are those covering at least 50 faces of the
/// size of a globe of `finest_faces` faces (0: of `tm`).
template <class TriangleMesh, class VertexPointOutMap, class NamedParameters>
Globe_cartogram_report globe_cartogram_on(const TriangleMesh& tm, const std::vector<Spherical_region>& regions,
                                          const std::vector<double>& values, VertexPointOutMap sphere_map,
                                          const NamedParameters& np, const Globe_map* start,
                                          std::size_t finest_faces = 0)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  typedef CGAL::Simple_cartesian<double>::Point_3 Point;
  const internal::Mesh_arrays<TriangleMesh> a = internal::globe_arrays(tm, np);
  Globe_cartogram_report rep;
  rep.populations = internal::region_populations(a, regions, values, np);
  const Region_populations& pop = rep.populations;
  const double tolerance = choose_parameter(get_parameter(np, internal_np::relative_area_tolerance), 0.01);
  const std::size_t max_passes = choose_parameter(get_parameter(np, internal_np::number_of_passes), 8u);
  if(!(tolerance > 0)) throw Invalid_input("relative_area_tolerance must be positive");
  if(max_passes < 1) throw Invalid_input("number_of_passes must be at least 1");

  const std::size_t nr = regions.size();
  const double total_value = std::accumulate(values.begin(), values.end(), 0.);
  const double total_population = total_value + pop.sea_density * pop.sea_area;
  // faces of the size of those of the globe the cartogram is for (a coarse
  // globe holds the regions that the finest globe holds)
  const bool coarse_level = finest_faces > 0;
  const double mean_face = std::accumulate(pop.face_area.begin(), pop.face_area.end(), 0.) /
                           double(finest_faces > 0 ? finest_faces : pop.face_area.size());
  rep.value_share.resize(nr);
  rep.faces_covered.resize(nr);
  for(std::size_t r = 0; r < nr; ++r) {
    rep.value_share[r] = values[r] / total_value;
    rep.faces_covered[r] = pop.region_area[r] / mean_face;
    if(rep.faces_covered[r] < rep.minimum_faces) rep.too_small.push_back(r);
  }
  rep.sea_target_share = pop.sea_density * pop.sea_area / total_population;
  std::vector<char> small(nr, 0);
  for(std::size_t r : rep.too_small) small[r] = 1;

  // current map, by vertex index and face index of the arrays
  internal::Matrix Y = a.X;
  std::vector<Point> position(a.vertices.size());
  std::vector<double> face_pop(a.faces.size());
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  std::map<face_descriptor, std::size_t> face_slot;
  for(std::size_t k = 0; k < a.faces.size(); ++k) face_slot[a.faces[k]] = k;
  auto position_map = boost::make_iterator_property_map(position.begin(), vim);
  auto population_map = boost::make_function_property_map<face_descriptor>(
    [&](face_descriptor f) { return face_pop[face_slot.at(f)]; });

  // the report's shares and errors from the regions' areas and the sea's
  auto set_shares = [&](const std::vector<double>& area, double sea) {
    const double land = std::accumulate(area.begin(), area.end(), 0.);
    rep.area_share.assign(nr, 0.);
    rep.relative_error.assign(nr, 0.);
    rep.max_relative_error = rep.mean_relative_error = 0;
    std::size_t counted = 0;
    for(std::size_t r = 0; r < nr; ++r) {
      rep.area_share[r] = area[r] / land;
      rep.relative_error[r] = rep.value_share[r] > 0 ? std::abs(rep.area_share[r] / rep.value_share[r] - 1)
                                                     : (rep.area_share[r] > 0 ? 1. : 0.);
      if(small[r]) continue;
      rep.max_relative_error = std::max(rep.max_relative_error, rep.relative_error[r]);
      rep.mean_relative_error += rep.relative_error[r];
      ++counted;
    }
    if(counted > 0) rep.mean_relative_error /= double(counted);
    rep.sea_area_share = sea / (land + sea);
  };
  // on the mesh: covered fractions of the faces times their flat areas under Z
  auto measure = [&](const internal::Matrix& Z, std::vector<double>& area, double& sea) {
    internal::region_areas(pop.face_parts, internal::flat_face_areas(Z, a.F), nr, area, sea);
    set_shares(area, sea);
  };
  // on the regions' boundaries carried through Z, as spherical polygons: what a reader of
  // the output polygons measures. The two differ by the radial projection of the deformed
  // faces, most where a region is shrunk a thousandfold and its neighbours' faces are long.
  const internal::Mapped_surface globe_surface(a.X, a.F, a.X, internal::domain_shape(Unit_sphere_domain()));
  const double boundary_step = 0.5 * internal::mean_edge_length(a.X, a.F);
  auto measure_polygons = [&](const internal::Matrix& Z) {
    const internal::Mapped_surface image(a.X, a.F, Z, internal::domain_shape(Unit_sphere_domain()));
    const std::vector<double> polygon_area =
      pushed_forward_region_areas(regions, internal::push_forward_regions(globe_surface, image, regions, boundary_step));
    const double land = std::accumulate(polygon_area.begin(), polygon_area.end(), 0.);
    set_shares(polygon_area, 4 * 3.14159265358979323846 - land);
  };

  std::vector<double> area;
  double sea = 0;
  measure(Y, area, sea);
  // One density-equalizing pass from the current map Y; false if it did not
  // give a fold-free map (Y is then unchanged).
  auto run_pass = [&]() {
    // densities that would give every region its target share if the flow equalized exactly
    const std::vector<double> A = internal::flat_face_areas(Y, a.F);
    std::vector<double> density(nr);
    for(std::size_t r = 0; r < nr; ++r) density[r] = area[r] > 0 ? values[r] / total_population / area[r] : 0;
    const double sea_density = sea > 0 ? rep.sea_target_share / sea : 0;
    face_pop = internal::populations_for_densities(pop.face_parts, A, density, sea_density);
    for(std::size_t i = 0; i < position.size(); ++i) position[i] = Point(Y(i, 0), Y(i, 1), Y(i, 2));
    std::vector<Point> next(position.size());
    auto next_map = boost::make_iterator_property_map(next.begin(), vim);
    rep.last_pass = spherical_density_equalizing_map(
      tm, next_map,
      parameters::combine(np, parameters::initial_map(position_map), parameters::face_population_map(population_map),
                          parameters::vertex_point_map(position_map)));
    ++rep.passes;
    if(rep.last_pass.fold_overs > 0) return false; // keep the last fold-free map
    for(std::size_t i = 0; i < next.size(); ++i) {
      const Eigen::Vector3d y(next[i].x(), next[i].y(), next[i].z());
      Y.row(Eigen::Index(i)) = y.normalized().transpose();
    }
    measure(Y, area, sea);
    rep.max_error_after_pass.push_back(rep.max_relative_error);
    if constexpr(!is_default_parameter<NamedParameters, internal_np::pass_callback_t>::value)
      get_parameter(np, internal_np::pass_callback)(rep.passes, rep.max_relative_error);
    return true;
  };
  // The region-area correction (internal/region_area_correction.h) from Y:
  // the passes stall where a region must shrink by orders of magnitude.
  auto correct = [&](const internal::Coarse_displacements* space, std::size_t max_iterations) {
    // One constraint per region held to the tolerance, one for the regions
    // too small for the mesh together (so that the land keeps its share
    // without a solve per small region), the sea as the rest.
    std::vector<std::size_t> part_of(nr);
    std::size_t parts = 0;
    for(std::size_t r = 0; r < nr; ++r)
      if(!small[r]) part_of[r] = parts++;
    const std::size_t small_part = parts;
    if(!rep.too_small.empty()) ++parts;
    for(std::size_t r : rep.too_small) part_of[r] = small_part;
    const internal::Vector weight = internal::Vector::Ones(Eigen::Index(parts) + 1);
    internal::Face_parts face_parts(pop.face_parts.size());
    for(std::size_t f = 0; f < face_parts.size(); ++f)
      for(const auto& p : pop.face_parts[f]) {
        const std::size_t j = part_of[p.first];
        auto same = std::find_if(face_parts[f].begin(), face_parts[f].end(), [&](const auto& q) { return q.first == j; });
        if(same == face_parts[f].end()) face_parts[f].emplace_back(j, p.second);
        else same->second += p.second;
      }
    std::unique_ptr<internal::Spd_solver> solver = internal::solver_from_parameters(np);
    // The mesh's measure steers; the polygons decide. Where the two differ (the
    // radial projection of long deformed faces), the shares the mesh must reach are
    // corrected by the ratio of the two measures, region by region, and the correction
    // runs again from there (defect correction): a few rounds, each to 0.1 of the
    // tolerance on the mesh. A coarse globe is only a start: its mesh measure is enough.
    std::vector<double> aim(nr, 1.); // the mesh share to reach = value share x aim (normalized)
    double sea_aim = 1;
    std::size_t left = max_iterations;
    for(int round = 0;; ++round) {
      internal::Vector target = internal::Vector::Zero(Eigen::Index(parts) + 1);
      for(std::size_t r = 0; r < nr; ++r)
        target[Eigen::Index(part_of[r])] += rep.value_share[r] * aim[r] * (1 - rep.sea_target_share);
      target[Eigen::Index(parts)] = rep.sea_target_share * sea_aim;
      double aimed_land = 0;
      for(std::size_t r = 0; r < nr; ++r) aimed_land += rep.value_share[r] * aim[r];
      auto off_aim = [&]() { // the largest relative error of the mesh shares to the aimed ones
        double e = 0;
        for(std::size_t r = 0; r < nr; ++r)
          if(!small[r] && rep.value_share[r] > 0)
            e = std::max(e, std::abs(rep.area_share[r] / (rep.value_share[r] * aim[r] / aimed_land) - 1));
        return e;
      };
      const internal::Region_area_correction_result c = internal::correct_region_areas(
        Y, a.F, face_parts, parts, target, weight, *solver, [&](const internal::Matrix& Z, std::size_t iteration) {
          measure(Z, area, sea);
          if constexpr(!is_default_parameter<NamedParameters, internal_np::progress_callback_t>::value)
            if(iteration > 0 && !get_parameter(np, internal_np::progress_callback)(iteration, rep.max_relative_error))
              return true;
          return off_aim() <= (coarse_level ? 1. : 0.1) * tolerance;
        }, left, space);
      rep.correction_iterations += c.iterations;
      rep.correction_message = c.message;
      left -= std::min(left, c.iterations);
      if(coarse_level || !c.message.empty()) break;
      measure(Y, area, sea);
      const std::vector<double> mesh_share = rep.area_share;
      const double mesh_sea = rep.sea_area_share;
      measure_polygons(Y);
      if(rep.max_relative_error <= tolerance) break;
      if(round == 5 || left == 0) {
        rep.correction_message = "the areas of the output polygons differ from the mesh's measure by more than the "
                                 "tolerance after 6 rounds of correction";
        break;
      }
      for(std::size_t r = 0; r < nr; ++r)
        if(rep.area_share[r] > 0) aim[r] *= mesh_share[r] / rep.area_share[r];
      if(rep.sea_area_share > 0) sea_aim *= mesh_sea / rep.sea_area_share;
    }
    measure(Y, area, sea);
  };

  // The start: the coarse globe's map carried to this globe, if it turns no
  // face of this globe over; the passes otherwise.
  std::optional<internal::Coarse_displacements> coarse;
  if(start) {
    internal::Coarse_displacements c;
    c.prolongation = internal::globe_prolongation(start->X, start->F, a.X);
    c.map = start->Y;
    c.faces = start->F;
    // Each face of this globe lies inside one of the coarse globe (seen from the
    // centre), where the map is linear: fold-free if the coarse map is (checked).
    const internal::Matrix Z = internal::prolonged_map(c.prolongation, start->Y);
    const std::size_t folds = internal::count_inverted_faces_about_center(Z, a.F);
    if(folds == 0) {
      Y = Z;
      coarse = std::move(c);
      measure(Y, area, sea);
    } else {
      rep.coarse_globe_message = "the coarse globe's map turns " + std::to_string(folds) +
                                 " face(s) of this globe over; the passes ran on this globe";
    }
  }
  if(!coarse) {
    for(std::size_t pass = 0; pass < max_passes; ++pass) {
      const double before = rep.max_relative_error;
      if(!run_pass() || rep.max_relative_error <= tolerance) break;
      // A pass that does not halve the largest error is stalling: the flow is
      // crushing faces next to regions that must shrink by orders of magnitude
      // (the world's Antarctica), and further passes leave a mesh the
      // correction can hardly move (benchmark/RESULTS.md).
      if(!(rep.max_relative_error <= 0.5 * before)) break;
    }
  }
  rep.max_error_before_correction = rep.max_relative_error;
  // A coarse globe is a start for the finer ones: its mesh measure is enough
  // there (its faces are large, and its polygons the finer globes correct).
  auto measure_final = [&]() {
    if(coarse_level) measure(Y, area, sea);
    else measure_polygons(Y);
  };
  if(rep.max_relative_error <= tolerance) measure_final(); // the passes may have met it on the mesh only
  if(rep.max_relative_error > tolerance && rep.last_pass.fold_overs == 0) {
    // another pass and correction after a stalled one do not help (RESULTS.md);
    // in the coarse globe's displacements first (cheap), then in this globe's
    if(coarse) {
      correct(&*coarse, 60);
      measure_final();
    }
    if(!coarse || rep.max_relative_error > tolerance) correct(nullptr, 200);
  }
  measure(Y, area, sea);
  rep.max_relative_error_on_mesh = rep.max_relative_error;
  measure_final();
  rep.converged = rep.max_relative_error <= tolerance;
  rep.fold_overs = internal::count_inverted_faces_about_center(Y, a.F);
  internal::write_points(a, Y, sphere_map);
  return rep;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief Computes a globe cartogram: a fold-free map of the globe onto itself under which
/// every region's share of the land area is its share of the values.
///
/// The face populations are those of `face_populations_from_regions()`. The map is a
/// composition of spherical density-equalizing maps (`spherical_density_equalizing_map()`),
/// each started from the identity of the current globe: the first equalizes the face
/// populations; as the flow stops at a tolerance on the density, not on the regions' areas,
/// each further pass (as the planar cartogram tools of Gastner and Newman do) gives every
/// region the density (target share) / (current share) on the deformed globe and flows again,
/// until every region covering at least 50 faces has its area share within
/// `relative_area_tolerance` of its value share, `number_of_passes` passes are done, or a
/// pass does not halve the largest error (it is stalling on regions that must shrink by
/// orders of magnitude). If the tolerance is not met then, a region-area correction
/// follows: Gauss-Newton steps on the regions' areas (the regions too small for the mesh
/// held together), each the smoothest displacement of the vertices that brings the areas
/// closer to their targets, halved until no face turns over; it stops at the tolerance or
/// says in `Globe_cartogram_report::correction_message` why it stopped short.
/// The sea keeps the share of the population the sea density gives it. Each pass and each
/// correction step is fold-free (certified by exact predicates), so is their composition.
/// The passes and the correction measure areas on the mesh (covered fractions of the faces
/// times their deformed flat areas); the report's area shares and errors, and the test
/// of the tolerance that ends the correction, are those of the regions' boundaries carried
/// through the map (`push_forward_region_boundaries()`) measured as spherical polygons,
/// which is what a reader of the output sees (`max_relative_error_on_mesh` keeps the
/// mesh's measure). For exact overlaps without thin slivers, snap the globe to the borders
/// first (`snap_globe_to_region_borders()`).
///
/// <b>Coarse to fine.</b> On a globe built by `make_cartogram_globe()` (midpoint
/// subdivisions of a coarse geodesic sphere), with `coarse_globe_vertices` set to the count
/// it returned, the passes and a first correction run on the coarse globe, which holds the
/// regions that cover 50 faces of `tm` (on its own mesh measure); its map is carried to each
/// finer globe in turn (each face of a finer globe lies inside one of the globe below, where
/// the map is linear, so the carried map is fold-free, checked by exact predicates) and the
/// correction continues there, with displacements of the globe below (whose stiffness is
/// factored once: a solve on a quarter of the vertices), then, if that stalls, of the globe's
/// own vertices. The passes, the costly part on a fine globe (every SDEM iteration solves a
/// diffusion system on the deformed globe), thus run on a few thousand vertices: the world's
/// population cartogram on 103,680 faces takes seconds instead of minutes
/// (benchmark/RESULTS.md). Every finer globe measures its regions with its own exact
/// overlaps, and the finest ends with the same polygon test of the tolerance.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeGraph`
/// \tparam VertexPointOutMap a writable vertex property map with 3D points as values
/// \param tm the globe: a closed genus-0 mesh with its vertices on the unit sphere
/// \param regions the regions of the globe
/// \param values one non-negative value per region
/// \param sphere_map receives the image of each vertex on the unit sphere
/// \param np optional named parameters: those of `face_populations_from_regions()`, those of
///   `spherical_density_equalizing_map()` (used by every pass; `initial_map` and
///   `face_population_map` are set by the passes), and:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{relative_area_tolerance}
///     \cgalParamDescription{the largest relative error of a region's area share that stops the passes}
///     \cgalParamType{double}
///     \cgalParamDefault{0.01}
///   \cgalParamNEnd
///   \cgalParamNBegin{number_of_passes}
///     \cgalParamDescription{the largest number of density-equalizing passes}
///     \cgalParamType{unsigned int}
///     \cgalParamDefault{8}
///   \cgalParamNEnd
///   \cgalParamNBegin{progress_callback}
///     \cgalParamDescription{a callable `bool(std::size_t iteration, double error)`: called by every
///       pass's SDEM iterations (their stopping quantity) and by the region-area correction
///       (its iterations and the largest relative area error); returning `false` stops the
///       pass, or the correction}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{pass_callback}
///     \cgalParamDescription{a callable `void(std::size_t pass, double max_relative_error)` called after each pass}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{coarse_globe_vertices}
///     \cgalParamDescription{the count returned by `make_cartogram_globe()` for `tm`: compute coarse to fine
///       (see above); 0: on `tm` alone}
///     \cgalParamType{std::size_t}
///     \cgalParamDefault{0}
///   \cgalParamNEnd
///   \cgalParamNBegin{concurrency_tag}
///     \cgalParamDescription{`CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`: the loops over faces and
///       vertices run on TBB's threads (when built with TBB); the result is the same to the last bit}
///     \cgalParamType{`CGAL::Sequential_tag`, `CGAL::Parallel_tag` or `CGAL::Parallel_if_available_tag`}
///     \cgalParamDefault{`CGAL::Sequential_tag` (called by another map of the package: that map's)}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre as `face_populations_from_regions()` and `spherical_density_equalizing_map()` (checked)
/// \returns the areas reached, the errors, the passes, and the populations used
/// \throws Invalid_input on a violated precondition, or if `tm` is not the globe
///   `make_cartogram_globe()` builds for the regions with `coarse_globe_vertices`
/// \throws Algorithm_failure if a pass cannot start (see `spherical_density_equalizing_map()`)
template <class TriangleMesh, class VertexPointOutMap, class NamedParameters = parameters::Default_named_parameters>
Globe_cartogram_report globe_cartogram(const TriangleMesh& tm, const std::vector<Spherical_region>& regions,
                                       const std::vector<double>& values, VertexPointOutMap sphere_map,
                                       const NamedParameters& np = parameters::default_values())
{
  const internal::Concurrency_scope concurrency = internal::concurrency_scope_from_parameters(np);
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  if constexpr(is_default_parameter<NamedParameters, internal_np::coarse_globe_vertices_t>::value) {
    return internal::globe_cartogram_on(tm, regions, values, sphere_map, np, nullptr);
  } else {
    const std::size_t coarse_vertices = get_parameter(np, internal_np::coarse_globe_vertices);
    if(coarse_vertices == 0) return internal::globe_cartogram_on(tm, regions, values, sphere_map, np, nullptr);
    // the globes below tm, rebuilt as make_cartogram_globe() built them
    const internal::Mesh_arrays<TriangleMesh> a = internal::globe_arrays(tm, np);
    const int f0 = int(std::lround(std::sqrt(double(coarse_vertices - 2) / 10)));
    int subdivisions = 0;
    while(internal::geodesic_sphere_vertices(f0 << subdivisions) < std::size_t(a.X.rows()) && subdivisions < 16) ++subdivisions;
    const std::vector<internal::Triangle_arrays> levels = internal::cartogram_globe_levels(regions, f0, subdivisions);
    const internal::Triangle_arrays& finest = levels.back();
    if(internal::geodesic_sphere_vertices(f0) != coarse_vertices || subdivisions == 0 ||
       !internal::same_triangle_mesh(finest, a.X, a.F))
      throw Invalid_input("the globe is not one that make_cartogram_globe() builds on a coarse globe of " +
                          std::to_string(coarse_vertices) + " vertices (coarse_globe_vertices)");
    typedef CGAL::Simple_cartesian<double>::Point_3 Point;
    typedef CGAL::Surface_mesh<Point> Globe;
    std::optional<internal::Globe_map> start;
    std::vector<Globe_cartogram_report> coarse_reports;
    for(std::size_t k = 0; k + 1 < levels.size(); ++k) {
      Globe globe;
      internal::write_triangle_mesh(levels[k].X, levels[k].F, globe);
      auto image = globe.template add_property_map<typename Globe::Vertex_index, Point>("v:cartogram").first;
      coarse_reports.push_back(internal::globe_cartogram_on(
        globe, regions, values, image,
        parameters::combine(np, parameters::vertex_point_map(get(CGAL::vertex_point, globe)),
                            parameters::vertex_index_map(get(CGAL::vertex_index, globe))),
        start ? &*start : nullptr, std::size_t(finest.F.rows())));
      internal::Globe_map g;
      g.X = levels[k].X;
      g.F = levels[k].F;
      g.Y.resize(g.X.rows(), 3);
      for(auto v : globe.vertices()) g.Y.row(Eigen::Index(v.idx())) << image[v].x(), image[v].y(), image[v].z();
      start = std::move(g);
    }
    Globe_cartogram_report rep = internal::globe_cartogram_on(tm, regions, values, sphere_map, np, &*start);
    if(rep.coarse_globe_message.empty()) { // the passes are the coarsest globe's
      const Globe_cartogram_report& coarsest = coarse_reports.front();
      rep.passes = coarsest.passes;
      rep.max_error_after_pass = coarsest.max_error_after_pass;
      rep.last_pass = coarsest.last_pass;
    }
    for(std::size_t k = 0; k < coarse_reports.size(); ++k) {
      Globe_cartogram_report::Coarse_globe level;
      level.vertices = std::size_t(levels[k].X.rows());
      level.correction_iterations = coarse_reports[k].correction_iterations;
      level.max_relative_error_on_mesh = coarse_reports[k].max_relative_error;
      rep.coarse_globes.push_back(level);
    }
    return rep;
  }
}

/// \ingroup PkgDensityEqualizingMapsCartogram
/// What `make_cartogram_globe()` built.
struct Cartogram_globe
{
  /// the vertices of the coarse globe (pass it to `globe_cartogram()` as `coarse_globe_vertices`),
  /// 0 if the globe is not subdivided
  std::size_t coarse_globe_vertices = 0;
  std::size_t subdivisions = 0;     ///< midpoint subdivisions from the coarse globe to the globe
  std::size_t snapped_vertices = 0; ///< vertices of the coarse globe snapped to a border
};

/// \ingroup PkgDensityEqualizingMapsCartogram
/// \brief Builds a globe mesh on which `globe_cartogram()` can work coarse to fine.
///
/// The globe is the icosahedral geodesic sphere of frequency \f$ f = f_0 2^k \f$ nearest to
/// `vertices` (\f$ 10 f^2 + 2 \f$ vertices) with \f$ f_0 \leq 20 \f$ (at most 4,002 vertices on
/// the coarse globe), built as \f$ k \f$ midpoint subdivisions of the geodesic sphere of
/// frequency \f$ f_0 \f$ whose vertices near a border are snapped onto it (as
/// `snap_globe_to_region_borders()` does). Pass `coarse_globe_vertices` of the result to
/// `globe_cartogram()`: it then runs its passes on the coarse globe and carries the map up
/// the subdivisions, correcting the regions' areas on each globe (see `globe_cartogram()`).
/// Up to 4,002 vertices (\f$ k = 0 \f$) the globe is the snapped geodesic sphere itself.
///
/// \tparam PolygonMesh a model of `MutableFaceGraph` with a vertex point map
/// \param globe receives the globe (its content is replaced); vertices in the order of construction
/// \param regions the regions whose borders the coarse globe is snapped to
/// \param vertices about how many vertices the globe should have (at least 12)
/// \returns the coarse globe's vertex count (for `coarse_globe_vertices`), the subdivisions
///   and the snapped vertices
/// \throws Invalid_input on an invalid ring or fewer than 12 vertices asked
template <class PolygonMesh>
Cartogram_globe make_cartogram_globe(PolygonMesh& globe, const std::vector<Spherical_region>& regions,
                                     std::size_t vertices)
{
  if(vertices < 12) throw Invalid_input("a globe needs at least 12 vertices (got " + std::to_string(vertices) + ")");
  const double f = std::sqrt((double(vertices) - 2) / 10);
  const int subdivisions = f > 20 ? int(std::ceil(std::log2(f / 20))) : 0;
  const int f0 = std::max(1, int(std::lround(f / double(1 << subdivisions))));
  Cartogram_globe out;
  const std::vector<internal::Triangle_arrays> levels =
    internal::cartogram_globe_levels(regions, f0, subdivisions, &out.snapped_vertices);
  internal::write_triangle_mesh(levels.back().X, levels.back().F, globe);
  out.subdivisions = std::size_t(subdivisions);
  if(subdivisions > 0) out.coarse_globe_vertices = internal::geodesic_sphere_vertices(f0);
  return out;
}

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_GLOBE_CARTOGRAM_H
