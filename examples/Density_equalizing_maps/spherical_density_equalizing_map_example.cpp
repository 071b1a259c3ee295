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

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, icosphere(3, [](const Point_3& p) { return p; }))) return EXIT_FAILURE;
  const std::string output = argc > 2 ? argv[2] : "spherical_density_equalizing_map.off";

  // population = area x density, the density a smooth step from 1 to 10 along z
  const Face_map population = smooth_step_population(mesh, 10.);
  const auto np = DEM::parameters::face_population_map(population);

  // the image of every vertex on the unit sphere
  Point_map sphere_point = image_map(mesh, "sphere_point");

  DEM::Map_report report;
  try {
    // defaults: time step 0.1, stop when sd/mean of the density < 1e-3, at most
    // 200 iterations; the initial map is the spherical conformal map with the
    // Moebius area correction
    report = DEM::spherical_density_equalizing_map(mesh, sphere_point, np);
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // Var of the normalized vertex density (population / area) before and after
  Point_map conformal = image_map(mesh, "conformal");
  DEM::spherical_conformal_map(mesh, conformal, DEM::parameters::mobius_area_correction(true));
  const double before = DEM::density_variance(mesh, conformal, np).vertex;
  const double after = DEM::density_variance(mesh, sphere_point, np).vertex;

  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "iterations: " << report.iterations << " (" << DEM::to_string(report.termination) << ")\n"
            << "sd/mean of the density: " << report.initial_error << " -> " << report.final_error << "\n"
            << "Var(normalized vertex density), conformal map -> SDEM: " << before << " -> " << after << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << (report.message.empty() ? "" : "note: " + report.message + "\n");

  if(!write_mapped_mesh(mesh, sphere_point, output)) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
