// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surface registration (papers 001 §5.1, 003 §5): two genus-0 surfaces and a few
// corresponding landmarks give a dense, bijective correspondence. The target's
// height is carried onto the source through it, and both surfaces are written as
// PLY files coloured by that height (side by side they show the correspondence).
//   surface_registration_example [source.off target.off pairs.txt [source.ply target.ply]]
// pairs.txt: lines "source_vertex target_vertex". Without arguments, a bumpy
// surface is registered to a stretched, independently meshed copy of itself.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <CGAL/Density_equalizing_maps/IO/landmark_pairs.h>
#include <CGAL/Density_equalizing_maps/remeshing.h>
#include <CGAL/Density_equalizing_maps/surface_registration.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;

namespace DEM = CGAL::Density_equalizing_maps;

// a sphere with a bump, meshed with n vertices, stretched along x by `stretch`
Mesh bumpy_surface(std::size_t n, double stretch)
{
  Mesh m;
  DEM::uniform_domain_mesh(DEM::Unit_sphere_domain(), n, m);
  for(vertex_descriptor v : m.vertices()) {
    const Point_3& p = m.point(v);
    const double s = 1 + 0.5 * std::exp(-4 * ((p.x() - 0.6) * (p.x() - 0.6) + p.y() * p.y() + (p.z() - 0.8) * (p.z() - 0.8)));
    m.point(v) = Point_3(stretch * s * p.x(), s * p.y(), 1.2 * s * p.z());
  }
  return m;
}

vertex_descriptor nearest_vertex(const Mesh& m, const Point_3& q)
{
  return *std::min_element(m.vertices().begin(), m.vertices().end(), [&](vertex_descriptor a, vertex_descriptor b) {
    return CGAL::squared_distance(m.point(a), q) < CGAL::squared_distance(m.point(b), q);
  });
}

// ASCII PLY with a blue-to-red colour per face from the mean of a vertex value
template <class Value>
void write_colored(const std::string& file, const Mesh& m, Value value, double lo, double hi)
{
  std::ofstream out(file);
  out << "ply\nformat ascii 1.0\nelement vertex " << m.number_of_vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << m.number_of_faces()
      << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  for(vertex_descriptor v : m.vertices()) out << m.point(v) << "\n";
  for(auto f : m.faces()) {
    double t = 0;
    out << 3;
    for(vertex_descriptor v : vertices_around_face(m.halfedge(f), m)) { out << " " << v.idx(); t += value(v) / 3; }
    t = std::clamp((t - lo) / (hi - lo), 0., 1.);
    out << " " << int(255 * t) << " " << int(255 * (1 - std::abs(2 * t - 1))) << " " << int(255 * (1 - t)) << "\n";
  }
}

int main(int argc, char** argv)
{
  Mesh source, target;
  std::vector<std::pair<vertex_descriptor, vertex_descriptor>> pairs;
  if(argc > 3) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], source) || !CGAL::IO::read_polygon_mesh(argv[2], target)) {
      std::cerr << "cannot read the meshes\n";
      return EXIT_FAILURE;
    }
    for(const auto& p : DEM::IO::read_landmark_pairs(argv[3], source.number_of_vertices(), target.number_of_vertices()))
      pairs.emplace_back(vertex_descriptor(Mesh::size_type(p.first)), vertex_descriptor(Mesh::size_type(p.second)));
  } else {
    source = bumpy_surface(3000, 1.0);
    target = bumpy_surface(3400, 1.3); // another mesh of a stretched copy
    // landmarks: the vertices nearest to the six axis extremities of each surface
    for(const Point_3 d : {Point_3(1, 0, 0), Point_3(-1, 0, 0), Point_3(0, 1, 0), Point_3(0, -1, 0),
                           Point_3(0, 0, 1.5), Point_3(0, 0, -1.2)})
      pairs.emplace_back(nearest_vertex(source, d), nearest_vertex(target, Point_3(1.3 * d.x(), d.y(), d.z())));
  }

  // the correspondence: every source vertex's partner on the target (through LSDEM maps onto the sphere)
  auto partner = source.add_property_map<vertex_descriptor, Point_3>("v:partner").first;
  const DEM::Registration_report report = DEM::register_surfaces(source, target, pairs, partner);

  std::cout << "fold-overs of the two maps (exact): " << report.source_map.fold_overs << ", "
            << report.target_map.fold_overs << "\nlandmark error: mean " << report.landmark_error_mean / report.target_diagonal
            << ", max " << report.landmark_error_max / report.target_diagonal << " of the target's diagonal\n"
            << "registration map: mean |mu| " << report.mean_abs_mu << ", mean |d_area| " << report.mean_abs_darea << "\n";

  // the target's height, and the same field carried onto the source
  double lo = 1e300, hi = -1e300;
  for(vertex_descriptor v : target.vertices()) { lo = std::min(lo, target.point(v).z()); hi = std::max(hi, target.point(v).z()); }
  write_colored(argc > 4 ? argv[4] : "registered_source.ply", source, [&](vertex_descriptor v) { return partner[v].z(); }, lo, hi);
  write_colored(argc > 5 ? argv[5] : "registered_target.ply", target, [&](vertex_descriptor v) { return target.point(v).z(); }, lo, hi);
  return EXIT_SUCCESS;
}
