// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Maps a genus-0 mesh conformally onto an ellipsoid: first with the
// bounding-box radii, then with radii optimized for low area distortion.
//   ellipsoidal_conformal_map_example [input.off [output.off]]
// Without an input, an icosahedron scaled by (1, 0.7, 1.8) is used.

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>

#include <cstdlib>
#include <iostream>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh,
                 icosphere(0, [](const Point_3& p) { return Point_3(p.x(), 0.7 * p.y(), 1.8 * p.z()); })))
    return EXIT_FAILURE;

  Point_map ellipsoid = image_map(mesh, "ellipsoid");
  DEM::Map_report report;
  try {
    // Default: bounding-box radii of the centred, principal-axis aligned mesh (mean 1).
    report = DEM::ellipsoidal_conformal_map(mesh, ellipsoid);
    std::cout << "radii " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2]
              << ", fold-overs " << report.fold_overs << "\n";

    // Radii optimized for area distortion (the map stays conformal).
    report = DEM::ellipsoidal_conformal_map(mesh, ellipsoid, DEM::parameters::optimize_radii(true));
    std::cout << "optimized radii " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2]
              << ", " << report.message << ", fold-overs " << report.fold_overs << "\n";
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << "\n";
    return EXIT_FAILURE;
  }

  if(argc > 2 && !write_mapped_mesh(mesh, ellipsoid, argv[2])) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
