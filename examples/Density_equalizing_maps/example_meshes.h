// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What every example does around its one call of the package, written once:
// read the mesh named on the command line or build the example's own surface,
// give the faces a population, and write the mapped mesh. The examples
// themselves then show only how a method is called and what it reports.

#ifndef DEM_EXAMPLE_MESHES_H
#define DEM_EXAMPLE_MESHES_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace example {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef K::Point_2 Point_2;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;
typedef Mesh::Halfedge_index halfedge_descriptor;
typedef Mesh::Property_map<vertex_descriptor, Point_3> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_map;

/// A vertex property receiving a map's image points.
inline Point_map image_map(Mesh& mesh, const std::string& name)
{
  return mesh.add_property_map<vertex_descriptor, Point_3>("v:" + name).first;
}

/// An icosahedron subdivided `levels` times (Loop) with its vertices on the
/// unit sphere, then each vertex moved by `shape` (a Point_3 -> Point_3).
template <class Shape>
Mesh icosphere(int levels, Shape shape)
{
  Mesh mesh;
  CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.0);
  if(levels > 0) CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(levels));
  for(vertex_descriptor v : vertices(mesh)) {
    const K::Vector_3 d = mesh.point(v) - CGAL::ORIGIN;
    mesh.point(v) = shape(CGAL::ORIGIN + d / std::sqrt(d.squared_length()));
  }
  return mesh;
}

/// A regular nu x nv triangulation of the closed surface swept by the circle
/// of radius r(a) about the circle of radius R: (a, b) -> ((R + r(a) cos b) cos a,
/// (R + r(a) cos b) sin a, r(a) sin b); counter-clockwise seen from outside.
template <class TubeRadius>
Mesh torus(double R, TubeRadius r, int nu, int nv)
{
  Mesh m;
  std::vector<vertex_descriptor> v;
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      const double a = 2 * M_PI * i / nu, b = 2 * M_PI * j / nv, ra = r(a);
      v.push_back(m.add_vertex(Point_3((R + ra * std::cos(b)) * std::cos(a), (R + ra * std::cos(b)) * std::sin(a),
                                       ra * std::sin(b))));
    }
  auto id = [&](int i, int j) { return v[((i + nu) % nu) * nv + (j + nv) % nv]; };
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      m.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

/// The triangle mesh of the file `argv[1]` when there is one (false, with a
/// message, when it cannot be read), else the example's own `generated` mesh.
inline bool input_mesh(int argc, char** argv, Mesh& mesh, const Mesh& generated)
{
  if(argc <= 1) {
    mesh = generated;
    return true;
  }
  if(!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
    std::cerr << "cannot read a triangle mesh from " << argv[1] << std::endl;
    return false;
  }
  return true;
}

/// Population = face area x a density rising smoothly (smoothstep) from 1 at
/// the bottom quarter to `top` at the top quarter of the bounding box in z.
inline Face_map smooth_step_population(Mesh& mesh, double top)
{
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(mesh);
  Face_map population = mesh.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(face_descriptor f : faces(mesh)) {
    const auto h = halfedge(f, mesh);
    const Point_3 c = CGAL::centroid(mesh.point(source(h, mesh)), mesh.point(target(h, mesh)),
                                     mesh.point(target(next(h, mesh), mesh)));
    const double t = std::clamp((c.z() - box.zmin()) / (box.zmax() - box.zmin()) * 2 - 0.5, 0., 1.);
    put(population, f, CGAL::Polygon_mesh_processing::face_area(f, mesh) * (1 + (top - 1) * t * t * (3 - 2 * t)));
  }
  return population;
}

/// Writes the mesh with every vertex at its image (same connectivity).
inline bool write_mapped_mesh(const Mesh& mesh, Point_map image, const std::string& file)
{
  Mesh mapped = mesh;
  for(vertex_descriptor v : vertices(mapped)) mapped.point(v) = get(image, v);
  if(!CGAL::IO::write_polygon_mesh(file, mapped, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << file << std::endl;
    return false;
  }
  std::cout << "wrote " << file << std::endl;
  return true;
}

} // namespace example

#endif // DEM_EXAMPLE_MESHES_H
