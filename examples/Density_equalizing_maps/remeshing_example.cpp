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

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <CGAL/Density_equalizing_maps/remeshing.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;

namespace DEM = CGAL::Density_equalizing_maps;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(argc > 1) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh)) { std::cerr << "cannot read " << argv[1] << "\n"; return EXIT_FAILURE; }
  } else {
    // a sphere with a large bump: a conformal map shrinks the bump's image
    DEM::uniform_domain_mesh(DEM::Unit_sphere_domain(), 4000, mesh);
    for(vertex_descriptor v : mesh.vertices()) {
      const Point_3& p = mesh.point(v);
      const double s = 1 + 0.8 * std::exp(-8 * ((p.x() - 1) * (p.x() - 1) + p.y() * p.y() + p.z() * p.z()));
      mesh.point(v) = Point_3(s * p.x(), s * p.y(), s * p.z());
    }
  }
  const std::size_t vertices = argc > 2 ? std::size_t(std::atol(argv[2])) : 2000;

  // two maps onto the unit sphere
  auto conformal = mesh.add_property_map<vertex_descriptor, Point_3>("v:conformal").first;
  auto equalized = mesh.add_property_map<vertex_descriptor, Point_3>("v:sdem").first;
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
