// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem --repair`: makes a polygon soup from a scan or an export usable by the
// methods, with CGAL's Polygon_mesh_processing repair functions, and says what
// it changed. Off by default: a repaired mesh is not the mesh the user gave,
// and the output has the repaired connectivity.
//
// Steps, in order (each counted):
//  1. merge duplicate points (exactly equal coordinates);
//  2. drop repeated consecutive corners of a polygon, then polygons with
//     fewer than 3 distinct corners;
//  3. remove duplicate polygons (same corners, either orientation), keeping one;
//  4. remove points no polygon uses;
//  5. orient the polygons consistently (orient_polygon_soup; a vertex where
//     that is impossible is duplicated);
//  6. on the halfedge mesh: remove zero-area faces (collinear corners) by edge
//     collapses and flips (remove_degenerate_faces);
//  7. keep the largest connected component (by faces).

#ifndef DEM_TOOL_SOUP_REPAIR_H
#define DEM_TOOL_SOUP_REPAIR_H

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace dem_cli {

/// What `repair_soup()` changed.
struct Soup_repairs
{
  std::size_t merged_points = 0;
  std::size_t simplified_polygons = 0;
  std::size_t removed_invalid_polygons = 0;
  std::size_t removed_duplicate_polygons = 0;
  std::size_t removed_isolated_points = 0;
  std::size_t reoriented_polygons = 0;
  std::size_t duplicated_points = 0;       // non-manifold vertices split by the orientation
  std::size_t removed_degenerate_faces = 0; // net change of the face count in step 6
  std::size_t removed_components = 0;
  std::size_t removed_component_faces = 0;

  bool changed() const
  {
    return merged_points + simplified_polygons + removed_invalid_polygons + removed_duplicate_polygons +
             removed_isolated_points + reoriented_polygons + duplicated_points + removed_degenerate_faces +
             removed_components > 0;
  }

  /// One clause per change, e.g. "merged 12 duplicate points; removed 2 duplicate faces".
  std::string summary() const
  {
    std::string s;
    auto add = [&s](std::size_t n, const char* what) {
      if(n == 0) return;
      s += (s.empty() ? "" : "; ") + std::string(what) + " " + std::to_string(n);
    };
    add(merged_points, "merged duplicate points:");
    add(simplified_polygons, "polygons with a repeated corner simplified:");
    add(removed_invalid_polygons, "removed polygons with fewer than 3 corners:");
    add(removed_duplicate_polygons, "removed duplicate faces:");
    add(removed_isolated_points, "removed unused points:");
    add(reoriented_polygons, "faces reoriented:");
    add(duplicated_points, "non-manifold vertices split:");
    add(removed_degenerate_faces, "removed zero-area faces:");
    if(removed_components)
      s += (s.empty() ? "" : "; ") + std::string("removed small connected components: ") +
           std::to_string(removed_components) + " (" + std::to_string(removed_component_faces) + " faces)";
    return s.empty() ? "nothing to repair" : s;
  }
};

/// True when `q` lists the corners of `p` in the same cyclic order.
inline bool same_cycle(const std::vector<std::size_t>& p, const std::vector<std::size_t>& q)
{
  if(p.size() != q.size()) return false;
  if(p.empty()) return true;
  const auto start = std::find(q.begin(), q.end(), p[0]);
  if(start == q.end()) return false;
  const std::size_t offset = std::size_t(start - q.begin());
  for(std::size_t i = 0; i < p.size(); ++i)
    if(p[i] != q[(i + offset) % q.size()]) return false;
  return true;
}

/// Repairs a soup in place (steps above). `Mesh` is a halfedge mesh type
/// (Surface_mesh) used for steps 6-7; the result is a soup of triangles
/// (non-triangular polygons are left as they are; the caller's validation
/// refuses them).
template <class Mesh, class Point>
Soup_repairs repair_soup(std::vector<Point>& points, std::vector<std::vector<std::size_t> >& polygons)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef typename CGAL::Kernel_traits<Point>::Kernel Kernel;
  Soup_repairs r;
  r.merged_points = PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  r.simplified_polygons = PMP::internal::simplify_polygons_in_polygon_soup(points, polygons, Kernel());
  r.removed_invalid_polygons = PMP::internal::remove_invalid_polygons_in_polygon_soup(points, polygons);
  r.removed_duplicate_polygons = PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons);
  r.removed_isolated_points = PMP::remove_isolated_points_in_polygon_soup(points, polygons);

  const std::vector<std::vector<std::size_t> > before = polygons;
  const std::size_t points_before = points.size();
  PMP::orient_polygon_soup(points, polygons);
  r.duplicated_points = points.size() - points_before;
  auto count_changed = [&] {
    std::size_t n = 0;
    for(std::size_t k = 0; k < polygons.size() && k < before.size(); ++k) n += !same_cycle(polygons[k], before[k]);
    return n;
  };
  r.reoriented_polygons = count_changed();
  // orient_polygon_soup keeps the orientation of the face it starts from; if
  // that was one of the flipped ones, reverse them all (the methods accept
  // either global orientation), so that the fewest faces change
  if(r.duplicated_points == 0 && polygons.size() == before.size() && 2 * r.reoriented_polygons > polygons.size()) {
    for(auto& p : polygons) std::reverse(p.begin(), p.end());
    r.reoriented_polygons = count_changed();
  }

  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  const std::size_t faces_before = num_faces(mesh);
  if(CGAL::is_triangle_mesh(mesh)) PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  r.removed_degenerate_faces = faces_before - std::min(faces_before, std::size_t(num_faces(mesh)));
  const std::size_t faces_with_all = num_faces(mesh);
  r.removed_components = PMP::keep_largest_connected_components(mesh, 1);
  mesh.collect_garbage();
  r.removed_component_faces = faces_with_all - num_faces(mesh);

  points.clear();
  polygons.clear();
  for(auto v : vertices(mesh)) points.push_back(mesh.point(v));
  for(auto f : faces(mesh)) {
    std::vector<std::size_t> p;
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) p.push_back(std::size_t(v.idx()));
    polygons.push_back(p);
  }
  return r;
}

} // namespace dem_cli

#endif // DEM_TOOL_SOUP_REPAIR_H
