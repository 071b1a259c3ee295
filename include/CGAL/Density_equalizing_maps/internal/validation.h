// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_VALIDATION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_VALIDATION_H

// Input checks shared by every method. They work on the index arrays so that
// the command-line tool can run them on a polygon soup before a halfedge
// structure exists (a non-manifold edge cannot even be stored in one).

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

inline std::string face_name(Eigen::Index k) { return "face " + std::to_string(k); }
inline std::string vertex_name(Eigen::Index i) { return "vertex " + std::to_string(i); }

/// Topological facts of a closed, oriented, manifold triangle mesh.
struct Mesh_topology
{
  std::size_t edges = 0;
  long euler_characteristic = 0;
  long genus() const { return (2 - euler_characteristic) / 2; }
};

/// Checks everything a closed surface method needs and returns the topology.
/// `expected_euler` is 2 for genus 0, 0 for genus 1. Throws `Invalid_input`.
inline Mesh_topology validate_closed_surface(const Matrix& X, const Index_matrix& F,
                                             long expected_euler, Eigen::Index min_vertices)
{
  const Eigen::Index nv = X.rows(), nf = F.rows();
  if(nv < min_vertices)
    throw Invalid_input("too few vertices: the mesh has " + std::to_string(nv) +
                        ", at least " + std::to_string(min_vertices) + " are needed");
  if(nf == 0) throw Invalid_input("the mesh has no faces");
  for(Eigen::Index i = 0; i < nv; ++i)
    for(int c = 0; c < 3; ++c)
      if(!std::isfinite(X(i, c)))
        throw Invalid_input("non-finite coordinates at " + vertex_name(i));
  for(Eigen::Index k = 0; k < nf; ++k)
    for(int c = 0; c < 3; ++c)
      if(F(k, c) < 0 || F(k, c) >= nv)
        throw Invalid_input(face_name(k) + " refers to vertex " + std::to_string(F(k, c)) +
                            ", out of range");

  // Every directed edge must occur once and its reverse once: anything else is
  // a boundary, a non-manifold edge or inconsistent orientation. The directed
  // edges are bucketed by their source vertex (a counting sort, linear time):
  // a look-up scans the few edges leaving one vertex, which is cheaper than a
  // global sort and binary searches, or a hash map, on large meshes.
  std::vector<Eigen::Index> first_out(static_cast<std::size_t>(nv) + 1, 0);
  for(Eigen::Index k = 0; k < nf; ++k)
    for(int c = 0; c < 3; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3);
      if(i == j) throw Invalid_input("degenerate " + face_name(k) + ": repeated vertex " + std::to_string(i));
      ++first_out[i + 1];
    }
  for(Eigen::Index i = 0; i < nv; ++i)
    if(first_out[i + 1] == 0) throw Invalid_input("isolated " + vertex_name(i) + " belongs to no face");
  // faces around vertex i = directed edges leaving i (one per corner)
  auto incident_faces = [&](Eigen::Index i) { return first_out[i + 1] - first_out[i]; };
  for(Eigen::Index i = 0; i < nv; ++i) first_out[i + 1] += first_out[i];
  struct Out_edge { int target; Eigen::Index face; };
  std::vector<Out_edge> out(static_cast<std::size_t>(3 * nf));
  {
    std::vector<Eigen::Index> fill(first_out.begin(), first_out.end() - 1);
    for(Eigen::Index k = 0; k < nf; ++k)
      for(int c = 0; c < 3; ++c) out[fill[F(k, c)]++] = {F(k, (c + 1) % 3), k};
  }
  // the face containing the directed edge (i, j), or -1
  auto face_of_edge = [&](Eigen::Index i, int j) -> Eigen::Index {
    for(Eigen::Index e = first_out[i]; e < first_out[i + 1]; ++e)
      if(out[e].target == j) return out[e].face;
    return -1;
  };
  {
    std::vector<Eigen::Index> last_source(static_cast<std::size_t>(nv), -1);
    for(Eigen::Index i = 0; i < nv; ++i)
      for(Eigen::Index e = first_out[i]; e < first_out[i + 1]; ++e) {
        const int j = out[e].target;
        if(last_source[j] == i) {
          const bool both_ways = face_of_edge(j, int(i)) >= 0;
          throw Invalid_input(std::string(both_ways ? "non-manifold edge (" : "inconsistent face orientation or non-manifold edge (") +
                              std::to_string(i) + ", " + std::to_string(j) + ")" +
                              (both_ways ? " shared by more than two faces" : "") + " (at " + face_name(out[e].face) + ")");
        }
        last_source[j] = i;
      }
  }
  for(Eigen::Index k = 0; k < nf; ++k)
    for(int c = 0; c < 3; ++c) {
      const int i = F(k, c), j = F(k, (c + 1) % 3);
      if(face_of_edge(j, i) < 0)
        throw Invalid_input("open boundary: edge (" + std::to_string(i) + ", " + std::to_string(j) + ") of " +
                            face_name(k) + " has no opposite face; the mesh must be closed");
    }

  // Non-manifold vertices: the faces around a vertex must form one fan.
  std::vector<char> visited(static_cast<std::size_t>(nv), 0);
  for(Eigen::Index k = 0; k < nf; ++k)
    for(int c = 0; c < 3; ++c) {
      const int v = F(k, c);
      if(visited[v]) continue;
      visited[v] = 1;
      // walk the fan: from face (v, a, b) go to the face containing edge (v, b)
      Eigen::Index count = 0;
      Eigen::Index f = k;
      do {
        ++count;
        int cv = 0;
        while(F(f, cv) != v) ++cv;
        f = face_of_edge(v, F(f, (cv + 2) % 3));
      } while(f != k && count <= incident_faces(v));
      if(count != incident_faces(v))
        throw Invalid_input("non-manifold " + vertex_name(v) + ": its faces form more than one fan");
    }

  // Connectivity (faces through shared edges).
  {
    std::vector<char> seen(static_cast<std::size_t>(nf), 0);
    std::vector<Eigen::Index> stack{0};
    seen[0] = 1;
    Eigen::Index reached = 1;
    while(!stack.empty()) {
      Eigen::Index f = stack.back(); stack.pop_back();
      for(int c = 0; c < 3; ++c) {
        Eigen::Index g = face_of_edge(F(f, (c + 1) % 3), F(f, c));
        if(!seen[g]) { seen[g] = 1; ++reached; stack.push_back(g); }
      }
    }
    if(reached != nf)
      throw Invalid_input("the mesh is not connected (" + std::to_string(nf - reached) +
                          " faces are not reachable from face 0)");
  }

  Mesh_topology t;
  t.edges = static_cast<std::size_t>(3 * nf) / 2;
  t.euler_characteristic = static_cast<long>(nv) - static_cast<long>(t.edges) + static_cast<long>(nf);
  if(t.euler_characteristic != expected_euler) {
    const long g = (2 - t.euler_characteristic) / 2;
    throw Invalid_input("wrong topology: Euler characteristic " + std::to_string(t.euler_characteristic) +
                        " (genus " + std::to_string(g) + "), this method needs genus " +
                        std::to_string((2 - expected_euler) / 2));
  }

  // Degenerate faces, decided exactly (thin slivers are valid input).
  const std::vector<Epick::Point_3> P = epick_points_3(X);
  const Eigen::Index degenerate =
    first_index_where(nf, [&](Eigen::Index k) { return CGAL::collinear(P[F(k, 0)], P[F(k, 1)], P[F(k, 2)]); });
  if(degenerate < nf)
    throw Invalid_input("degenerate " + face_name(degenerate) + ": its corners are collinear (zero area)");
  return t;
}

