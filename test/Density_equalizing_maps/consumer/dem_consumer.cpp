// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The consumer of an installed copy (see CMakeLists.txt beside it): maps a bumpy
// icosphere it generates onto the unit sphere, area-preserving, and checks what a
// user relies on: the map is fold-over free, every image lies on the sphere, the
// density became more uniform, and the headers state the version the package
// configuration announced. Exit status 0 only when all of this holds.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/version.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
namespace DEM = CGAL::Density_equalizing_maps;

// An icosphere (3 Loop subdivisions, 642 vertices) with radial bumps, so that the
// area distortion of a conformal map is far from uniform.
static Mesh bumpy_icosphere()
{
  Mesh mesh;
  CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.0);
  CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
  for(Mesh::Vertex_index v : vertices(mesh)) {
    const K::Vector_3 d = mesh.point(v) - CGAL::ORIGIN;
    const K::Vector_3 u = d / std::sqrt(d.squared_length());
    const double bump = 1 + 0.25 * std::sin(3 * u.x()) * std::cos(2 * u.y());
    mesh.point(v) = CGAL::ORIGIN + bump * u;
  }
  return mesh;
}

int main()
{
  std::cout << "Density_equalizing_maps " << CGAL_DEM_VERSION_STR << std::endl;
  if(std::string(CGAL_DEM_VERSION_STR) != DEM_CONSUMER_EXPECTED_VERSION) {
    std::cerr << "the headers state version " << CGAL_DEM_VERSION_STR << ", the package configuration "
              << DEM_CONSUMER_EXPECTED_VERSION << std::endl;
    return EXIT_FAILURE;
  }

  Mesh mesh = bumpy_icosphere();
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point_3>("v:sphere").first;

  DEM::Map_report report;
  try {
    report = DEM::spherical_density_equalizing_map(mesh, sphere);   // population = face area
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  double worst_radius_error = 0;
  for(Mesh::Vertex_index v : vertices(mesh))
    worst_radius_error = (std::max)(worst_radius_error,
                                    std::abs(std::sqrt((get(sphere, v) - CGAL::ORIGIN).squared_length()) - 1));
  const std::size_t folds = DEM::number_of_fold_overs(mesh, sphere);
  const DEM::Distortion_statistics d = DEM::map_distortion(mesh, sphere);

  std::cout << num_vertices(mesh) << " vertices, " << report.iterations << " iterations, "
            << folds << " fold-overs, max | |f(v)| - 1 | " << worst_radius_error
            << ", mean |d_area| " << d.mean_abs_darea << std::endl;
  const bool ok = folds == 0 && report.fold_overs == 0 && worst_radius_error < 1e-9 &&
                  d.mean_abs_darea < 0.05;
  std::cout << (ok ? "consumer: OK" : "consumer: FAILED") << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
