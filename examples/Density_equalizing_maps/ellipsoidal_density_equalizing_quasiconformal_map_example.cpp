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

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>

#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/measures.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3                                          Point_3;
typedef CGAL::Surface_mesh<Point_3>                         Mesh;
typedef Mesh::Vertex_index                                  vertex_descriptor;
typedef Mesh::Face_index                                    face_descriptor;

namespace DEM = CGAL::Density_equalizing_maps;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(argc > 1) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh) || !CGAL::is_triangle_mesh(mesh)) {
      std::cerr << "cannot read a triangle mesh from " << argv[1] << std::endl;
      return EXIT_FAILURE;
    }
  } else {
    CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.0);
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(3));
    for(vertex_descriptor v : vertices(mesh)) {
      const Point_3& p = mesh.point(v);
      const double r = std::sqrt((p - CGAL::ORIGIN).squared_length());
      mesh.point(v) = Point_3(p.x() / r, 0.8 * p.y() / r, 1.6 * p.z() / r);
    }
  }
  const std::string output = argc > 2 ? argv[2] : "ellipsoidal_density_equalizing_quasiconformal_map.off";

  // population = area x density, the density a smooth step from 1 to 5 along z
  const CGAL::Bbox_3 box = PMP::bbox(mesh);
  Mesh::Property_map<face_descriptor, double> population =
    mesh.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(face_descriptor f : faces(mesh)) {
    const auto h = halfedge(f, mesh);
    const Point_3 c = CGAL::centroid(mesh.point(source(h, mesh)), mesh.point(target(h, mesh)),
                                     mesh.point(target(next(h, mesh), mesh)));
    const double t = std::clamp((c.z() - box.zmin()) / (box.zmax() - box.zmin()) * 2 - 0.5, 0., 1.);
    put(population, f, PMP::face_area(f, mesh) * (1 + 4 * t * t * (3 - 2 * t)));
  }

  Mesh::Property_map<vertex_descriptor, Point_3> ellipsoid_point =
    mesh.add_property_map<vertex_descriptor, Point_3>("v:ellipsoid_point").first;

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

  Mesh out = mesh;
  for(vertex_descriptor v : vertices(out)) out.point(v) = get(ellipsoid_point, v);
  if(!CGAL::IO::write_polygon_mesh(output, out, CGAL::parameters::stream_precision(17))) {
    std::cerr << "cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "wrote " << output << std::endl;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
