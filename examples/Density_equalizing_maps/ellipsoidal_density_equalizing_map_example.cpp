// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Ellipsoidal density-equalizing map (EDEM): the density-equalizing flow of
// SDEM on an ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1. Faces carry a
// population (here: face area times a density rising from 1 to 10 along z);
// on the output ellipsoid, image areas are proportional to it.
//   ellipsoidal_density_equalizing_map_example [input.off [output.off]]
// Without an input, a subdivided icosahedron scaled to the ellipsoid (1, 1, 1.5)
// is mapped onto that ellipsoid; an input is mapped onto its bounding-box
// ellipsoid (the default radii).

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/measures.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <string>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  const std::array<double, 3> radii = {1., 1., 1.5};
  auto onto_ellipsoid = [&](const Point_3& p) { return Point_3(radii[0] * p.x(), radii[1] * p.y(), radii[2] * p.z()); };
  if(!input_mesh(argc, argv, mesh, icosphere(3, onto_ellipsoid))) return EXIT_FAILURE;
  const std::string output = argc > 2 ? argv[2] : "ellipsoidal_density_equalizing_map.off";

  // population = area x density, the density a smooth step from 1 to 10 along z
  const Face_map population = smooth_step_population(mesh, 10.);

  Point_map ellipsoid_point = image_map(mesh, "ellipsoid_point");

  DEM::Map_report report;
  try {
    // the initial map is the ellipsoidal conformal map with the same radii;
    // defaults: time step 0.1, tolerance 1e-3, at most 300 iterations
    if(argc > 1)
      report = DEM::ellipsoidal_density_equalizing_map(mesh, ellipsoid_point,
                                                       DEM::parameters::face_population_map(population));
    else
      report = DEM::ellipsoidal_density_equalizing_map(
        mesh, ellipsoid_point,
        DEM::parameters::combine(DEM::parameters::ellipsoid_radii(radii),
                                 DEM::parameters::face_population_map(population)));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // the variance of the normalized face density (population / image area)
  const DEM::Density_variance v =
    DEM::density_variance(mesh, ellipsoid_point, DEM::parameters::face_population_map(population));
  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "radii: " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2] << "\n"
            << "iterations: " << report.iterations << " (" << DEM::to_string(report.termination) << ")\n"
            << "sd/mean of the density: " << report.initial_error << " -> " << report.final_error << "\n"
            << "Var(normalized face density): " << v.face << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << (report.message.empty() ? "" : "note: " + report.message + "\n");

  if(!write_mapped_mesh(mesh, ellipsoid_point, output)) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
