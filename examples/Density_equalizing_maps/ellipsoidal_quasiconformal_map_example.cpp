// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Landmark-aligned quasi-conformal map onto an ellipsoid (FEQCM): a few
// vertices are pulled toward prescribed points on the ellipsoid; a larger
// landmark weight lambda matches them better at the price of more distortion.
//   ellipsoidal_quasiconformal_map_example [input.off]
// Without an input, a subdivided icosahedron (an icosphere) is used.

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <utility>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, icosphere(3, [](const Point_3& p) { return p; }))) return EXIT_FAILURE;

  const std::array<double, 3> radii = {1., 1., 1.5};
  Point_map ellipsoid = image_map(mesh, "ellipsoid");
  bool bijective = true;
  try {
    // Where the conformal map puts the vertices...
    DEM::ellipsoidal_conformal_map(mesh, ellipsoid, DEM::parameters::ellipsoid_radii(radii));

    // ...and landmarks: three vertices, each sent to its conformal image
    // rotated by 30 degrees about the z axis (targets lie on the ellipsoid).
    std::vector<std::pair<vertex_descriptor, Point_3>> landmarks;
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    std::size_t step = std::max<std::size_t>(1, num_vertices(mesh) / 3), k = 0;
    for(vertex_descriptor v : vertices(mesh)) {
      if(k++ % step != 0 || landmarks.size() == 3) continue;
      const Point_3 p = get(ellipsoid, v);
      const double x = c * p.x() - s * p.y(), y = s * p.x() + c * p.y();
      // the rotated point is scaled back onto the ellipsoid (a = b here, so it already is)
      landmarks.emplace_back(v, Point_3(x, y, p.z()));
    }

    for(double lambda : {0.1, 1., 10.}) {
      const DEM::Map_report report = DEM::ellipsoidal_quasiconformal_map(
        mesh, landmarks, ellipsoid,
        DEM::parameters::combine(DEM::parameters::ellipsoid_radii(radii), DEM::parameters::landmark_weight(lambda)));
      std::cout << "lambda " << lambda << ": mean landmark error " << report.landmark_error << ", fold-overs "
                << report.fold_overs << "\n";
      bijective = bijective && report.is_bijective();
    }
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return bijective ? EXIT_SUCCESS : EXIT_FAILURE;
}
