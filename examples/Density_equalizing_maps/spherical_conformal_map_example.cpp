// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Maps a genus-0 closed triangle mesh conformally onto the unit sphere, with
// the Moebius area correction, and writes the spherical mesh.
//   spherical_conformal_map_example [input.off [output.off]]
// Without an input, a stretched subdivided icosahedron is used.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3                                          Point_3;
typedef CGAL::Surface_mesh<Point_3>                         Mesh;
typedef Mesh::Vertex_index                                  vertex_descriptor;

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
    // an icosphere stretched along x: a conformal map of it distorts areas
    CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.0);
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    for(vertex_descriptor v : vertices(mesh)) {
      const Point_3& p = mesh.point(v);
      mesh.point(v) = Point_3(2.5 * p.x(), p.y(), p.z());
    }
  }
  const std::string output = argc > 2 ? argv[2] : "spherical_conformal_map.off";

  // the image of every vertex on the unit sphere, stored in a vertex property
  Mesh::Property_map<vertex_descriptor, Point_3> sphere_point =
    mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere_point").first;

  DEM::Map_report report;
  try {
    report = DEM::spherical_conformal_map(mesh, sphere_point,
                                          DEM::parameters::mobius_area_correction(true));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // Area distortion: mean |log(normalized image area / normalized input area)|.
  // PMP::face_area reads the positions through our output map.
  const double input_area = PMP::area(mesh);
  const double sphere_area = PMP::area(mesh, CGAL::parameters::vertex_point_map(sphere_point));
  double mean_abs_log_area_ratio = 0;
  for(Mesh::Face_index f : faces(mesh)) {
    const double a = PMP::face_area(f, mesh) / input_area;
    const double b = PMP::face_area(f, mesh, CGAL::parameters::vertex_point_map(sphere_point)) / sphere_area;
    mean_abs_log_area_ratio += std::abs(std::log(b / a));
  }
  mean_abs_log_area_ratio /= num_faces(mesh);

  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << "bijective: " << (report.is_bijective() ? "yes" : "no") << "\n"
            << "Tutte fallback used: " << (report.used_tutte_fallback ? "yes" : "no") << "\n"
            << "mean |log area ratio|: " << mean_abs_log_area_ratio << std::endl;

  // write the spherical mesh: same connectivity, the vertices on the sphere
  Mesh sphere_mesh = mesh;
  for(vertex_descriptor v : vertices(sphere_mesh))
    sphere_mesh.point(v) = sphere_point[v];
  if(!CGAL::IO::write_polygon_mesh(output, sphere_mesh, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "wrote " << output << std::endl;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
