// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Globe cartograms (issue 17), on generated globes and regions:
//  - overlap areas of faces and spherical polygons against the exact areas of the polygons
//    (a cap, a band with a hole): sampled within 1e-3 relative (ten times finer than the
//    1 % the cartogram must reach), exact within 1e-5;
//  - two hemispheres of values 3:1 give area shares 0.75 / 0.25 within 1 %;
//  - a polygon across the antimeridian and one around the south pole: exact overlaps before
//    and after rotating them away from both, and the shares of the rotated polygons, and
//    their values' shares within 1 %;
//  - a region with a hole, and the region in its hole;
//  - snapping the globe to the borders moves vertices onto them, within reach, fold-free;
//  - a near-empty region around a pole (value share 1e-4, as Antarctica's population):
//    the region-area correction after the passes lowers the largest error tenfold, and
//    the report says whether 1 % was reached (`known`: the 1 % itself); the boundaries
//    pushed forward through that map are the exact image of the rings;
//  - coarse to fine (make_cartogram_globe(), coarse_globe_vertices) on a globe subdivided
//    once from a coarse one, with a polar region shrunk tenfold: the carried map turns no
//    face over, the result is fold-free and within 1 %; a globe not built for it is refused;
//  - every cartogram is fold-free (exact count);
//  - `dem cartogram`: a run writes its four outputs (the deformed regions read back, same
//    ids, closed rings); each GeoJSON / CSV error gives exit 3, a message naming the
//    feature or the line, and no output file.

#include <CGAL/Density_equalizing_maps/globe_cartogram.h>
#include <CGAL/Density_equalizing_maps/internal/uniform_domain_mesh.h>
#include <CGAL/Density_equalizing_maps/remeshing.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#ifdef DEM_HAVE_CARTOGRAM
#include <CGAL/Density_equalizing_maps/IO/geojson.h>
#endif

#include "dem_cli_runner.h"

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
using dem_cli_test::check;
typedef CGAL::Simple_cartesian<double>::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Globe;

