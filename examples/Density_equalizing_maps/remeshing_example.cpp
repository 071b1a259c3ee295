// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Remeshing through a map (paper 000 Sec. 5): a uniform mesh of the sphere is
// pulled back to the surface through a conformal and through an
// area-preserving density-equalizing map. The conformal route keeps the
// triangles' shapes but not their sizes; the density-equalizing route makes
// the sizes uniform on the surface.
//   remeshing_example [input.off [vertices [conformal.off density.off]]]
// Without an input, a bumpy sphere is remeshed.

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/remeshing.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace DEM = CGAL::Density_equalizing_maps;
using namespace example;

int main(int argc, char** argv)
{
  // a sphere with a large bump: a conformal map shrinks the bump's image
  auto bump = [](const Point_3& p) {
    const double s = 1 + 0.8 * std::exp(-8 * ((p.x() - 1) * (p.x() - 1) + p.y() * p.y() + p.z() * p.z()));
    return Point_3(s * p.x(), s * p.y(), s * p.z());
  };
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, icosphere(5, bump))) return EXIT_FAILURE;
  const std::size_t vertices = argc > 2 ? std::size_t(std::atol(argv[2])) : 2000;

  // two maps onto the unit sphere
  Point_map conformal = image_map(mesh, "conformal");
  Point_map equalized = image_map(mesh, "sdem");
  DEM::spherical_conformal_map(mesh, conformal);
  DEM::spherical_density_equalizing_map(mesh, equalized); // default population: face areas

  // pull a uniform sphere mesh back through each
  Mesh through_conformal, through_equalized;
  const DEM::Remeshing_report rc =
    DEM::remesh_through_map(mesh, conformal, DEM::Unit_sphere_domain(), vertices, through_conformal);
  const DEM::Remeshing_report re =
    DEM::remesh_through_map(mesh, equalized, DEM::Unit_sphere_domain(), vertices, through_equalized);

  std::cout << "domain mesh:              delta_size " << rc.domain_delta_size << ", delta_shape "
            << rc.domain_delta_shape << "\n"
            << "through the conformal map: delta_size " << rc.delta_size << ", delta_shape " << rc.delta_shape << "\n"
            << "through SDEM:              delta_size " << re.delta_size << ", delta_shape " << re.delta_shape << "\n";
  if(argc > 4) {
    CGAL::IO::write_polygon_mesh(argv[3], through_conformal, CGAL::parameters::stream_precision(17));
    CGAL::IO::write_polygon_mesh(argv[4], through_equalized, CGAL::parameters::stream_precision(17));
  }
  return EXIT_SUCCESS;
}
