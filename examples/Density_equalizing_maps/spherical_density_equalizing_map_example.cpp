// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Spherical density-equalizing map (SDEM): faces carry a "population"; the map
// onto the unit sphere gives every face an image area proportional to it, so
// densely populated regions are enlarged. Here the population is the face area
// times a density that rises from 1 (bottom) to 10 (top) along z.
//   spherical_density_equalizing_map_example [input.off [output.off]]
// Without an input, a subdivided icosahedron (an icosphere) is used.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3                                          Point_3;
typedef CGAL::Surface_mesh<Point_3>                         Mesh;
typedef Mesh::Vertex_index                                  vertex_descriptor;
typedef Mesh::Face_index                                    face_descriptor;

namespace DEM = CGAL::Density_equalizing_maps;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(argc > 1) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
      std::cerr << "cannot read a triangle mesh from " << argv[1] << std::endl;
      return EXIT_FAILURE;
    }
  } else {
    CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.0);
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    for(vertex_descriptor v : vertices(mesh)) { // onto the unit sphere
      const K::Vector_3 d = mesh.point(v) - CGAL::ORIGIN;
      mesh.point(v) = CGAL::ORIGIN + d / std::sqrt(d.squared_length());
    }
  }
  const std::string output = argc > 2 ? argv[2] : "spherical_density_equalizing_map.off";

  // population = area x density, the density a smooth step from 1 to 10 along z
  const CGAL::Bbox_3 box = PMP::bbox(mesh);
  Mesh::Property_map<face_descriptor, double> population =
    mesh.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(face_descriptor f : faces(mesh)) {
    const auto h = halfedge(f, mesh);
    const Point_3 c = CGAL::centroid(mesh.point(source(h, mesh)), mesh.point(target(h, mesh)),
                                     mesh.point(target(next(h, mesh), mesh)));
    const double t = std::clamp((c.z() - box.zmin()) / (box.zmax() - box.zmin()) * 2 - 0.5, 0., 1.);
    put(population, f, PMP::face_area(f, mesh) * (1 + 9 * t * t * (3 - 2 * t)));
  }

  // the image of every vertex on the unit sphere
  Mesh::Property_map<vertex_descriptor, Point_3> sphere_point =
    mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere_point").first;

  DEM::Map_report report;
  try {
    // defaults: time step 0.1, stop when sd/mean of the density < 1e-3, at most
    // 200 iterations; the initial map is the spherical conformal map with the
    // Moebius area correction
    report = DEM::spherical_density_equalizing_map(mesh, sphere_point,
                                                   DEM::parameters::face_population_map(population));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // Var of the normalized vertex density (population / area) before and after
  const auto np = DEM::parameters::face_population_map(population);
  Mesh::Property_map<vertex_descriptor, Point_3> conformal =
    mesh.add_property_map<vertex_descriptor, Point_3>("v:conformal").first;
  DEM::spherical_conformal_map(mesh, conformal, DEM::parameters::mobius_area_correction(true));
  const double before = DEM::density_variance(mesh, conformal, np).vertex;
  const double after = DEM::density_variance(mesh, sphere_point, np).vertex;

  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "iterations: " << report.iterations << " (" << DEM::to_string(report.termination) << ")\n"
            << "sd/mean of the density: " << report.initial_error << " -> " << report.final_error << "\n"
            << "Var(normalized vertex density), conformal map -> SDEM: " << before << " -> " << after << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << (report.message.empty() ? "" : "note: " + report.message + "\n");

  Mesh sphere = mesh; // same connectivity, vertices moved onto the sphere
  for(vertex_descriptor v : vertices(sphere)) sphere.point(v) = get(sphere_point, v);
  if(!CGAL::IO::write_polygon_mesh(output, sphere, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "wrote " << output << std::endl;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
