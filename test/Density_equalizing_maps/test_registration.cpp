// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Surface registration (issue 18): register_surfaces(), the landmark-pairs
// reader and `dem register`, on generated meshes (dem_registration_cases.h:
// a surface and an independently meshed, deformed and moved copy, with the
// true correspondence known from the analytic parameter).
//   test_registration           accuracy on the sphere route (issue: mean error <= 1 %
//                               of the target's bounding-box diagonal, landmark error
//                               <= 0.5 %, 8 pairs), bijectivity, the ellipsoid route,
//                               bad input (library, reader, CLI)
//   test_registration --shared  maxplanck registered to a deformed copy of itself

#include "include/dem_registration_cases.h"
#include "include/dem_cli_runner.h"
#include "include/dem_test_meshes.h"

#include <CGAL/Density_equalizing_maps/IO/landmark_pairs.h>
#include <CGAL/Density_equalizing_maps/surface_registration.h>
#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <fstream>
#include <sstream>

namespace DEM = CGAL::Density_equalizing_maps;
namespace R = dem_registration;
using dem_test::check;
using dem_test::contains;
using dem_test::expect_throw;

namespace {

typedef R::Mesh::Face_index Face;
typedef std::pair<Face, std::array<double, 3> > Location;

void write_off(const R::Mesh& m, const std::string& file)
{
  std::ofstream out(file);
  out.precision(17);
  out << "OFF\n" << m.number_of_vertices() << " " << m.number_of_faces() << " 0\n";
  for(R::Vertex v : m.vertices()) out << m.point(v) << "\n";
  for(Face f : m.faces()) {
    out << 3;
    for(R::Vertex v : vertices_around_face(m.halfedge(f), m)) out << " " << v.idx();
    out << "\n";
  }
}

void accuracy_on_the_sphere()
{
  R::Case c = R::make_case(2500, 2700, 8);
  auto registered = c.source.add_property_map<R::Vertex, R::Point>("v:registered").first;
  std::map<R::Vertex, Location> loc;
  const DEM::Registration_report rep = DEM::register_surfaces(
    c.source, c.target, c.pairs, registered,
    DEM::parameters::target_location_map(boost::make_assoc_property_map(loc)));
  const R::Accuracy a = R::accuracy(c, registered);
  std::cout << "sphere route: mean error " << a.mean << " (max " << a.max << ") of the diagonal, landmark error "
            << rep.landmark_error_max / rep.target_diagonal << " (max), mean|mu| " << rep.mean_abs_mu << std::endl;
  check(rep.source_map.fold_overs == 0 && rep.target_map.fold_overs == 0 && rep.is_bijective(),
        "both maps are fold-free (exact counts)");
  check(rep.source_start_correction.exact && rep.target_start_correction.exact && rep.source_correction.exact &&
          rep.target_correction.exact,
        "the landmark corrections are exact");
  check(rep.source_map.landmark_error < 1e-9 && rep.target_map.landmark_error < 1e-9,
        "both maps put the landmarks at the common positions");
  check(a.mean <= 0.01, "mean distance to the true partner <= 1 % of the target's diagonal");
  check(rep.landmark_error_max / rep.target_diagonal <= 0.005, "landmark error <= 0.5 % of the diagonal");
  check(std::abs(R::bounding_box_diagonal(c.target) - rep.target_diagonal) < 1e-9, "the report's diagonal");
  // every location is a point of the target: its face's combination is the registered point
  double worst = 0;
  for(R::Vertex v : c.source.vertices()) {
    const Location& l = loc.at(v);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    // the convention of Polygon_mesh_processing::locate(): source(h), target(h), target(next(h))
    const auto h = c.target.halfedge(l.first);
    const R::Vertex corner[3] = {c.target.source(h), c.target.target(h), c.target.target(c.target.next(h))};
    for(int k = 0; k < 3; ++k) p += l.second[k] * R::to_eigen(c.target.point(corner[k]));
    check(l.second[0] >= 0 && l.second[1] >= 0 && l.second[2] >= 0, "barycentric coordinates non-negative");
    worst = (std::max)(worst, (p - R::to_eigen(registered[v])).norm());
  }
  check(worst < 1e-9, "target face + barycentric coordinates give the registered point");
  // the registration map is itself fold-free seen from a common domain: the source
  // connectivity over the registered points, pushed to the target's sphere
  check(rep.landmark_positions.size() == c.pairs.size(), "one common position per pair");
  for(const auto& p : rep.landmark_positions)
    check(std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1) < 1e-9, "common positions on the sphere");
}

