// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Toroidal density-equalizing map (TDEM): a mesh lying on the torus (R, r) is
// deformed on the torus so that the faces' areas become proportional to a
// prescribed population. Writes the mapped torus mesh and the flat-torus
// coordinates (u, v) of every vertex.
//   toroidal_density_equalizing_map_example [input.off population.txt R r [output.off]]
// Without arguments, a torus (R, r) = (3, 1) is generated and given a
// population twice as dense in a disk around one point as elsewhere (the
// "ball on a torus" of Yao and Choi, Fig. 10).

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace DEM = CGAL::Density_equalizing_maps;
namespace params = DEM::parameters;
using namespace example;

int main(int argc, char** argv)
{
  Mesh mesh;
  std::array<double, 2> radii{3, 1};
  auto population = mesh.add_property_map<face_descriptor, double>("f:population", 1.).first;
  if(argc > 4) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
      std::cerr << "cannot read a triangle mesh from " << argv[1] << std::endl;
      return EXIT_FAILURE;
    }
    population = mesh.add_property_map<face_descriptor, double>("f:population", 1.).first;
    std::ifstream in(argv[2]);
    for(face_descriptor f : faces(mesh))
      if(!(in >> population[f])) { std::cerr << "too few values in " << argv[2] << std::endl; return EXIT_FAILURE; }
    radii = {std::atof(argv[3]), std::atof(argv[4])};
  } else {
    mesh = torus(radii[0], [&](double) { return radii[1]; }, 80, 40);
    population = mesh.add_property_map<face_descriptor, double>("f:population", 1.).first;
    // population 2 per unit area within distance 1.2 of the outer equator point (R + r, 0, 0), 1 elsewhere
    const Point_3 center(radii[0] + radii[1], 0, 0);
    for(face_descriptor f : faces(mesh)) {
      const auto h = mesh.halfedge(f);
      const Point_3 &p = mesh.point(mesh.source(h)), &q = mesh.point(mesh.target(h)),
                    &s = mesh.point(mesh.target(mesh.next(h)));
      const double area = std::sqrt(CGAL::squared_area(p, q, s));
      population[f] = area * (CGAL::squared_distance(CGAL::centroid(p, q, s), center) < 1.44 ? 2. : 1.);
    }
  }
  const std::string output = argc > 5 ? argv[5] : "toroidal_density_equalizing_map.off";

  Point_map torus_point = image_map(mesh, "torus_point");
  auto flat_point = mesh.add_property_map<vertex_descriptor, Point_2>("v:flat_torus_point").first;

  DEM::Map_report report;
  try {
    // CGAL 5.5 cannot append the package's own names to a chain: join them with combine()
    report = DEM::toroidal_density_equalizing_map(
      mesh, torus_point,
      params::combine(params::torus_radii(radii), params::face_population_map(population),
                      params::flat_torus_coordinates(flat_point)));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  std::cout << "TDEM: " << report.iterations << " iterations (" << DEM::to_string(report.termination)
            << "), sd/mean of the density " << report.initial_error << " -> " << report.final_error
            << ", fold-overs " << report.fold_overs << std::endl;

  if(!write_mapped_mesh(mesh, torus_point, output)) return EXIT_FAILURE;
  std::ofstream uv(output + ".uv.txt");
  uv.precision(17);
  for(vertex_descriptor v : vertices(mesh)) uv << flat_point[v].x() << " " << flat_point[v].y() << "\n";
  std::cout << "wrote " << output << " and " << output << ".uv.txt" << std::endl;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