/// Checks a per-face population: right length, finite and positive.
inline void validate_population(const Vector& p, Eigen::Index nf, const char* what = "population")
{
  if(p.size() != nf)
    throw Invalid_input(std::string(what) + " has " + std::to_string(p.size()) + " values, the mesh has " +
                        std::to_string(nf) + " faces");
  for(Eigen::Index k = 0; k < nf; ++k)
    if(!std::isfinite(p[k]) || !(p[k] > 0))
      throw Invalid_input(std::string("non-positive or non-finite ") + what + " at " + face_name(k) +
                          " (value " + std::to_string(p[k]) + ")");
}

/// Checks points that must lie on (or be projected radially onto) a domain
/// centred at the origin: all finite and none at the center, where the radial
/// projection is undefined.
inline void validate_spherical_points(const Matrix& S, const std::string& what)
{
  for(Eigen::Index i = 0; i < S.rows(); ++i) {
    if(!S.row(i).allFinite()) throw Invalid_input(what + " has non-finite coordinates at " + vertex_name(i));
    if(S(i, 0) == 0 && S(i, 1) == 0 && S(i, 2) == 0)
      throw Invalid_input(what + " sends " + vertex_name(i) + " to the center (0, 0, 0)");
  }
}

/// The sane range of the radii of a target domain (ellipsoid a, b, c; torus
/// R, r). The maps are computed in the domain's own units, independently of
/// the scale of the input mesh, so the range does not depend on the mesh:
///  - shape: largest / smallest radius at most `max_domain_aspect` (beyond
///    it the stereographic and flat-torus charts lose every significant digit
///    of the short direction);
///  - scale: every radius within [`min_domain_radius`, `max_domain_radius`],
///    so that areas and volumes of the domain (radius^3 at most) stay normal
///    doubles. The scale check is invariant under scaling the input mesh.
constexpr double max_domain_aspect = 1e6;
constexpr double min_domain_radius = 1e-100;
constexpr double max_domain_radius = 1e100;

/// Throws `Invalid_input` unless every radius is positive, finite and in the
/// sane range above. `what` names the radii in the message ("ellipsoid radii").
inline void validate_domain_radii(const double* radii, int count, const std::string& what)
{
  std::string list;
  for(int c = 0; c < count; ++c) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%s%.6g", c ? ", " : "", radii[c]);
    list += buffer;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for(int c = 0; c < count; ++c) {
    if(!std::isfinite(radii[c]) || !(radii[c] > 0))
      throw Invalid_input(what + " must be positive and finite (got " + list + ")");
    lo = std::min(lo, radii[c]);
    hi = std::max(hi, radii[c]);
  }
  if(lo < min_domain_radius || hi > max_domain_radius)
    throw Invalid_input(what + " out of the supported range [1e-100, 1e100] (got " + list + ")");
  if(hi > max_domain_aspect * lo)
    throw Invalid_input(what + " too unequal: the largest is more than 1e6 times the smallest (got " + list + ")");
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_VALIDATION_H