// the landmark correction of the sphere route (internal/landmark_warp.h): exact for small
// displacements, and never folds the map it moves (exact count), whatever is asked of it
void landmark_correction()
{
  namespace I = DEM::internal;
  const dem_test::Arrays a = dem_test::icosphere_arrays(3);
  check(I::count_inverted_faces_about_center(a.X, a.F) == 0, "correction: the icosphere is fold-free");
  const std::vector<Eigen::Index> l = {0, 100, 200, 300, 400, 500, 600};
  I::Matrix q(Eigen::Index(l.size()), 3);
  for(std::size_t k = 0; k < l.size(); ++k) { // each landmark turned its own way by 0.04 rad
    const Eigen::Vector3d axis = Eigen::Vector3d(std::cos(double(k)), std::sin(2. * k), 0.5).normalized();
    q.row(Eigen::Index(k)) = (Eigen::AngleAxisd(0.04, axis) * I::row3(a.X, l[k])).transpose();
  }
  I::Matrix x = a.X;
  const I::Landmark_warp_result small = I::warp_landmarks_onto_targets(x, a.F, l, q);
  double worst = 0, off_sphere = 0;
  for(std::size_t k = 0; k < l.size(); ++k) worst = (std::max)(worst, (x.row(l[k]) - q.row(Eigen::Index(k))).norm());
  for(Eigen::Index i = 0; i < x.rows(); ++i) off_sphere = (std::max)(off_sphere, std::abs(x.row(i).norm() - 1));
  check(small.exact && worst < 1e-12 && small.error_after < 1e-12, "correction: small displacements reached exactly");
  check(small.error_before > 0.03, "correction: the landmarks were off before");
  check(off_sphere < 1e-12, "correction: the points stay on the sphere");
  check(I::count_inverted_faces_about_center(x, a.F) == 0, "correction: fold-free after a small correction");
  // a landmark asked to move 1.2 rad away from its neighbour, which stays: the warp stretches the
  // mesh between them (reached or not, the map stays fold-free); then two neighbours asked to
  // swap places: each warp moves them towards each other along their edge, which no fold-free
  // warp can take them through, so the correction stops short of the targets
  Eigen::Index neighbour = -1;
  for(Eigen::Index f = 0; f < a.F.rows() && neighbour < 0; ++f)
    for(int c = 0; c < 3; ++c)
      if(a.F(f, c) == 0) neighbour = a.F(f, (c + 1) % 3);
  const std::vector<Eigen::Index> l2 = {0, neighbour, 300, 500};
  I::Matrix q2(4, 3);
  for(int k = 0; k < 4; ++k) q2.row(k) = a.X.row(l2[std::size_t(k)]);
  q2.row(0) = (Eigen::AngleAxisd(1.2, Eigen::Vector3d(0.3, 1, 0.2).normalized()) * I::row3(a.X, 0)).transpose();
  x = a.X;
  const I::Landmark_warp_result large = I::warp_landmarks_onto_targets(x, a.F, l2, q2);
  check(I::count_inverted_faces_about_center(x, a.F) == 0, "correction: fold-free after a large correction");
  check(large.error_after <= large.error_before, "correction: a large correction does not move away");
  q2.row(0) = a.X.row(neighbour);
  q2.row(1) = a.X.row(0);
  x = a.X;
  const I::Landmark_warp_result swap = I::warp_landmarks_onto_targets(x, a.F, l2, q2);
  check(I::count_inverted_faces_about_center(x, a.F) == 0, "correction: fold-free after an impossible correction");
  check(!swap.exact && swap.error_after > 1e-3, "correction: an impossible correction is reported not exact");
}

void ellipsoid_route()
{
  R::Case c = R::make_case(1500, 1600, 8);
  auto registered = c.source.add_property_map<R::Vertex, R::Point>("v:registered").first;
  const DEM::Registration_report rep = DEM::register_surfaces(
    c.source, c.target, c.pairs, registered,
    DEM::parameters::registration_domain(DEM::Registration_domain::ELLIPSOID));
  const R::Accuracy a = R::accuracy(c, registered);
  std::cout << "ellipsoid route: mean error " << a.mean << " of the diagonal, landmark error "
            << rep.landmark_error_max / rep.target_diagonal << " (max)" << std::endl;
  check(rep.is_bijective(), "ellipsoid route: both maps fold-free");
  check(rep.radii.size() == 3, "ellipsoid route reports its radii");
  for(const auto& p : rep.landmark_positions) {
    const double l = p[0] * p[0] / (rep.radii[0] * rep.radii[0]) + p[1] * p[1] / (rep.radii[1] * rep.radii[1]) +
                     p[2] * p[2] / (rep.radii[2] * rep.radii[2]);
    check(std::abs(l - 1) < 1e-9, "common positions on the ellipsoid");
  }
  // a correspondence, not a collapse: well below the error of sending every vertex to the
  // target's centroid (about a quarter of the diagonal here)
  check(a.mean < 0.03, "ellipsoid route: mean error < 3 % of the diagonal");
}

