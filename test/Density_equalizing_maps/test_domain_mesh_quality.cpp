// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Issue 12, item 2: uniform meshes of the domains. For every requested
// N in {100, 1000, 8500, 10000, 100000} (and, on the sphere, the awkward
// counts 400 and 10140, far from any geodesic sphere's 10 f^2 + 2) and every
// domain (unit sphere, ellipsoids 1:1:2, 1:2:3, 1:1:5, torus (3, 1)) the mesh
// must have N vertices within 1 %, be a closed manifold of the domain's genus
// with every vertex on the domain and every face outward (exact), and reach
// delta_shape <= 0.05 and delta_size <= 0.7 (the DistMesh quality the papers
// used). On the torus that holds for the relaxed mesh (torus_lattice(false));
// the default lattice (item 8) must give every vertex valence 6 and keep
// delta_size <= 0.7, its delta_shape (0.07 at R/r = 3) is printed, not
// bounded: a valence-6 lattice cannot have both (see uniform_domain_mesh.h).
// Prints one line per mesh (the table of benchmark/RESULTS.md).

#include "dem_test_meshes.h"

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/remeshing.h>

#include <CGAL/boost/graph/helpers.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

using namespace dem_test;
namespace DEM = CGAL::Density_equalizing_maps;

namespace {

bool closed_triangle_manifold(const Mesh& m, long euler)
{
  if(!CGAL::is_closed(m) || !CGAL::is_valid_polygon_mesh(m) || !CGAL::is_triangle_mesh(m)) return false;
  return long(m.number_of_vertices()) - long(m.number_of_edges()) + long(m.number_of_faces()) == euler;
}

/// Largest deviation of a vertex from the domain (implicit equation, relative).
double ellipsoid_deviation(const Mesh& m, double a, double b, double c)
{
  double worst = 0;
  for(auto v : m.vertices()) {
    const Point& p = m.point(v);
    const double s = std::sqrt(p.x() * p.x() / (a * a) + p.y() * p.y() / (b * b) + p.z() * p.z() / (c * c));
    worst = std::max(worst, std::abs(s - 1));
  }
  return worst;
}

double torus_deviation(const Mesh& m, double R, double r)
{
  double worst = 0;
  for(auto v : m.vertices()) {
    const Point& p = m.point(v);
    worst = std::max(worst, std::abs(std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r) / r);
  }
  return worst;
}

/// Faces whose orientation about the point of the torus' core circle nearest
/// their centroid is not positive (exact): folded or inward faces.
std::size_t torus_inward_faces(const Mesh& m, double R)
{
  std::size_t bad = 0;
  for(auto f : m.faces()) {
    std::vector<Point> p;
    for(auto v : vertices_around_face(m.halfedge(f), m)) p.push_back(m.point(v));
    const double x = (p[0].x() + p[1].x() + p[2].x()) / 3, y = (p[0].y() + p[1].y() + p[2].y()) / 3;
    const double s = R / std::hypot(x, y);
    if(CGAL::orientation(Point(s * x, s * y, 0), p[0], p[1], p[2]) != CGAL::POSITIVE) ++bad;
  }
  return bad;
}

bool every_valence_six(const Mesh& m)
{
  for(auto v : m.vertices())
    if(m.degree(v) != 6) return false;
  return true;
}

void report(const std::string& domain, std::size_t n, const Mesh& m, double seconds, bool bound_shape = true)
{
  const DEM::Mesh_uniformity u = DEM::mesh_uniformity(m);
  std::cout << "| " << domain << " | " << n << " | " << m.number_of_vertices() << " | " << std::fixed
            << std::setprecision(3) << u.delta_shape << " | " << u.delta_size << " | " << std::setprecision(2)
            << seconds << " |" << std::endl;
  std::cout.unsetf(std::ios::fixed);
  const std::string what = domain + ", N = " + std::to_string(n);
  check(std::abs(double(m.number_of_vertices()) - double(n)) <= 0.01 * double(n), what + ": N within 1 %");
  if(bound_shape)
    check(u.delta_shape <= 0.05, what + ": delta_shape <= 0.05 (is " + std::to_string(u.delta_shape) + ")");
  check(u.delta_size <= 0.7, what + ": delta_size <= 0.7 (is " + std::to_string(u.delta_size) + ")");
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

} // namespace

int main()
{
  const std::size_t sizes[] = {100, 1000, 8500, 10000, 100000};
  const double ellipsoids[][3] = {{1, 1, 1}, {1, 1, 2}, {1, 2, 3}, {1, 1, 5}};
  std::cout << "| domain | N requested | N | delta_shape | delta_size | seconds |\n|---|---:|---:|---:|---:|---:|"
            << std::endl;
  for(const auto& e : ellipsoids) {
    std::vector<std::size_t> counts(std::begin(sizes), std::end(sizes));
    if(e[0] == e[1] && e[1] == e[2]) counts = {100, 400, 1000, 8500, 10000, 10140, 100000};
    for(std::size_t n : counts) {
      Mesh m;
      const double t0 = now();
      DEM::uniform_domain_mesh(DEM::Ellipsoid_domain{e[0], e[1], e[2]}, n, m);
      const double t = now() - t0;
      std::ostringstream name;
      name << "ellipsoid " << e[0] << ":" << e[1] << ":" << e[2];
      check(closed_triangle_manifold(m, 2), name.str() + ": closed genus-0 triangle mesh");
      check(DEM::number_of_fold_overs(m, m.points()) == 0, name.str() + ": every face outward (exact)");
      check(ellipsoid_deviation(m, e[0], e[1], e[2]) <= 1e-12, name.str() + ": vertices on the ellipsoid");
      report(name.str(), n, m, t);
    }
  }
  for(bool lattice : {false, true})
    for(std::size_t n : sizes) {
      Mesh m;
      const double t0 = now();
      DEM::uniform_domain_mesh(DEM::Torus_domain{3, 1}, n, m, DEM::parameters::torus_lattice(lattice));
      const double t = now() - t0;
      const std::string name = lattice ? "torus 3, 1 lattice" : "torus 3, 1 relaxed";
      check(closed_triangle_manifold(m, 0), name + ": closed genus-1 triangle mesh");
      check(torus_deviation(m, 3, 1) <= 1e-12, name + ": vertices on the torus");
      check(torus_inward_faces(m, 3) == 0, name + ": every face outward (exact)");
      if(lattice) check(every_valence_six(m), name + ": every vertex of valence 6");
      report(name, n, m, t, !lattice);
    }
  return finish("test_domain_mesh_quality");
}
