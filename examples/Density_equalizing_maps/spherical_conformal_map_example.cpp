// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Maps a genus-0 closed triangle mesh conformally onto the unit sphere, with
// the Moebius area correction, and writes the spherical mesh.
//   spherical_conformal_map_example [input.off [output.off]]
// Without an input, a subdivided icosahedron stretched 2.5 times along x is used.
// example_meshes.h holds what all examples share (reading or generating the
// input, writing the output).

#include "example_meshes.h"

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace DEM = CGAL::Density_equalizing_maps;
namespace PMP = CGAL::Polygon_mesh_processing;
using namespace example;

int main(int argc, char** argv)
{
  // a stretched sphere: a conformal map of it distorts areas
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, icosphere(3, [](const Point_3& p) { return Point_3(2.5 * p.x(), p.y(), p.z()); })))
    return EXIT_FAILURE;
  const std::string output = argc > 2 ? argv[2] : "spherical_conformal_map.off";

  // the image of every vertex on the unit sphere, stored in a vertex property
  Point_map sphere_point = image_map(mesh, "sphere_point");

  DEM::Map_report report;
  try {
    report = DEM::spherical_conformal_map(mesh, sphere_point, DEM::parameters::mobius_area_correction(true));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // Area distortion: mean |log(normalized image area / normalized input area)|.
  // PMP::face_area reads the positions through our output map.
  const double input_area = PMP::area(mesh);
  const double sphere_area = PMP::area(mesh, CGAL::parameters::vertex_point_map(sphere_point));
  double mean_abs_log_area_ratio = 0;
  for(face_descriptor f : faces(mesh)) {
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

  // the spherical mesh: same connectivity, the vertices on the sphere
  if(!write_mapped_mesh(mesh, sphere_point, output)) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