// the populations pass through: the face areas given explicitly give the default result
void populations_pass_through()
{
  R::Case c = R::make_case(600, 650, 8);
  auto a = c.source.add_property_map<R::Vertex, R::Point>("v:a").first;
  auto b = c.source.add_property_map<R::Vertex, R::Point>("v:b").first;
  auto ps = c.source.add_property_map<Face, double>("f:p").first;
  auto pt = c.target.add_property_map<Face, double>("f:p").first;
  for(Face f : c.source.faces()) ps[f] = 3 * CGAL::Polygon_mesh_processing::face_area(f, c.source);
  for(Face f : c.target.faces()) pt[f] = 5 * CGAL::Polygon_mesh_processing::face_area(f, c.target);
  DEM::register_surfaces(c.source, c.target, c.pairs, a);
  const DEM::Registration_report r = DEM::register_surfaces(
    c.source, c.target, c.pairs, b,
    DEM::parameters::combine(DEM::parameters::face_population_map(ps), DEM::parameters::target_face_population_map(pt)));
  double d = 0;
  for(R::Vertex v : c.source.vertices()) d = (std::max)(d, (R::to_eigen(a[v]) - R::to_eigen(b[v])).norm());
  check(r.is_bijective() && d < 1e-6 * r.target_diagonal, "populations proportional to the areas give the default result");
  // a population that differs on the target changes the correspondence (it is used)
  for(Face f : c.target.faces()) pt[f] = (c.target.point(c.target.target(c.target.halfedge(f))).z() > 2 ? 4 : 1) *
                                         CGAL::Polygon_mesh_processing::face_area(f, c.target);
  DEM::register_surfaces(c.source, c.target, c.pairs, b, DEM::parameters::target_face_population_map(pt));
  d = 0;
  for(R::Vertex v : c.source.vertices()) d = (std::max)(d, (R::to_eigen(a[v]) - R::to_eigen(b[v])).norm());
  check(d > 1e-3 * r.target_diagonal, "the target's population is used");
}

void bad_input_library()
{
  R::Case c = R::make_case(300, 320, 8);
  auto out = c.source.add_property_map<R::Vertex, R::Point>("v:out", R::Point(7, 7, 7)).first;
  const auto untouched = [&] {
    for(R::Vertex v : c.source.vertices()) if(out[v] != R::Point(7, 7, 7)) return false;
    return true;
  };
  auto run = [&](const std::vector<std::pair<R::Vertex, R::Vertex> >& p, const R::Mesh& s, const R::Mesh& t) {
    return [&, p] { DEM::register_surfaces(s, t, p, out); };
  };
  auto pairs = c.pairs;
  std::string m = expect_throw<DEM::Invalid_input>(run({pairs[0], pairs[1]}, c.source, c.target), "2 pairs");
  check(contains(m, "at least 3 landmark pairs"), "fewer than 3 pairs named: " + m);
  auto dup = pairs; dup.push_back(pairs[2]);
  m = expect_throw<DEM::Invalid_input>(run(dup, c.source, c.target), "duplicate pair");
  check(contains(m, "duplicates pair 2"), "duplicate pair named: " + m);
  auto twice = pairs; twice[3].first = twice[1].first;
  m = expect_throw<DEM::Invalid_input>(run(twice, c.source, c.target), "vertex in two pairs");
  check(contains(m, "already in pair 1"), "vertex in two pairs named: " + m);
  auto out_of_range = pairs; out_of_range[0].second = R::Vertex(100000);
  m = expect_throw<DEM::Invalid_input>(run(out_of_range, c.source, c.target), "index out of range");
  check(contains(m, "target vertex") && contains(m, "out of range"), "out-of-range vertex named: " + m);
  const dem_test::Mesh torus = dem_test::torus(3, 1, 24, 12);
  std::vector<std::pair<R::Vertex, R::Vertex> > tp = {{pairs[0].first, R::Vertex(0)}, {pairs[1].first, R::Vertex(5)},
                                                      {pairs[2].first, R::Vertex(40)}};
  m = expect_throw<DEM::Invalid_input>(run(tp, c.source, torus), "genus mismatch");
  check(contains(m, "genus mismatch") && contains(m, "genus 1"), "genus mismatch named: " + m);
  std::vector<std::pair<R::Vertex, R::Vertex> > tt = {{R::Vertex(0), R::Vertex(0)}, {R::Vertex(5), R::Vertex(5)},
                                                      {R::Vertex(40), R::Vertex(40)}};
  m = expect_throw<DEM::Invalid_input>(run(tt, torus, torus), "two tori");
  check(contains(m, "genus 1") && contains(m, "needs genus 0"), "non-genus-0 surfaces named: " + m);
  check(untouched(), "nothing written on bad input");
}

