// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Accuracy and speed of register_surfaces() (issue 18).
//
//   bench_registration [faces=25000] [repeats=3] [route=sphere|ellipsoid] [alpha] [beta] [gamma] [tolerance]
//     the generated case of test/Density_equalizing_maps/include/dem_registration_cases.h:
//     a surface registered to an independently meshed, deformed and moved copy of
//     itself (8 exact landmark pairs, true correspondence known); both meshes have
//     `faces` faces (the target from a turned lattice). Prints the median wall time of
//     register_surfaces() (both maps, the landmark positions and the transfer) and the
//     errors relative to the target's bounding-box diagonal.
//   bench_registration --mesh FILE [repeats] [route] [alpha] [beta] [gamma]
//     FILE registered to a copy of itself deformed by the same map (same connectivity,
//     so the true partner of vertex i is vertex i of the copy), 8 landmark pairs at the
//     vertices nearest to the corners of the bounding box.
//   bench_registration --mesh FILE --index-landmarks [repeats] ...
//     the same with the 8 landmark pairs at the vertices i n / 8 (as test_registration --shared).

#include "../../test/Density_equalizing_maps/include/dem_registration_cases.h"

#include <CGAL/Density_equalizing_maps/surface_registration.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace R = dem_registration;

int main(int argc, char** argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string mesh_file;
  bool index_landmarks = false;
  if(!args.empty() && args[0] == "--mesh") {
    if(args.size() < 2) { std::cerr << "--mesh needs a file\n"; return 2; }
    mesh_file = args[1];
    args.erase(args.begin(), args.begin() + 2);
    if(!args.empty() && args[0] == "--index-landmarks") { index_landmarks = true; args.erase(args.begin()); }
    args.insert(args.begin(), "0");
  }
  const std::size_t faces = args.size() > 0 ? std::size_t(std::atol(args[0].c_str())) : 25000;
  const int repeats = args.size() > 1 ? std::atoi(args[1].c_str()) : 3;
  const bool ellipsoid = args.size() > 2 && args[2] == "ellipsoid";
  const double alpha = args.size() > 3 ? std::atof(args[3].c_str()) : 1;
  const double beta = args.size() > 4 ? std::atof(args[4].c_str()) : 2;
  const double gamma = args.size() > 5 ? std::atof(args[5].c_str()) : 20;
  const double tolerance = args.size() > 6 ? std::atof(args[6].c_str()) : 1e-3;

  R::Case c;
  std::vector<R::Vertex> truth; // mesh mode: the true partner of every source vertex
  if(mesh_file.empty()) {
    c = R::make_case(faces / 2 + 2, faces / 2 + 2); // the target lattice is turned: another mesh
  } else {
    if(!CGAL::IO::read_polygon_mesh(mesh_file, c.source)) { std::cerr << "cannot read " << mesh_file << "\n"; return 1; }
    c.target = c.source;
    const double d = R::bounding_box_diagonal(c.source);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for(R::Vertex v : c.source.vertices()) centre += R::to_eigen(c.source.point(v)) / double(c.source.number_of_vertices());
    for(R::Vertex v : c.target.vertices()) { // the deformation at the scale of the generated case (diagonal ~ 4)
      const Eigen::Vector3d p = R::rigid_motion(R::deformation((R::to_eigen(c.source.point(v)) - centre) * (4. / d)) * (d / 4.));
      c.target.point(v) = R::Point(p.x(), p.y(), p.z());
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for(R::Vertex v : c.source.vertices()) { lo = lo.cwiseMin(R::to_eigen(c.source.point(v))); hi = hi.cwiseMax(R::to_eigen(c.source.point(v))); }
    for(int i = 0; i < 8 && index_landmarks; ++i) {
      const R::Vertex v(R::Mesh::size_type(std::size_t(i) * c.source.number_of_vertices() / 8));
      c.pairs.emplace_back(v, v);
    }
    for(int i = 0; i < 8 && !index_landmarks; ++i) {
      const Eigen::Vector3d corner(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
      R::Vertex best;
      double bd = 1e300;
      for(R::Vertex v : c.source.vertices()) {
        const double e = (R::to_eigen(c.source.point(v)) - corner).squaredNorm();
        if(e < bd) { bd = e; best = v; }
      }
      c.pairs.emplace_back(best, best);
    }
  }
  std::cout << "source " << c.source.number_of_faces() << " faces, target " << c.target.number_of_faces()
            << " faces, " << c.pairs.size() << " landmark pairs, route " << (ellipsoid ? "ellipsoid" : "sphere")
            << ", alpha " << alpha << " beta " << beta << " gamma " << gamma << " tolerance " << tolerance << "\n";

  auto registered = c.source.add_property_map<R::Vertex, R::Point>("v:registered").first;
  std::vector<double> times, cpu;
  DEM::Registration_report rep;
  for(int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    rep = DEM::register_surfaces(c.source, c.target, c.pairs, registered,
                                 DEM::parameters::combine(
                                   DEM::parameters::registration_domain(ellipsoid ? DEM::Registration_domain::ELLIPSOID
                                                                                  : DEM::Registration_domain::SPHERE),
                                   DEM::parameters::density_weight(alpha), DEM::parameters::harmonic_weight(beta),
                                   DEM::parameters::landmark_weight(gamma), DEM::parameters::stopping_tolerance(tolerance)));
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  double mean = 0, max = 0;
  if(mesh_file.empty()) {
    const R::Accuracy a = R::accuracy(c, registered);
    mean = a.mean;
    max = a.max;
  } else {
    const double diag = R::bounding_box_diagonal(c.target);
    for(R::Vertex v : c.source.vertices()) {
      const double e = (R::to_eigen(registered[v]) - R::to_eigen(c.target.point(v))).norm() / diag;
      mean += e / double(c.source.number_of_vertices());
      max = (std::max)(max, e);
    }
  }
  std::cout << "median seconds " << times[times.size() / 2] << " (min " << times.front() << ", max " << times.back()
            << ", " << repeats << " runs); median CPU seconds " << cpu[cpu.size() / 2] << "\n"
            << "mean error / diagonal " << mean << ", max " << max << "\n"
            << "landmark error / diagonal: mean " << rep.landmark_error_mean / rep.target_diagonal << ", max "
            << rep.landmark_error_max / rep.target_diagonal << "\n"
            << "fold-overs: source map " << rep.source_map.fold_overs << ", target map " << rep.target_map.fold_overs
            << "; iterations " << rep.source_map.iterations << " / " << rep.target_map.iterations << " ("
            << DEM::to_string(rep.source_map.termination) << " / " << DEM::to_string(rep.target_map.termination)
            << ")\nsphere landmark error: source map " << rep.source_map.landmark_error << ", target map "
            << rep.target_map.landmark_error << "\nlandmark correction (largest sphere distance before -> after, exact): start "
            << rep.source_start_correction.error_before << " -> " << rep.source_start_correction.error_after << " "
            << rep.source_start_correction.exact << " / " << rep.target_start_correction.error_before << " -> "
            << rep.target_start_correction.error_after << " " << rep.target_start_correction.exact << "; final "
            << rep.source_correction.error_before << " -> " << rep.source_correction.error_after << " "
            << rep.source_correction.exact << " / " << rep.target_correction.error_before << " -> "
            << rep.target_correction.error_after << " " << rep.target_correction.exact << "\nregistration map: mean |mu| " << rep.mean_abs_mu << ", mean |darea| " << rep.mean_abs_darea << "\n";
  return 0;
}
