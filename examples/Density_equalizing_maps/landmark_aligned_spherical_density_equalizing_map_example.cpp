// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Landmark-aligned spherical density-equalizing map (LSDEM): an area-preserving
// map onto the unit sphere (population = face area, the default) that also
// sends chosen landmark vertices to prescribed points of the sphere. Here the
// six extreme vertices of the input along -x, +x, -y, +y, -z, +z are sent to
// the points of the sphere on the coordinate axes, rotated by 20 degrees about z.
//   landmark_aligned_spherical_density_equalizing_map_example [input.off [output.off]]
// Without an input, a subdivided icosahedron stretched 1.8 times along z is used.

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, icosphere(3, [](const Point_3& p) { return Point_3(p.x(), p.y(), 1.8 * p.z()); })))
    return EXIT_FAILURE;
  const std::string output = argc > 2 ? argv[2] : "landmark_aligned_spherical_density_equalizing_map.off";

  // landmarks: (vertex, target on the unit sphere) pairs
  std::vector<std::pair<vertex_descriptor, Point_3> > landmarks;
  const double c = std::cos(M_PI / 9), s = std::sin(M_PI / 9);
  for(int axis = 0; axis < 3; ++axis)
    for(int sign : {-1, 1}) {
      vertex_descriptor best = *vertices(mesh).begin();
      for(vertex_descriptor v : vertices(mesh))
        if(sign * mesh.point(v)[axis] > sign * mesh.point(best)[axis]) best = v;
      double t[3] = {0, 0, 0};
      t[axis] = sign;
      landmarks.emplace_back(best, Point_3(c * t[0] - s * t[1], s * t[0] + c * t[1], t[2]));
    }

  Point_map sphere_point = image_map(mesh, "sphere_point");

  DEM::Map_report report;
  try {
    // weights of the density, harmonic and landmark terms (the defaults, spelled out)
    report = DEM::landmark_aligned_spherical_density_equalizing_map(
      mesh, landmarks, sphere_point,
      DEM::parameters::combine(DEM::parameters::density_weight(1.), DEM::parameters::harmonic_weight(2.),
                               DEM::parameters::landmark_weight(5.)));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  const DEM::Distortion_statistics d = DEM::map_distortion(mesh, sphere_point);
  std::cout << "vertices: " << num_vertices(mesh) << ", faces: " << num_faces(mesh) << "\n"
            << "iterations: " << report.iterations << " (" << DEM::to_string(report.termination) << ")\n"
            << "mean landmark error: " << report.landmark_error << "\n"
            << "mean |d_area|: " << d.mean_abs_darea << ", mean |mu|: " << d.mean_abs_mu << "\n"
            << "fold-overs (exact count): " << report.fold_overs << "\n"
            << (report.message.empty() ? "" : "note: " + report.message + "\n");

  if(!write_mapped_mesh(mesh, sphere_point, output)) return EXIT_FAILURE;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