void bad_input_reader()
{
  const auto read = [](const std::string& text) {
    return [text] { std::istringstream in(text); DEM::IO::read_landmark_pairs(in, 10, 20, "pairs.txt"); };
  };
  std::istringstream ok("# source target\n0 1\n\n2 3 # a comment\n4 19\n");
  check(DEM::IO::read_landmark_pairs(ok, 10, 20).size() == 3, "reader: comments and blank lines");
  std::string m = expect_throw<DEM::Invalid_input>(read("0 1\n2 x\n"), "malformed");
  check(contains(m, "pairs.txt line 2"), "malformed line numbered: " + m);
  m = expect_throw<DEM::Invalid_input>(read("0 1\n1 2\n10 3\n"), "source out of range");
  check(contains(m, "line 3") && contains(m, "source vertex 10 out of range"), "source index range: " + m);
  m = expect_throw<DEM::Invalid_input>(read("0 1\n1 20\n2 3\n"), "target out of range");
  check(contains(m, "line 2") && contains(m, "target vertex 20 out of range"), "target index range: " + m);
  m = expect_throw<DEM::Invalid_input>(read("0 1\n2 3\n0 1\n"), "duplicate");
  check(contains(m, "line 3") && contains(m, "duplicate pair") && contains(m, "line 1"), "duplicate pair: " + m);
  m = expect_throw<DEM::Invalid_input>(read("0 1\n2 1\n3 4\n"), "target twice");
  check(contains(m, "target vertex 1 is already paired on line 1"), "target twice: " + m);
  m = expect_throw<DEM::Invalid_input>(read("0 1\n2 3\n"), "two pairs");
  check(contains(m, "at least 3"), "fewer than 3 pairs: " + m);
}

void command_line()
{
  dem_cli_test::Temporary_folder dir("dem_test_registration");
  R::Case c = R::make_case(1200, 1300, 8);
  write_off(c.source, dir / "source.off");
  write_off(c.target, dir / "target.off");
  {
    std::ofstream p(dir / "pairs.txt");
    p << "# source target\n";
    for(const auto& q : c.pairs) p << q.first.idx() << " " << q.second.idx() << "\n";
  }
  const std::string base = dem_cli_test::quoted(dir / "source.off") + " " + dem_cli_test::quoted(dir / "target.off") +
                           " --landmark-pairs " + dem_cli_test::quoted(dir / "pairs.txt");
  const auto r = dem_cli_test::run_dem(dir, "register " + base + " --output " + dem_cli_test::quoted(dir / "out.off") +
                                              " --metrics " + dem_cli_test::quoted(dir / "m.json"));
  check(r.code == 0, "dem register exits 0: " + r.err);
  const std::string json = dem_cli_test::read_file(dir / "m.json");
  for(const char* key : {"\"landmark_error_3d\"", "\"relative_mean\"", "\"relative_max\"", "\"mean_abs_mu\"",
                         "\"mean_abs_darea\"", "\"source_map\"", "\"target_map\"", "\"fold_overs\": 0",
                         "\"landmark_correction\"", "\"exact\": true"})
    check(contains(json, key), std::string("metrics have ") + key);
  R::Mesh out;
  check(CGAL::IO::read_polygon_mesh(dir / "out.off", out) && out.number_of_vertices() == c.source.number_of_vertices() &&
          out.number_of_faces() == c.source.number_of_faces(),
        "--output has the source connectivity");
  if(out.number_of_vertices() == c.source.number_of_vertices()) {
    const R::Accuracy a = R::accuracy(c, out.points());
    check(a.mean <= 0.015, "the written points are the registered points (mean error " + std::to_string(a.mean) + ")");
  }
  // bad input: exit 3, message, nothing written
  const auto refused = [&](const std::string& pairs_text, const std::string& target, const std::string& expect) {
    dem_cli_test::write_file(dir / "bad_pairs.txt", pairs_text);
    const auto b = dem_cli_test::run_dem(dir, "register " + dem_cli_test::quoted(dir / "source.off") + " " +
                                                dem_cli_test::quoted(target) + " --landmark-pairs " +
                                                dem_cli_test::quoted(dir / "bad_pairs.txt") + " --output " +
                                                dem_cli_test::quoted(dir / "bad.off") + " --metrics " +
                                                dem_cli_test::quoted(dir / "bad.json"));
    check(b.code == 3, "exit 3 for " + expect + " (got " + std::to_string(b.code) + ")");
    check(contains(b.err, expect), "message names " + expect + ": " + b.err);
    check(!std::filesystem::exists(dir / "bad.off") && !std::filesystem::exists(dir / "bad.json"),
          "nothing written for " + expect);
  };
  refused("0 1\n1 2\n", dir / "target.off", "at least 3");
  refused("0 1\n1 2\n99999 3\n", dir / "target.off", "source vertex 99999 out of range");
  refused("0 1\n1 2\n0 1\n", dir / "target.off", "duplicate pair");
  write_off(dem_test::torus(3, 1, 24, 12), dir / "torus.off");
  refused("0 1\n1 2\n3 4\n", dir / "torus.off", "genus mismatch");
  refused("0 1\n1 2\n3 4\n", dir / "torus.off", "genus 1");
  const auto v = dem_cli_test::run_dem(dir, "register " + base + " --via conformal");
  check(v.code == 2 && contains(v.err, "--via must be"), "unknown --via is a usage error");
}

