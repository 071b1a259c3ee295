// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "problem.h"

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>
#include <CGAL/Density_equalizing_maps/internal/validation.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <unistd.h> // isatty

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>

namespace dem_cli {

namespace {

/// Copies a polygon soup into arrays; throws Invalid_input on a non-triangle.
template <class Point, class Polygon>
void soup_to_arrays(const std::vector<Point>& points, const std::vector<Polygon>& polygons, DI::Matrix& X,
                    DI::Index_matrix& F)
{
  X.resize(Eigen::Index(points.size()), 3);
  for(std::size_t i = 0; i < points.size(); ++i) {
    X(Eigen::Index(i), 0) = CGAL::to_double(points[i].x());
    X(Eigen::Index(i), 1) = CGAL::to_double(points[i].y());
    X(Eigen::Index(i), 2) = CGAL::to_double(points[i].z());
  }
  F.resize(Eigen::Index(polygons.size()), 3);
  for(std::size_t k = 0; k < polygons.size(); ++k) {
    if(polygons[k].size() != 3)
      throw CGAL::Density_equalizing_maps::Invalid_input(
          "not a triangle mesh: face " + std::to_string(k) + " has " + std::to_string(polygons[k].size()) +
          " vertices");
    for(int c = 0; c < 3; ++c) {
      const std::size_t v = polygons[k][std::size_t(c)];
      if(v >= points.size())
        throw CGAL::Density_equalizing_maps::Invalid_input("face " + std::to_string(k) + " refers to vertex " +
                                                           std::to_string(v) + ", out of range");
      F(Eigen::Index(k), c) = int(v);
    }
  }
}

} // namespace

Progress::Progress(bool quiet) : quiet_(quiet), tty_(isatty(2) != 0), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress()
{
  if(printed_ && tty_) std::cerr << std::endl;
}

bool Progress::operator()(std::size_t iteration, double error)
{
  if(quiet_) return true;
  const double t = seconds_since(start_);
  if(t > 1.0 && t - last_ >= 1.0) {
    // one line per second; rewritten in place on a terminal
    std::fprintf(stderr, tty_ ? "\r  iteration %zu, error %.3e, %.1f s   " : "  iteration %zu, error %.3e, %.1f s\n",
                 iteration, error, t);
    std::fflush(stderr);
    last_ = t;
    printed_ = true;
  }
  return true; // never cancel
}

DI::Matrix to_matrix(const Mesh& mesh, const Point_map& pm)
{
  DI::Matrix Y(mesh.number_of_vertices(), 3);
  for(Vertex v : mesh.vertices()) {
    const Point_3& p = pm[v];
    Y(v.idx(), 0) = p.x(); Y(v.idx(), 1) = p.y(); Y(v.idx(), 2) = p.z();
  }
  return Y;
}

Point_map fresh_point_map(Mesh& mesh, const std::string& name)
{
  return mesh.add_property_map<Vertex, Point_3>(name, Point_3(0, 0, 0)).first;
}

/// Reads and validates the mesh (exit 3 on failure, through Invalid_input).
void read_mesh(const Options& opt, Problem& pb)
{
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  {
    std::ifstream probe(opt.input);
    if(!probe) throw DEM::Invalid_input("cannot open " + opt.input);
  }
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(opt.input, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception& e) {
    throw DEM::Invalid_input("cannot read " + opt.input + ": " + e.what());
  }
  if(!ok || polygons.empty())
    throw DEM::Invalid_input("cannot read a mesh from " + opt.input +
                             " (unknown format, syntax error or no face)");
  soup_to_arrays(points, polygons, pb.X, pb.F);
  DI::validate_closed_surface(pb.X, pb.F, domain_of(opt.method) == Domain::TORUS ? 0 : 2,
                              domain_of(opt.method) == Domain::TORUS ? 7 : 4);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, pb.mesh);
  if(pb.mesh.number_of_vertices() != std::size_t(pb.X.rows()) ||
     pb.mesh.number_of_faces() != std::size_t(pb.F.rows()))
    throw DEM::Invalid_input("the mesh could not be built from " + opt.input);
}

void read_sidecars(const Options& opt, Problem& pb)
{
  const std::size_t nv = std::size_t(pb.X.rows()), nf = std::size_t(pb.F.rows());
  if(!opt.population.empty() && opt.population != "area") {
    const std::vector<double> p = DEM::IO::read_face_values(opt.population, nf);
    pb.population = Eigen::Map<const DI::Vector>(p.data(), Eigen::Index(p.size()));
    pb.explicit_population = true;
  } else {
    pb.population = DI::face_areas(pb.X, pb.F);
  }
  pb.population_map = pb.mesh.add_property_map<Face, double>("f:dem_population", 0.).first;
  for(Face f : pb.mesh.faces()) pb.population_map[f] = pb.population[f.idx()];

  if(!opt.landmarks.empty())
    for(const DEM::IO::Indexed_landmark& l : DEM::IO::read_landmarks(opt.landmarks, nv))
      pb.landmarks.emplace_back(Vertex(Mesh::size_type(l.vertex)), Point_3(l.target[0], l.target[1], l.target[2]));
  if(!opt.cut_edges.empty())
    for(const auto& e : DEM::IO::read_vertex_pairs(opt.cut_edges, nv))
      pb.cut_edges.emplace_back(Vertex(Mesh::size_type(e.first)), Vertex(Mesh::size_type(e.second)));
}

DI::Matrix landmark_targets(const Landmarks& l, std::vector<Eigen::Index>& index)
{
  DI::Matrix Q(l.size(), 3);
  index.resize(l.size());
  for(std::size_t k = 0; k < l.size(); ++k) {
    index[k] = Eigen::Index(l[k].first.idx());
    Q(k, 0) = l[k].second.x(); Q(k, 1) = l[k].second.y(); Q(k, 2) = l[k].second.z();
  }
  return Q;
}

bool write_output(const std::string& file, const DI::Matrix& Y, const DI::Index_matrix& F)
{
  std::vector<Point_3> points;
  points.reserve(std::size_t(Y.rows()));
  for(Eigen::Index i = 0; i < Y.rows(); ++i) points.emplace_back(Y(i, 0), Y(i, 1), Y(i, 2));
  std::vector<std::array<std::size_t, 3>> triangles(std::size_t(F.rows()));
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) triangles[k][c] = std::size_t(F(k, c));
  return CGAL::IO::write_polygon_soup(file, points, triangles, CGAL::parameters::stream_precision(17));
}

} // namespace dem_cli
