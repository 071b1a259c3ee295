// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "problem.h"
#include "dem_formats.h"
#include "mesh_input.h"
#include "output_files.h"

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>
#include <CGAL/Density_equalizing_maps/internal/validation.h>

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

namespace {
Stage_progress* stage_progress_ = nullptr;
}

void set_stage_progress(Stage_progress* s) { stage_progress_ = s; }
Stage_progress* stage_progress() { return stage_progress_; }

std::function<void(const std::string&)> stage_callback()
{
  return [](const std::string& name) {
    if(stage_progress_) stage_progress_->substage(name);
  };
}

bool Progress::operator()(std::size_t iteration, double error)
{
  if(quiet_) return true;
  if(stage_progress_) return stage_progress_->iteration(iteration, error);
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

/// Reads and validates the mesh (exit 3 on failure, through Invalid_input): FreeSurfer
/// and GIfTI surfaces with the package's readers, the rest with CGAL's (dem_formats.h).
void read_mesh(const Options& opt, Problem& pb)
{
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  read_surface(opt.input, points, polygons);
  if(opt.repair) {
    const Soup_repairs r = repair_soup<Mesh>(points, polygons);
    pb.repairs = r.summary();
    pb.repaired = r.changed();
    if(!opt.quiet || pb.repaired) std::cerr << "dem: --repair: " << pb.repairs << "\n";
    if(pb.repaired && ((!opt.population.empty() && opt.population != "area") || !opt.landmarks.empty() ||
                       !opt.cut_edges.empty()))
      throw DEM::Invalid_input("--repair changed the mesh (" + pb.repairs +
                               "), so the faces and vertices of the --population, --landmarks or --cut-edges "
                               "file no longer match it: write the repaired mesh first (dem METHOD INPUT "
                               "--repair --output REPAIRED) and give files for that mesh");
  }
  try {
    soup_to_arrays(points, polygons, pb.X, pb.F);
    DI::validate_closed_surface(pb.X, pb.F, domain_of(opt.method) == Domain::TORUS ? 0 : 2,
                                domain_of(opt.method) == Domain::TORUS ? 7 : 4);
  } catch(const DEM::Invalid_input& e) {
    throw DEM::Invalid_input(opt.repair ? std::string(e.what()) + " (after --repair: " + pb.repairs + ")"
                                        : with_repair_hint(e.what()));
  }
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
  } else if(!opt.vertex_population.empty()) {
    DEM::IO::Triangle_soup soup;
    for(Eigen::Index i = 0; i < pb.X.rows(); ++i) soup.points.push_back({{pb.X(i, 0), pb.X(i, 1), pb.X(i, 2)}});
    for(Eigen::Index k = 0; k < pb.F.rows(); ++k)
      soup.faces.push_back({{std::size_t(pb.F(k, 0)), std::size_t(pb.F(k, 1)), std::size_t(pb.F(k, 2))}});
    const std::vector<double> p = face_population_from_vertex_density(
      soup, read_vertex_values(opt.vertex_population, nv), opt.vertex_population);
    pb.population = Eigen::Map<const DI::Vector>(p.data(), Eigen::Index(p.size()));
    pb.explicit_population = true;
  } else {
    // at unit size (a power of two): areas of coordinates near 1e+-100 overflow
    pb.population = DI::face_areas(pb.X * DI::unit_scale(pb.X), pb.F);
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
  std::string error;
  return write_atomically(file, [&](const std::string& f) {
    return CGAL::IO::write_polygon_soup(f, points, triangles, CGAL::parameters::stream_precision(17));
  }, error);
}

} // namespace dem_cli