void shared_maxplanck()
{
  // maxplanck registered to a deformed copy (same connectivity: vertex i's partner is vertex i)
  // is a benchmark (bench_registration --mesh), recorded in benchmark/RESULTS.md; here it is
  // checked against the bounds.
  const std::string file = dem_test::data_path("maxplanck.off");
  R::Case c;
  if(!CGAL::IO::read_polygon_mesh(file, c.source)) { std::cerr << "cannot read " << file << "\n"; ++dem_test::failure_count(); return; }
  c.target = c.source;
  const double d = R::bounding_box_diagonal(c.source);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for(R::Vertex v : c.source.vertices()) centre += R::to_eigen(c.source.point(v)) / double(c.source.number_of_vertices());
  for(R::Vertex v : c.target.vertices()) {
    const Eigen::Vector3d p = R::rigid_motion(R::deformation((R::to_eigen(c.source.point(v)) - centre) * (4. / d)) * (d / 4.));
    c.target.point(v) = R::Point(p.x(), p.y(), p.z());
  }
  for(std::size_t k = 0; k < 8; ++k) {
    const R::Vertex v(R::Mesh::size_type(k * c.source.number_of_vertices() / 8));
    c.pairs.emplace_back(v, v);
  }
  auto registered = c.source.add_property_map<R::Vertex, R::Point>("v:registered").first;
  const DEM::Registration_report rep = DEM::register_surfaces(c.source, c.target, c.pairs, registered);
  double mean = 0;
  for(R::Vertex v : c.source.vertices())
    mean += (R::to_eigen(registered[v]) - R::to_eigen(c.target.point(v))).norm() / rep.target_diagonal /
            double(c.source.number_of_vertices());
  std::cout << "maxplanck: mean error " << mean << ", landmark error " << rep.landmark_error_max / rep.target_diagonal
            << std::endl;
  check(rep.is_bijective(), "maxplanck: both maps fold-free");
  check(mean <= 0.01, "maxplanck: mean error <= 1 % of the diagonal");
  check(rep.landmark_error_max / rep.target_diagonal <= 0.005, "maxplanck: landmark error <= 0.5 %");
}

} // namespace

int main(int argc, char** argv)
{
  if(dem_test::shared_part_requested(argc, argv)) {
    if(!dem_test::data_available("maxplanck.off")) return dem_test::skip_code;
    shared_maxplanck();
    return dem_test::finish("test_registration --shared");
  }
  bad_input_reader();
  bad_input_library();
  landmark_correction();
  populations_pass_through();
  accuracy_on_the_sphere();
  ellipsoid_route();
  command_line();
  dem_test::failure_count() += dem_cli_test::failures();
  return dem_test::finish("test_registration");
}
