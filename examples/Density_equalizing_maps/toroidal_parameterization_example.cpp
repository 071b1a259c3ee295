// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Area-preserving parameterization of a closed genus-one mesh on the torus
// (R, r): seamless periodic harmonic map found from two homology loops (given
// as cut edges, or found automatically), then TDEM with the face areas as the
// population. Writes the torus mesh, the flat-torus coordinates and the
// integer lattice offset of every halfedge (the mesh is never cut).
//   toroidal_parameterization_example [input.off [R r [cut_edges.txt [output.off]]]]
// cut_edges.txt: one "i j" vertex pair per line (0-based, '#' comments). Without
// arguments, a torus whose tube radius varies along its length is generated.

#include "example_meshes.h"

#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace params = DEM::parameters;
using namespace example;

int main(int argc, char** argv)
{
  // a torus whose tube radius varies along its length: not a surface of revolution
  Mesh mesh;
  if(!input_mesh(argc, argv, mesh, torus(2.5, [](double a) { return 0.8 + 0.3 * std::cos(3 * a); }, 96, 32)))
    return EXIT_FAILURE;
  const std::array<double, 2> radii{argc > 3 ? std::atof(argv[2]) : 2., argc > 3 ? std::atof(argv[3]) : 1.};
  std::vector<std::pair<vertex_descriptor, vertex_descriptor> > cut;
  if(argc > 4) {
    std::ifstream in(argv[4]);
    std::string line;
    while(std::getline(in, line)) {
      if(line.empty() || line[0] == '#') continue;
      std::istringstream s(line);
      int i, j;
      if(s >> i >> j) cut.emplace_back(vertex_descriptor(i), vertex_descriptor(j));
    }
  }
  const std::string output = argc > 5 ? argv[5] : "toroidal_parameterization.off";

  Point_map torus_point = image_map(mesh, "torus_point");
  auto flat_point = mesh.add_property_map<vertex_descriptor, Point_2>("v:flat_torus_point").first;
  auto offset = mesh.add_property_map<halfedge_descriptor, std::array<int, 2> >("h:lattice_offset").first;

  DEM::Map_report report;
  try {
    const auto common = params::combine(params::torus_radii(radii), params::flat_torus_coordinates(flat_point),
                                        params::flat_torus_offsets(offset));
    if(cut.empty()) // automatic homology loops (tree-cotree)
      report = DEM::toroidal_parameterization(mesh, torus_point, common);
    else
      report = DEM::toroidal_parameterization(mesh, torus_point, params::combine(common, params::cut_edges(cut)));
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }

  // area distortion: mean |log| of the ratio of normalized face areas
  double input_total = 0, output_total = 0, mean_abs_log = 0;
  std::vector<std::pair<double, double> > areas;
  for(auto f : faces(mesh)) {
    std::vector<vertex_descriptor> c;
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) c.push_back(v);
    const double a = std::sqrt(CGAL::squared_area(mesh.point(c[0]), mesh.point(c[1]), mesh.point(c[2])));
    const double b = std::sqrt(CGAL::squared_area(torus_point[c[0]], torus_point[c[1]], torus_point[c[2]]));
    areas.emplace_back(a, b);
    input_total += a;
    output_total += b;
  }
  for(const auto& ab : areas) mean_abs_log += std::abs(std::log((ab.second / output_total) / (ab.first / input_total)));
  mean_abs_log /= double(areas.size());

  std::cout << "toroidal parameterization: " << report.iterations << " TDEM iterations ("
            << DEM::to_string(report.termination) << "), mean |d_area| " << mean_abs_log << ", fold-overs "
            << report.fold_overs << std::endl;

  if(!write_mapped_mesh(mesh, torus_point, output)) return EXIT_FAILURE;
  // flat-torus layout: per vertex (u, v); per face and corner the lattice offset
  // of the halfedge leaving it lets a viewer draw every face unbroken
  std::ofstream uv(output + ".uv.txt");
  uv.precision(17);
  for(vertex_descriptor v : vertices(mesh)) uv << flat_point[v].x() << " " << flat_point[v].y() << "\n";
  std::ofstream off(output + ".offsets.txt");
  for(auto f : faces(mesh))
    for(auto h : halfedges_around_face(halfedge(f, mesh), mesh))
      off << std::size_t(source(h, mesh)) << " " << std::size_t(target(h, mesh)) << " " << offset[h][0] << " "
          << offset[h][1] << "\n";
  std::cout << "wrote " << output << ", " << output << ".uv.txt and " << output << ".offsets.txt" << std::endl;
  return report.is_bijective() ? EXIT_SUCCESS : EXIT_FAILURE;
}
