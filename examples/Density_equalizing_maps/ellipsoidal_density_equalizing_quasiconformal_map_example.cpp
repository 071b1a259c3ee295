// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Ellipsoidal density-equalizing quasi-conformal map (EDEQ): like EDEM, but
// the radii of the target ellipsoid are searched too, lowering an energy that
// combines the density gradient and the conformal distortion (weight
// beltrami_weight). The radius a is kept; b and c are found.
//   ellipsoidal_density_equalizing_quasiconformal_map_example [input.off [output.off]]
// Without an input, a subdivided icosahedron scaled to (1, 0.8, 1.6) carries a
// population dense at the top, and the search starts from the radii (1, 1, 1.2).
// An input starts from its bounding-box radii.

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
  auto scaled = [](const Point_3& p) { return Point_3(p.x(), 0.8 * p.y(), 1.6 * p.z()); };
  if(!input_mesh(argc, argv, mesh, icosphere(3, scaled))) return EXIT_FAILURE;
  const std::string output = argc > 2 ? argv[2] : "ellipsoidal_density_equalizing_quasiconformal_map.off";

  // population = area x density, the density a smooth step from 1 to 5 along z
  const Face_map population = smooth_step_population(mesh, 5.);

  Point_map ellipsoid_point = image_map(mesh, "ellipsoid_point");

  DEM::Map_report report;
  try {
    // alpha = 5 (the default) weighs the Beltrami term; stop on a relative
    // energy change below 1e-5 or after 300 iterations
    const auto np = DEM::parameters::combine(DEM::parameters::face_population_map(population),
                                             DEM::parameters::beltrami_weight(5.));
    if(argc > 1)
      report = DEM::ellipsoidal_density_equalizing_quasiconformal_map(mesh, ellipsoid_point, np);
    else
      report = DEM::ellipsoidal_density_equalizing_quasiconformal_map(
        mesh, ellipsoid_point,
        DEM::parameters::combine(np, DEM::parameters::ellipsoid_radii(std::array<double, 3>{1., 1., 1.2})));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  const DEM::Density_variance v =
    DEM::density_variance(mesh, ellipsoid_point, DEM::parameters::face_population_map(population));
  const DEM::Distortion_statistics d = DEM::map_distortion(mesh, ellipsoid_point);
  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "radii found: " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2] << "\n"
            << "iterations: " << report.iterations << " (" << DEM::to_string(report.termination) << ")\n"
            << "Var(normalized face density): " << v.face << ", mean |mu|: " << d.mean_abs_mu << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << (report.message.empty() ? "" : "note: " + report.message + "\n");

  if(!write_mapped_mesh(mesh, ellipsoid_point, output)) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