namespace {

const double pi = 3.14159265358979323846;

Globe geodesic_globe(int f)
{
  const DEM::internal::Triangle_arrays t = DEM::internal::geodesic_sphere(f);
  Globe g;
  DEM::internal::write_triangle_mesh(t.X, t.F, g);
  return g;
}

/// A ring of n vertices at angular radius `radius` (degrees) about (lon, lat), counterclockwise.
std::vector<DEM::Lon_lat> circle(double lon, double lat, double radius, int n)
{
  const Eigen::Vector3d c = DEM::internal::unit_vector({lon, lat});
  Eigen::Vector3d e = c.cross(Eigen::Vector3d::UnitZ());
  if(e.norm() < 1e-9) e = Eigen::Vector3d::UnitX();
  e.normalize();
  const Eigen::Vector3d nn = c.cross(e);
  const double r = radius * pi / 180;
  std::vector<DEM::Lon_lat> ring;
  for(int k = 0; k < n; ++k) {
    const double a = 2 * pi * k / n;
    ring.push_back(DEM::internal::lon_lat(std::cos(r) * c + std::sin(r) * (std::cos(a) * e + std::sin(a) * nn)));
  }
  return ring;
}

std::vector<DEM::Lon_lat> parallel(double lat, int n, bool eastward)
{
  std::vector<DEM::Lon_lat> ring;
  for(int k = 0; k < n; ++k) ring.push_back({-180 + 360. * (eastward ? k : n - k) / n, lat});
  return ring;
}

DEM::Spherical_region region(const std::string& id, std::vector<std::vector<DEM::Lon_lat> > rings)
{
  DEM::Spherical_region r;
  r.id = id;
  DEM::Spherical_polygon p;
  p.rings = std::move(rings);
  r.polygons.push_back(p);
  return r;
}

double exact_area(const DEM::Spherical_region& r)
{
  double a = 0;
  for(const auto& p : r.polygons) {
    const auto rings = DEM::internal::polygon_rings(p, r.id);
    a += rings[0].enclosed_area();
    for(std::size_t g = 1; g < rings.size(); ++g) a -= rings[g].enclosed_area();
  }
  return a;
}

double total(const std::vector<double>& v)
{
  double s = 0;
  for(double x : v) s += x;
  return s;
}

/// Relative error of each region's mesh area share against its exact area share.
double worst_overlap_error(const Globe& g, const std::vector<DEM::Spherical_region>& regions, int subdivision = 8)
{
  std::vector<double> values(regions.size(), 1.);
  const DEM::Region_populations p =
    DEM::face_populations_from_regions(g, regions, values, DEM::parameters::overlap_subdivision(subdivision));
  // the overlaps are fractions of faces: weighted by the spherical areas of the faces, so
  // that the flat faces' chord error (up to ~0.3 % here, varying over the geodesic globe)
  // does not hide or add to the error of the overlaps
  std::vector<double> area(regions.size(), 0.);
  std::size_t k = 0;
  for(auto f : g.faces()) {
    std::vector<Eigen::Vector3d> c;
    for(auto v : vertices_around_face(g.halfedge(f), g)) c.emplace_back(g.point(v).x(), g.point(v).y(), g.point(v).z());
    const double a = DEM::internal::signed_triangle_area(c[0].normalized(), c[1].normalized(), c[2].normalized());
    for(const auto& part : p.face_parts[k]) area[part.first] += part.second * a;
    ++k;
  }
  double worst = 0;
  for(std::size_t r = 0; r < regions.size(); ++r) {
    const double e = std::abs(area[r] / exact_area(regions[r]) - 1);
    std::cout << "  " << regions[r].id << ": overlap area " << area[r] << ", exact "
              << exact_area(regions[r]) << ", relative error " << e << "\n";
    worst = std::max(worst, e);
  }
  return worst;
}

/// The largest distance (radians) from the boundary of `regions` to the preimages, under the
/// map `mapped` of `g`, of the midpoints between consecutive points of the boundaries pushed
/// forward through that map. The map is linear on each face, so the image of a ring is the
/// chain of great-circle arcs between the images of the ring's crossings with mesh edges: if
/// the pushed-forward points hold every crossing, the midpoints pull back onto the ring (up to
/// round-off); if they cut a corner of that chain, onto a point off the ring.
double worst_pushed_boundary_deviation(const Globe& g, const Globe& mapped,
                                       const std::vector<DEM::Spherical_region>& regions,
                                       const std::vector<DEM::Spherical_region>& pushed)
{
  const DEM::Point_transfer<Globe, DEM::Unit_sphere_domain, Point> image(g, mapped.points(), DEM::Unit_sphere_domain());
  double worst = 0;
  for(std::size_t r = 0; r < regions.size(); ++r)
    for(std::size_t p = 0; p < regions[r].polygons.size(); ++p)
      for(std::size_t k = 0; k < regions[r].polygons[p].rings.size(); ++k) {
        const auto& ring = regions[r].polygons[p].rings[k];
        const auto& moved = pushed[r].polygons[p].rings[k];
        for(std::size_t i = 0; i < moved.size(); ++i) {
          const Eigen::Vector3d mid = (DEM::internal::unit_vector(moved[i]) +
                                       DEM::internal::unit_vector(moved[(i + 1) % moved.size()])).normalized();
          const Point q = image.pull_back(Point(mid.x(), mid.y(), mid.z()));
          const Eigen::Vector3d x = Eigen::Vector3d(q.x(), q.y(), q.z()).normalized();
          double d = 10;
          for(std::size_t j = 0; j < ring.size(); ++j)
            d = std::min(d, DEM::internal::distance_to_arc(x, DEM::internal::unit_vector(ring[j]),
                                                           DEM::internal::unit_vector(ring[(j + 1) % ring.size()])));
          worst = std::max(worst, d);
        }
      }
  return worst;
}

/// A cartogram of `regions` on `g` (fold-free: checked); with `mapped`, also the globe it maps to.
DEM::Globe_cartogram_report cartogram(const Globe& g, const std::vector<DEM::Spherical_region>& regions,
                                      const std::vector<double>& values,
                                      Globe* mapped = nullptr)
{
  Globe copy = g;
  auto out = copy.add_property_map<Globe::Vertex_index, Point>("v:out").first;
  const DEM::Globe_cartogram_report rep = DEM::globe_cartogram(copy, regions, values, out);
  if(mapped) {
    *mapped = g;
    for(auto v : mapped->vertices()) mapped->point(v) = out[v];
  }
  check(rep.fold_overs == 0, "the cartogram is fold-free (exact count " + std::to_string(rep.fold_overs) + ")");
  double shares = 0;
  for(std::size_t r = 0; r < regions.size(); ++r) {
    std::cout << "  " << regions[r].id << ": value share " << rep.value_share[r] << ", area share " << rep.area_share[r]
              << " (relative error " << rep.relative_error[r] << ", " << rep.faces_covered[r] << " faces)\n";
    shares += rep.value_share[r];
  }
  std::cout << "  passes " << rep.passes << ", max relative error " << rep.max_relative_error << "\n";
  return rep;
}

/// A rotation of the globe taking (-180, 0) to (0, 0) and the south pole to (-90, 0).
DEM::Lon_lat rotated(const DEM::Lon_lat& x)
{
  const Eigen::Vector3d v = DEM::internal::unit_vector(x);
  const Eigen::Vector3d about_x(v.x(), -v.z(), v.y()); // 90 degrees about x: (0,0,-1) -> (0,1,0)
  const Eigen::Vector3d about_z(-about_x.x(), -about_x.y(), about_x.z()); // 180 degrees about z
  return DEM::internal::lon_lat(about_z);
}

DEM::Spherical_region rotated(const DEM::Spherical_region& r)
{
  DEM::Spherical_region o = r;
  for(auto& p : o.polygons)
    for(auto& ring : p.rings)
      for(auto& x : ring) x = rotated(x);
  return o;
}

bool crosses_antimeridian_or_pole(const DEM::Spherical_region& r)
{
  for(const auto& p : r.polygons)
    for(const auto& ring : p.rings) {
      double turn = 0;
      for(std::size_t i = 0; i < ring.size(); ++i) {
        double d = ring[(i + 1) % ring.size()].lon - ring[i].lon;
        if(std::abs(d) > 180) return true;
        turn += d;
      }
      if(std::abs(turn) > 1) return true; // winds around a pole
    }
  return false;
}

void test_overlap_accuracy(const Globe& g)
{
  std::cout << "overlap areas (" << g.number_of_faces() << " faces)\n";
  const std::vector<DEM::Spherical_region> regions = {
    region("cap across the antimeridian", {circle(180, 10, 12, 90)}),
    region("south polar cap", {parallel(-62, 120, false)}),
    region("band with a hole", {circle(40, 45, 25, 150), circle(40, 45, 10, 60)}),
    region("hole", {circle(40, 45, 10, 60)})};
  const double e = worst_overlap_error(g, regions);
  check(e < 1e-3, "sampled overlap areas within 1e-3 relative of the exact polygon areas (worst " + std::to_string(e) + ")");
  // exact overlaps (subdivision 0) are exact on the flat faces; what remains is the radial
  // projection's variation over a face (the weights above use the spherical face area),
  // O(h^2) ~ 1e-7 here
  const double exact = worst_overlap_error(g, regions, 0);
  check(exact < 1e-5, "exact overlap areas within 1e-5 relative of the exact polygon areas (worst " +
                        std::to_string(exact) + ")");
  // the same regions with every ring reversed (winding does not matter: each ring encloses its smaller side)
  std::vector<DEM::Spherical_region> reversed = regions;
  for(auto& r : reversed)
    for(auto& p : r.polygons)
      for(auto& ring : p.rings) std::reverse(ring.begin(), ring.end());
  const double er = worst_overlap_error(g, reversed);
  check(std::abs(er - e) < 1e-12, "reversed rings give the same overlaps");
  check(std::abs(worst_overlap_error(g, reversed, 0) - exact) < 1e-12, "reversed rings give the same exact overlaps");
}

void test_hemispheres(const Globe& g)
{
  std::cout << "hemispheres 3:1\n";
  const std::vector<DEM::Spherical_region> regions = {region("north", {parallel(0, 16, true)}),
                                                      region("south", {parallel(0, 16, false)})};
  const DEM::Globe_cartogram_report rep = cartogram(g, regions, {3., 1.});
  check(std::abs(rep.area_share[0] / 0.75 - 1) <= 0.01, "northern hemisphere: area share 0.75 within 1 %");
  check(std::abs(rep.area_share[1] / 0.25 - 1) <= 0.01, "southern hemisphere: area share 0.25 within 1 %");
  check(std::abs(rep.sea_area_share) < 1e-9, "two hemispheres leave no sea");
}

void test_antimeridian_and_pole(const Globe& g, const Globe& fine)
{
  std::cout << "antimeridian and south pole, then rotated away\n";
  std::vector<DEM::Spherical_region> regions = {
    region("across the antimeridian", {{{160, -20}, {-160, -20}, {-160, 20}, {160, 20}}}),
    region("around the south pole", {parallel(-60, 36, true)}),
    region("elsewhere", {circle(60, 30, 15, 60)})};
  const std::vector<double> values = {5, 1, 2};
  std::vector<DEM::Spherical_region> turned;
  for(const auto& r : regions) turned.push_back(rotated(r));
  check(crosses_antimeridian_or_pole(regions[0]) && crosses_antimeridian_or_pole(regions[1]),
        "the test regions do cross the antimeridian / contain the pole");
  check(!crosses_antimeridian_or_pole(turned[0]) && !crosses_antimeridian_or_pole(turned[1]),
        "the rotated regions cross neither");
  // Exact overlaps, before and after the rotation. (Sampled with 8 x 8 sub-triangle centroids,
  // the square comes out 2.4e-3 small here and 3e-4 rotated: the samples' rows line up with
  // its long edges; a 30 x 30 sampling is still 6e-4 off. That was test_cartogram_known's
  // failure until the overlaps were exact.)
  const double e0 = worst_overlap_error(fine, regions, 0), e1 = worst_overlap_error(fine, turned, 0);
  check(e0 < 1e-5 && e1 < 1e-5, "exact overlap areas within 1e-5 of the exact areas, before and after the rotation");
  const DEM::Globe_cartogram_report a = cartogram(g, regions, values), b = cartogram(g, turned, values);
  for(std::size_t r = 0; r < regions.size(); ++r) {
    check(a.relative_error[r] <= 0.01 && b.relative_error[r] <= 0.01,
          regions[r].id + ": area share within 1 % of the value share, at the antimeridian/pole and rotated");
    check(std::abs(a.area_share[r] / b.area_share[r] - 1) <= 0.02,
          regions[r].id + ": same area share as the rotated region (within the two tolerances)");
  }
}

void test_hole(const Globe& g)
{
  std::cout << "a region with a hole, and the region in the hole\n";
  const std::vector<DEM::Spherical_region> regions = {
    region("ring", {parallel(30, 72, true), parallel(60, 36, false)}),
    region("inner", {parallel(60, 36, true)})};
  // values: the inner cap (a quarter of the ring's area) gets as much as the ring
  const DEM::Globe_cartogram_report rep = cartogram(g, regions, {1., 1.});
  check(rep.max_relative_error <= 0.01, "ring and hole: both area shares within 1 % of 0.5");
  check(std::abs(rep.populations.region_area[0] / total(rep.populations.face_area) / (exact_area(regions[0]) / (4 * pi)) - 1) < 1e-3,
        "the ring's area excludes its hole (within 1e-3 of the exact area)");
}

/// The globe after snap_globe_to_region_borders(): every vertex on the unit sphere, every
/// moved vertex on a border and within the reach (0.45 mean edge lengths) of where it was,
/// every face still turning the same way about the centre (exact), and some vertices moved.
void check_snapped_globe(const Globe& before, const Globe& after, const std::vector<DEM::Spherical_region>& regions)
{
  double mean_edge = 0;
  for(auto e : before.edges())
    mean_edge += std::sqrt(CGAL::squared_distance(before.point(before.vertex(e, 0)), before.point(before.vertex(e, 1))));
  mean_edge /= double(before.number_of_edges());
  std::size_t moved = 0, off_border = 0, too_far = 0, off_sphere = 0;
  for(auto v : after.vertices()) {
    const Eigen::Vector3d x(after.point(v).x(), after.point(v).y(), after.point(v).z());
    const Eigen::Vector3d y(before.point(v).x(), before.point(v).y(), before.point(v).z());
    if(std::abs(x.norm() - 1) > 1e-12) ++off_sphere;
    if(x == y) continue;
    ++moved;
    if((x - y).norm() > 0.45 * mean_edge * (1 + 1e-6)) ++too_far;
    double d = 10;
    for(const auto& r : regions)
      for(const auto& p : r.polygons)
        for(const auto& ring : p.rings)
          for(std::size_t j = 0; j < ring.size(); ++j)
            d = std::min(d, DEM::internal::distance_to_arc(x, DEM::internal::unit_vector(ring[j]),
                                                           DEM::internal::unit_vector(ring[(j + 1) % ring.size()])));
    if(d > 1e-12) ++off_border;
  }
  std::size_t turned = 0;
  for(auto f : after.faces()) {
    std::vector<Eigen::Vector3d> c;
    for(auto v : vertices_around_face(after.halfedge(f), after)) c.emplace_back(after.point(v).x(), after.point(v).y(), after.point(v).z());
    if(DEM::internal::orientation_about_center(c[0], c[1], c[2]) <= 0) ++turned;
  }
  check(moved > 0 && off_sphere == 0 && off_border == 0 && too_far == 0 && turned == 0,
        "snapped globe: " + std::to_string(moved) + " vertices moved, each onto a border and within reach (" +
          std::to_string(off_border) + " off a border, " + std::to_string(too_far) + " too far, " +
          std::to_string(off_sphere) + " off the sphere), " + std::to_string(turned) + " faces turned or flat");
}

/// A near-empty region around a pole, like Antarctica in a population cartogram: it must
/// shrink by about 10^3 while its neighbours grow. The density-equalizing passes stall
/// there (the faces next to a region shrunk that much cannot take the area the flow asks
/// of them); the region-area correction after them must bring the largest error down by
/// at least 10x without a fold-over, and the report must say whether 1 % was reached.
/// `known` asks for the 1 % itself (issue 17 item 3; not reached yet).
void test_near_empty_polar_region(const Globe& g, bool known)
{
  std::cout << "a near-empty polar region (value share 1e-4, area share 0.15)\n";
  const std::vector<DEM::Spherical_region> regions = {
    region("south polar cap", {parallel(-50, 120, false)}),
    region("northern cap", {parallel(30, 120, true)}),
    region("equatorial cap", {circle(60, 0, 25, 120)})};
  // the globe's vertices next to a border moved onto it (as `dem cartogram` does)
  Globe snapped = g;
  const std::size_t moved = DEM::snap_globe_to_region_borders(snapped, regions);
  std::cout << "  " << moved << " vertices snapped to the borders\n";
  check_snapped_globe(g, snapped, regions);
  Globe mapped;
  const DEM::Globe_cartogram_report rep = cartogram(snapped, regions, {1., 6000., 4000.}, &mapped);
  std::cout << "  largest error after the passes " << rep.max_error_before_correction << ", after "
            << rep.correction_iterations << " correction iterations " << rep.max_relative_error
            << " (on the mesh " << rep.max_relative_error_on_mesh << ")"
            << (rep.correction_message.empty() ? "" : " (" + rep.correction_message + ")") << "\n";
  if(known) {
    check(rep.max_relative_error <= 0.01, "near-empty polar region: every region within 1 % of its value share");
    return;
  }
  check(rep.max_error_before_correction > 0.01, "the passes alone leave the polar region off (the case needs the correction)");
  check(rep.max_relative_error <= 0.1 * rep.max_error_before_correction,
        "the region-area correction lowers the largest relative error at least tenfold");
  check(rep.converged == (rep.max_relative_error <= 0.01), "the report's converged flag is the 1 % test");
  check(rep.converged || !rep.correction_message.empty(), "a correction that stops short says why");
  // the faces next to the shrunk cap are sheared most: there the output polygons must follow
  // the piecewise-linear map through every face they cross, not cut its corners
  const double d = worst_pushed_boundary_deviation(snapped, mapped, regions,
                                                   DEM::push_forward_region_boundaries(snapped, mapped.points(), regions));
  std::cout << "  pushed-forward boundaries: largest distance of a pulled-back midpoint from the ring " << d << " rad\n";
  check(d <= 1e-9, "the pushed-forward boundaries are the exact image of the rings (midpoints pull back onto them)");
}

/// Coarse to fine (issue 17 item 5): on a globe that make_cartogram_globe() builds as a
/// midpoint subdivision of a snapped coarse globe, globe_cartogram() runs its passes on the
/// coarse globe and carries the map up: the carried map must be fold-free (each fine face
/// lies inside a coarse one), and the regions within 1 % of their value shares, with a
/// polar region that must shrink tenfold and one across the antimeridian.
void test_coarse_to_fine()
{
  std::cout << "coarse to fine: 16,002 vertices from 4,002\n";
  const std::vector<DEM::Spherical_region> regions = {
    region("across the antimeridian", {{{160, -20}, {-160, -20}, {-160, 20}, {160, 20}}}),
    region("around the south pole", {parallel(-60, 36, true)}),
    region("elsewhere", {circle(60, 30, 15, 60)})};
  const std::vector<double> values = {5, 0.05, 2};
  Globe g;
  const DEM::Cartogram_globe made = DEM::make_cartogram_globe(g, regions, 16000);
  check(made.coarse_globe_vertices == 4002 && made.subdivisions == 1 && g.number_of_vertices() == 16002,
        "make_cartogram_globe: 16,002 vertices as one subdivision of 4,002 (got " +
          std::to_string(g.number_of_vertices()) + " from " + std::to_string(made.coarse_globe_vertices) + ")");
  check(made.snapped_vertices > 0, "make_cartogram_globe snaps the coarse globe to the borders");
  auto out = g.add_property_map<Globe::Vertex_index, Point>("v:out").first;
  const DEM::Globe_cartogram_report rep = DEM::globe_cartogram(
    g, regions, values, out, DEM::parameters::coarse_globe_vertices(made.coarse_globe_vertices));
  for(std::size_t r = 0; r < regions.size(); ++r)
    std::cout << "  " << regions[r].id << ": value share " << rep.value_share[r] << ", area share " << rep.area_share[r]
              << " (relative error " << rep.relative_error[r] << ")\n";
  std::cout << "  coarse globes " << rep.coarse_globes.size() << (rep.coarse_globe_message.empty() ? "" : " (" + rep.coarse_globe_message + ")")
            << ", correction iterations " << (rep.coarse_globes.empty() ? 0 : rep.coarse_globes[0].correction_iterations)
            << " + " << rep.correction_iterations << ", largest error " << rep.max_relative_error
            << (rep.correction_message.empty() ? "" : " (" + rep.correction_message + ")") << "\n";
  check(rep.coarse_globes.size() == 1 && rep.coarse_globes[0].vertices == 4002,
        "the cartogram ran on the coarse globe first");
  check(rep.coarse_globe_message.empty(), "the coarse globe's map carried to the fine globe turns no face over");
  check(rep.fold_overs == 0, "coarse to fine: fold-free (exact count " + std::to_string(rep.fold_overs) + ")");
  check(rep.converged && rep.max_relative_error <= 0.01, "coarse to fine: every region within 1 % of its value share");
  // a globe that make_cartogram_globe() did not build for these regions is refused
  bool refused = false;
  try {
    Globe other = geodesic_globe(40); // the same vertex count, not snapped
    auto o = other.add_property_map<Globe::Vertex_index, Point>("v:out").first;
    DEM::globe_cartogram(other, regions, values, o, DEM::parameters::coarse_globe_vertices(std::size_t(4002)));
  } catch(const DEM::Invalid_input& e) {
    refused = std::string(e.what()).find("coarse_globe_vertices") != std::string::npos;
  }
  check(refused, "coarse_globe_vertices with a globe make_cartogram_globe() did not build: Invalid_input naming it");
}

#ifdef DEM_HAVE_CARTOGRAM
void test_command_line()
{
  using namespace dem_cli_test;
  std::cout << "dem cartogram\n";
  Temporary_folder dir("dem_cartogram");
  const std::string good_geojson =
    "{\"type\":\"FeatureCollection\",\"features\":[\n"
    "{\"type\":\"Feature\",\"properties\":{\"code\":\"N\"},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":"
    "[[[-180,0],[-90,0],[0,0],[90,0],[-180,0]]]}},\n"
    "{\"type\":\"Feature\",\"properties\":{\"code\":\"S\"},\"geometry\":{\"type\":\"MultiPolygon\",\"coordinates\":"
    "[[[[-180,0],[90,0],[0,0],[-90,0],[-180,0]]]]}}\n]}\n";
  const std::string good_csv = "code,name,people\nN,north,300\nS,\"south, the\",100\n";
  write_file(dir / "regions.geojson", good_geojson);
  write_file(dir / "values.csv", good_csv);
  const std::string outputs = " --output-geojson " + quoted(dir / "out.geojson") + " --output " + quoted(dir / "out.ply") +
                              " --image " + quoted(dir / "out.svg") + " --metrics " + quoted(dir / "metrics.json");
  const std::string base = "cartogram " + quoted(dir / "regions.geojson") + " --values " + quoted(dir / "values.csv") +
                           " --id-property code --value-column people --vertices 2000 --quiet";
  Result r = run_dem(dir, base + outputs);
  check(r.code == 0, "a good run exits 0 (got " + std::to_string(r.code) + ": " + r.err + ")");
  for(const char* f : {"out.geojson", "out.ply", "out.svg", "metrics.json"})
    check(fs::exists(dir / f), std::string("a good run writes ") + f);
  if(fs::exists(dir / "out.geojson")) {
    const DEM::IO::GeoJSON_regions back = DEM::IO::read_GeoJSON_regions(dir / "out.geojson", "code");
    check(back.regions.size() == 2 && back.regions[0].id == "N" && back.regions[1].id == "S",
          "the deformed regions read back with their ids");
  }
  if(fs::exists(dir / "metrics.json")) {
    const nlohmann::json m = nlohmann::json::parse(read_file(dir / "metrics.json"));
    check(m["fold_overs"].get<int>() == 0, "metrics: 0 fold-overs");
    check(m["max_relative_area_error"].get<double>() <= 0.01, "metrics: max relative area error within 1 %");
    check(m.contains("max_relative_area_error_on_mesh") && m["max_relative_area_error_on_mesh"].get<double>() <= 0.01,
          "metrics: the error measured on the mesh, within 1 % too");
    check(m.contains("sampled_overlaps") && m.contains("vertices_snapped_to_borders"),
          "metrics: how many overlaps fell back to samples and how many globe vertices were snapped");
    check(m.contains("correction_iterations") && m.contains("max_relative_area_error_before_correction") &&
            m["max_relative_area_error_before_correction"].get<double>() >= m["max_relative_area_error"].get<double>(),
          "metrics: the region-area correction's iterations and the error before it");
  }

  struct Bad { const char* what; std::string geojson, csv, message; };
  const std::string ring_open = "[[[-180,0],[-90,0],[0,0],[90,0]]]";
  const std::vector<Bad> bad = {
    {"malformed JSON", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",", good_csv, "malformed JSON"},
    {"non-closed ring",
     "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"code\":\"N\"},"
     "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":" + ring_open + "}}]}",
     good_csv, "feature 0 (code \"N\"), ring 0: the ring is not closed"},
    {"unknown geometry type",
     "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{\"code\":\"N\"},"
     "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[1,1]]}}]}",
     good_csv, "feature 0 (code \"N\"): unknown geometry type \"LineString\""},
    {"id missing from the CSV", good_geojson, "code,people\nN,300\n", "feature 1 (code \"S\"): no value for it"},
    {"negative value", good_geojson, "code,people\nN,300\nS,-5\n", "values.csv:3: the value -5 of \"S\" is negative"},
    {"non-numeric value", good_geojson, "code,people\nN,lots\nS,100\n", "values.csv:2: the value \"lots\" of \"N\" is not a number"},
  };
  for(const Bad& b : bad) {
    for(const char* f : {"out.geojson", "out.ply", "out.svg", "metrics.json"}) fs::remove(dir / f);
    write_file(dir / "regions.geojson", b.geojson);
    write_file(dir / "values.csv", b.csv);
    const std::string args = "cartogram " + quoted(dir / "regions.geojson") + " --values " + quoted(dir / "values.csv") +
                             " --id-property code --value-column people --vertices 2000 --quiet" + outputs;
    r = run_dem(dir, args);
    check(r.code == 3, std::string(b.what) + ": exit 3 (got " + std::to_string(r.code) + ")");
    check(contains(r.err, b.message), std::string(b.what) + ": the message says \"" + b.message + "\" (got: " + r.err + ")");
    bool none = true;
    for(const char* f : {"out.geojson", "out.ply", "out.svg", "metrics.json"}) none = none && !fs::exists(dir / f);
    check(none, std::string(b.what) + ": no output file");
  }
}
#endif

} // namespace

int main(int argc, char** argv)
{
  const bool known = argc > 1 && std::string(argv[1]) == "known";
  const Globe fine = geodesic_globe(40);   // 16,002 vertices, 32,000 faces
  const Globe coarse = geodesic_globe(20); // 4,002 vertices, 8,000 faces
  if(known) { // the part that does not hold yet (DEM_KNOWN_FAILURES: test_cartogram_known)
    test_near_empty_polar_region(coarse, true);
    return dem_cli_test::failures() ? 1 : 0;
  }
  test_overlap_accuracy(fine);
  test_hemispheres(coarse);
  test_antimeridian_and_pole(coarse, fine);
  test_hole(coarse);
  test_near_empty_polar_region(coarse, false);
  test_coarse_to_fine();
#ifdef DEM_HAVE_CARTOGRAM
  test_command_line();
#else
  std::cout << "dem cartogram not built (no nlohmann-json): command-line part not run\n";
#endif
  std::cout << (dem_cli_test::failures() ? "FAILED\n" : "all passed\n");
  return dem_cli_test::failures() ? 1 : 0;
}
