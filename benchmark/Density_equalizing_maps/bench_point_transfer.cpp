// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Point transfer and remeshing speed (issue 12, items 1 and 7):
//   bench_point_transfer [faces [queries [remesh_vertices [repeats]]]]
// A bumpy sphere with about `faces` faces is mapped conformally (FLASH, not
// timed); then, each `repeats` times (medians printed):
//   prepare  - Point_transfer construction (validation, adjacency, buckets)
//   coherent - `queries` pull-backs of points along a space-filling order
//              (consecutive queries close: walks from the previous answer)
//   random   - `queries` pull-backs of independent random directions
//   domain   - uniform_domain_mesh with `remesh_vertices` vertices
//   remesh   - remesh_through_map to `remesh_vertices` vertices (domain mesh included)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Density_equalizing_maps/point_transfer.h>
#include <CGAL/Density_equalizing_maps/remeshing.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
namespace DEM = CGAL::Density_equalizing_maps;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
  const std::size_t faces = argc > 1 ? std::size_t(std::atol(argv[1])) : 100000;
  const std::size_t queries = argc > 2 ? std::size_t(std::atol(argv[2])) : 1000000;
  const std::size_t remesh_vertices = argc > 3 ? std::size_t(std::atol(argv[3])) : 10000;
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 5;

  Mesh mesh;
  DEM::uniform_domain_mesh(DEM::Unit_sphere_domain(), faces / 2 + 2, mesh);
  for(vertex_descriptor v : mesh.vertices()) {
    const Point_3& p = mesh.point(v);
    const double s = 1 + 0.2 * std::sin(3 * p.x()) * std::cos(2 * p.y() + 0.5) * std::sin(4 * p.z() + 0.3);
    mesh.point(v) = Point_3(s * p.x(), s * p.y(), s * p.z());
  }
  auto sphere = mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere").first;
  DEM::spherical_conformal_map(mesh, sphere);

  // coherent queries: directions in a latitude-longitude raster (consecutive ones close)
  std::vector<Point_3> coherent, random;
  const std::size_t rows = std::size_t(std::sqrt(double(queries) / 2)) + 1, cols = queries / rows + 1;
  for(std::size_t i = 0; i < rows && coherent.size() < queries; ++i)
    for(std::size_t j = 0; j < cols && coherent.size() < queries; ++j) {
      const double theta = M_PI * (i + 0.5) / rows, phi = 2 * M_PI * ((i % 2) ? cols - 1 - j : j) / cols;
      coherent.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  for(std::size_t i = 0; i < queries; ++i) random.emplace_back(g(rng), g(rng), g(rng));

  std::vector<double> t_prepare, t_coherent, t_random, t_domain, t_remesh;
  double checksum = 0;
  for(int r = 0; r < repeats; ++r) {
    double t0 = now();
    const DEM::Point_transfer<Mesh> transfer(mesh, sphere, DEM::Unit_sphere_domain());
    t_prepare.push_back(now() - t0);
    t0 = now();
    for(const Point_3& q : coherent) checksum += transfer.pull_back(q).x();
    t_coherent.push_back(now() - t0);
    t0 = now();
    for(const Point_3& q : random) checksum += transfer.pull_back(q).x();
    t_random.push_back(now() - t0);
    Mesh d, out;
    t0 = now();
    DEM::uniform_domain_mesh(DEM::Unit_sphere_domain(), remesh_vertices, d);
    t_domain.push_back(now() - t0);
    t0 = now();
    DEM::remesh_through_map(mesh, sphere, DEM::Unit_sphere_domain(), remesh_vertices, out);
    t_remesh.push_back(now() - t0);
  }
  std::cout << "faces " << mesh.number_of_faces() << ", queries " << queries << ", remesh to " << remesh_vertices
            << " vertices, " << repeats << " repeats (medians, s)\n"
            << "prepare " << median(t_prepare) << "\ncoherent pull-backs " << median(t_coherent)
            << "\nrandom pull-backs " << median(t_random) << "\ndomain mesh " << median(t_domain)
            << "\nremesh (with domain mesh) " << median(t_remesh) << "\n(checksum " << checksum << ")" << std::endl;
  return 0;
}
