// Properties of the spherical density-equalizing map (SDEM) and of its
// landmark-aligned variant (LSDEM) on generated meshes (no shared data):
// bijectivity by the exact fold-over count, points on the unit sphere, the
// density variance reduced, area preservation, the population / density /
// initial-map / callback parameters, and the messages of bad input.
// The shared-mesh acceptance cases are in test_sdem_shared.cpp and
// test_lsdem_shared.cpp.
#include <dem_test_meshes.h>

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace P = CGAL::Density_equalizing_maps::parameters;
using namespace dem_test;

typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_values;
typedef Mesh::Property_map<vertex_descriptor, double> Vertex_values;
typedef std::vector<std::pair<vertex_descriptor, Point> > Landmarks;

namespace {

double face_area(const Mesh& m, face_descriptor f)
{
  const auto h = m.halfedge(f);
  const Point &p = m.point(m.source(h)), &q = m.point(m.target(h)), &r = m.point(m.target(m.next(h)));
  return std::sqrt(CGAL::squared_area(p, q, r));
}

Point face_centroid(const Mesh& m, face_descriptor f)
{
  const auto h = m.halfedge(f);
  return CGAL::centroid(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))));
}

/// population = area * (1 + (ratio - 1) [centroid z > 0.5]): the cap above z = 0.5
/// (a quarter of the sphere) is `ratio` times denser and must grow.
Face_values cap_population(Mesh& m, double ratio, const std::string& name = "f:population")
{
  Face_values p = m.add_property_map<face_descriptor, double>(name, 0.).first;
  for(face_descriptor f : faces(m)) put(p, f, face_area(m, f) * (face_centroid(m, f).z() > 0.5 ? ratio : 1.));
  return p;
}

/// The same cap with a smooth edge: the density rises from 1 to `ratio`
/// (smoothstep) for z between 0.2 and 0.8.
Face_values smooth_cap_population(Mesh& m, double ratio, const std::string& name = "f:smooth_population")
{
  Face_values p = m.add_property_map<face_descriptor, double>(name, 0.).first;
  for(face_descriptor f : faces(m)) {
    const double u = std::min(1., std::max(0., (face_centroid(m, f).z() - 0.2) / 0.6));
    put(p, f, face_area(m, f) * (1 + (ratio - 1) * u * u * (3 - 2 * u)));
  }
  return p;
}

/// The common output guarantees: report and exact count agree on 0 fold-overs, points on the unit sphere.
void check_bijective_on_sphere(const Mesh& m, const Point_map& out, const DEM::Map_report& r, const std::string& what)
{
  const std::size_t folds = DEM::number_of_fold_overs(m, out);
  const double dev = max_sphere_deviation(m, out);
  std::cout << what << ": " << r.iterations << " iterations (" << DEM::to_string(r.termination) << "), error "
            << r.initial_error << " -> " << r.final_error << ", fold-overs " << r.fold_overs << "/" << folds
            << ", repairs " << r.repairs << ", halvings " << r.step_halvings << ", max | |p|-1 | " << dev
            << std::endl;
  check(r.fold_overs == 0, what + ": report says 0 fold-overs");
  check(folds == 0, what + ": exact count finds 0 fold-overs");
  check(dev <= 1e-12, what + ": points on the unit sphere (1e-12)");
}

// ---------------------------------------------------------------------------

/// Fraction of the image area covered by the faces whose input centroid has z > 0.5.
double cap_image_fraction(const Mesh& m, const Point_map& out)
{
  double cap = 0, total = 0;
  for(face_descriptor f : faces(m)) {
    const auto h = m.halfedge(f);
    const double a =
      std::sqrt(CGAL::squared_area(get(out, m.source(h)), get(out, m.target(h)), get(out, m.target(m.next(h)))));
    total += a;
    if(face_centroid(m, f).z() > 0.5) cap += a;
  }
  return cap / total;
}

void test_smooth_cap_population()
{
  Mesh m = icosphere(4); // 2562 vertices, 5120 faces
  const Face_values pop = smooth_cap_population(m, 10.);
  const auto np_pop = P::face_population_map(pop);
  Point_map out = output_map(m, "v:sdem");
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(m, out, np_pop);
  check_bijective_on_sphere(m, out, r, "SDEM smooth cap x10");
  check(r.converged(), "SDEM smooth cap x10: converged");
  // the input is itself a sphere: its density variance is the initial one
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), np_pop);
  const DEM::Density_variance v1 = DEM::density_variance(m, out, np_pop);
  std::cout << "SDEM smooth cap x10: Var(vertex density) " << v0.vertex << " -> " << v1.vertex
            << ", Var(face density) " << v0.face << " -> " << v1.face << std::endl;
  // Initially Var ~ 1.1. The flow stops when sd/mean of the *diffused* density is
  // below 1e-3 (Var ~ 1e-6); the re-coupled density differs from it by what one
  // diffusion step smooths away, which is small for a smooth population. 0.002 is
  // the bound the issue sets for the shared meshes (paper 001 reaches ~1e-3).
  check(v1.vertex <= 0.002 && v1.vertex <= v0.vertex / 10,
        "SDEM smooth cap x10: Var(vertex density) <= min(0.002, initial/10)");
  // face densities are not averaged by M: more discretization noise (measured 0.0017)
  check(v1.face <= 0.005, "SDEM smooth cap x10: Var(face density) <= 0.005");
  const double cap = cap_image_fraction(m, out);
  std::cout << "SDEM smooth cap x10: cap (z > 0.5) image area fraction 0.25 -> " << cap << std::endl;
  check(cap > 0.5, "SDEM smooth cap x10: the dense cap covers more than half the sphere");
}

void test_step_cap_population()
{
  Mesh m = icosphere(4);
  const Face_values pop = cap_population(m, 10.);
  const auto np_pop = P::face_population_map(pop);
  Point_map out = output_map(m, "v:sdem");
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(m, out, np_pop);
  check_bijective_on_sphere(m, out, r, "SDEM step cap x10");
  check(r.converged(), "SDEM step cap x10: converged");
  // The local untangling's case: steps of this flow fold a few faces of the
  // band outside the growing cap (exact test); the untangling removes those
  // folds without shortening the step. Without it every such step would be
  // halved (mutation untangling_skipped of scripts/mutation_check.py).
  check(r.repairs > 0, "SDEM step cap x10: some steps folded and were repaired");
  check(r.step_halvings == 0, "SDEM step cap x10: every folding step untangled at full length (no halving)");
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), np_pop);
  const DEM::Density_variance v1 = DEM::density_variance(m, out, np_pop);
  std::cout << "SDEM step cap x10: Var(vertex density) " << v0.vertex << " -> " << v1.vertex
            << ", Var(face density) " << v0.face << " -> " << v1.face << std::endl;
  // A density jump: the ring of sparse faces just outside the growing cap is
  // compressed into a band of thin faces whose density stays far above the
  // mean (measured: up to 165x, Var(face) ~16, Var(vertex) ~0.006 at 2562
  // vertices, 0.003 at 10242). The diffused density the flow equalizes cannot
  // see that band, so only a hundredfold reduction of the vertex variance is
  // asserted here; the 0.002 bound is asserted for the smooth cap above.
  check(v1.vertex <= v0.vertex / 100, "SDEM step cap x10: Var(vertex density) reduced a hundredfold");
  const double cap = cap_image_fraction(m, out);
  std::cout << "SDEM step cap x10: cap image area fraction 0.25 -> " << cap << std::endl;
  check(cap > 0.6, "SDEM step cap x10: the dense cap covers most of the sphere (10/13 ideally)");
}

void test_extreme_population()
{
  Mesh m = icosphere(3);
  const Face_values pop = cap_population(m, 1e4);
  Point_map out = output_map(m, "v:sdem");
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(m, out, P::face_population_map(pop));
  check_bijective_on_sphere(m, out, r, "SDEM ratio 1e4");
  check(r.final_error < r.initial_error, "SDEM ratio 1e4: the density error decreased");
}

void test_area_preserving()
{
  Mesh m = bumpy(4);
  Point_map conformal = output_map(m, "v:conformal"), corrected = output_map(m, "v:corrected"),
            out = output_map(m, "v:sdem");
  DEM::spherical_conformal_map(m, conformal);
  DEM::spherical_conformal_map(m, corrected, P::mobius_area_correction(true));
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(m, out);
  check_bijective_on_sphere(m, out, r, "SDEM area-preserving bumpy");
  const double d_conf = DEM::map_distortion(m, conformal).mean_abs_darea;
  const double d_corr = DEM::map_distortion(m, corrected).mean_abs_darea;
  const DEM::Distortion_statistics d = DEM::map_distortion(m, out);
  std::cout << "bumpy: mean|d_area| conformal " << d_conf << ", Moebius-corrected " << d_corr << ", SDEM "
            << d.mean_abs_darea << " (mean|mu| " << d.mean_abs_mu << ")" << std::endl;
  check(d.mean_abs_darea < d_conf && d.mean_abs_darea < d_corr,
        "SDEM area-preserving: mean|d_area| below the conformal map's (with and without Moebius correction)");
  check(d.mean_abs_darea <= 0.05, "SDEM area-preserving: mean|d_area| <= 0.05");
}

void test_vertex_density()
{
  Mesh m = icosphere(3);
  Vertex_values rho = m.add_property_map<vertex_descriptor, double>("v:density", 0.).first;
  for(vertex_descriptor v : vertices(m)) put(rho, v, m.point(v).z() > 0.5 ? 10. : 1.);
  // the documented equivalent population: area times the mean density of the corners
  Face_values pop = m.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(face_descriptor f : faces(m)) {
    double s = 0;
    for(vertex_descriptor v : vertices_around_face(m.halfedge(f), m)) s += get(rho, v);
    put(pop, f, face_area(m, f) * s / 3);
  }
  Point_map a = output_map(m, "v:by_density"), b = output_map(m, "v:by_population");
  const DEM::Map_report ra = DEM::spherical_density_equalizing_map(m, a, P::vertex_density_map(rho));
  const DEM::Map_report rb = DEM::spherical_density_equalizing_map(m, b, P::face_population_map(pop));
  check_bijective_on_sphere(m, a, ra, "SDEM vertex_density_map");
  auto max_distance = [&](Point_map x, Point_map y) {
    double d = 0;
    for(vertex_descriptor v : vertices(m)) d = std::max(d, std::sqrt(CGAL::squared_distance(get(x, v), get(y, v))));
    return d;
  };
  // The two populations agree to round-off only (the library and this test
  // compute the face areas in different orders); 41 iterations with fold-over
  // repairs amplify that to ~1e-9 on the unit sphere, by an amount that
  // depends on the CPU's floating-point kernels. The bound sits far below what
  // another reading of the density gives (the control below: its mean density
  // without the area factor, a different population).
  const double diff = max_distance(a, b);
  std::cout << "vertex_density_map vs equivalent face population: max distance " << diff << std::endl;
  check(diff <= 1e-6, "SDEM: vertex_density_map gives the map of the equivalent face population");
  Face_values mean_density = m.add_property_map<face_descriptor, double>("f:mean_density", 0.).first;
  for(face_descriptor f : faces(m)) put(mean_density, f, get(pop, f) / face_area(m, f));
  Point_map c0 = output_map(m, "v:by_mean_density");
  DEM::spherical_density_equalizing_map(m, c0, P::face_population_map(mean_density));
  const double control = max_distance(a, c0);
  std::cout << "vertex_density_map vs a population without the area factor: max distance " << control << std::endl;
  check(control > 1e-3, "SDEM: another population gives a measurably different map (the bound above discriminates)");
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), P::face_population_map(pop));
  const DEM::Density_variance v1 = DEM::density_variance(m, a, P::face_population_map(pop));
  std::cout << "vertex_density_map: Var(vertex density) " << v0.vertex << " -> " << v1.vertex << std::endl;
  check(v1.vertex <= v0.vertex / 10, "SDEM vertex_density_map: variance reduced tenfold");

  Vertex_values bad = m.add_property_map<vertex_descriptor, double>("v:bad", 1.).first;
  put(bad, vertex_descriptor(17), -2.);
  Point_map c = output_map(m, "v:bad_out");
  const std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::spherical_density_equalizing_map(m, c, P::vertex_density_map(bad)); }, "negative vertex density");
  std::cout << "negative vertex density: " << msg << std::endl;
  check(contains(msg, "vertex 17"), "negative vertex density: the message names vertex 17");
  check(untouched(m, c), "negative vertex density: nothing written");
}

void test_initial_map()
{
  Mesh m = icosphere(3);
  const Face_values pop = cap_population(m, 5.);
  // a valid initial map: the identity of the icosphere (already on the sphere)
  Point_map out = output_map(m, "v:sdem");
  const DEM::Map_report r =
    DEM::spherical_density_equalizing_map(m, out, P::combine(P::initial_map(m.points()), P::face_population_map(pop)));
  check_bijective_on_sphere(m, out, r, "SDEM from the identity");
  const DEM::Density_variance v1 = DEM::density_variance(m, out, P::face_population_map(pop));
  check(r.converged() && v1.vertex <= 0.002, "SDEM from the identity: converged, Var(vertex density) <= 0.002");

  // a folded initial map: the mirror image (every face inverted)
  Point_map mirror = m.add_property_map<vertex_descriptor, Point>("v:mirror").first;
  for(vertex_descriptor v : vertices(m)) put(mirror, v, Point(m.point(v).x(), m.point(v).y(), -m.point(v).z()));
  Point_map o2 = output_map(m, "v:o2");
  std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::spherical_density_equalizing_map(m, o2, P::initial_map(mirror)); }, "mirrored initial map");
  std::cout << "mirrored initial map: " << msg << std::endl;
  check(contains(msg, "not bijective"), "mirrored initial map: message says not bijective");
  check(untouched(m, o2), "mirrored initial map: nothing written");

  // one vertex moved to its antipode: a few folded faces
  Point_map folded = m.add_property_map<vertex_descriptor, Point>("v:folded").first;
  for(vertex_descriptor v : vertices(m)) put(folded, v, m.point(v));
  const Point p = m.point(vertex_descriptor(100));
  put(folded, vertex_descriptor(100), Point(-p.x(), -p.y(), -p.z()));
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::spherical_density_equalizing_map(m, o2, P::initial_map(folded)); }, "folded initial map");
  std::cout << "folded initial map: " << msg << std::endl;
  check(contains(msg, "not bijective"), "folded initial map: message says not bijective");
  check(untouched(m, o2), "folded initial map: nothing written");

  // a vertex at the centre cannot be projected on the sphere
  put(folded, vertex_descriptor(100), Point(0, 0, 0));
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::spherical_density_equalizing_map(m, o2, P::initial_map(folded)); }, "initial map through the origin");
  check(contains(msg, "vertex 100"), "initial map sending vertex 100 to the origin: message names it");
  // non-finite coordinates, for SDEM and LSDEM
  put(folded, vertex_descriptor(100), Point(0, std::numeric_limits<double>::quiet_NaN(), 1));
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::spherical_density_equalizing_map(m, o2, P::initial_map(folded)); }, "NaN initial map");
  check(contains(msg, "non-finite"), "NaN initial map: message says non-finite (" + msg + ")");
  const Landmarks lm = {{vertex_descriptor(0), Point(1, 0, 0)}};
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, o2, P::initial_map(folded)); },
    "LSDEM NaN initial map");
  check(contains(msg, "non-finite"), "LSDEM NaN initial map: message says non-finite (" + msg + ")");
  check(untouched(m, o2), "non-finite initial map: nothing written");
}

void test_progress_callback()
{
  Mesh m = icosphere(3);
  const Face_values pop = cap_population(m, 10.);
  std::vector<std::pair<std::size_t, double> > calls;
  auto record = [&](std::size_t it, double err) { calls.emplace_back(it, err); return true; };
  Point_map out = output_map(m, "v:sdem");
  DEM::Map_report r =
    DEM::spherical_density_equalizing_map(m, out, P::combine(P::progress_callback(record), P::face_population_map(pop)));
  check(r.iterations > 3, "callback run: more than 3 iterations (needed for the cancellation test)");
  check(calls.size() == r.iterations, "callback called once per iteration");
  bool increasing = true, finite = true;
  for(std::size_t k = 0; k < calls.size(); ++k) {
    increasing = increasing && calls[k].first == k + 1;
    finite = finite && std::isfinite(calls[k].second) && calls[k].second >= 0;
  }
  check(increasing, "callback iteration numbers are 1, 2, 3, ...");
  check(finite, "callback errors are finite and non-negative");
  check(!calls.empty() && calls.back().second == r.final_error, "last callback error is the report's final error");

  std::size_t n_calls = 0;
  auto stop_at_3 = [&](std::size_t it, double) { ++n_calls; return it < 3; };
  Point_map out2 = output_map(m, "v:cancelled");
  r = DEM::spherical_density_equalizing_map(m, out2,
                                            P::combine(P::progress_callback(stop_at_3), P::face_population_map(pop)));
  check(r.termination == DEM::Termination::CANCELLED, "returning false cancels (Termination::CANCELLED)");
  check(r.iterations == 3 && n_calls == 3, "cancelled after the third iteration");
  check(!r.converged(), "a cancelled run does not claim convergence");
  check_bijective_on_sphere(m, out2, r, "SDEM cancelled");
}

void test_bad_input()
{
  Mesh m = icosphere(2);
  Point_map out = output_map(m, "v:out");
  Face_values pop = m.add_property_map<face_descriptor, double>("f:pop", 1.).first;
  auto run = [&](const auto& np) { return [&m, &out, np] { DEM::spherical_density_equalizing_map(m, out, np); }; };

  put(pop, face_descriptor(12), 0.);
  std::string msg = expect_throw<DEM::Invalid_input>(run(P::face_population_map(pop)), "zero population");
  std::cout << "zero population: " << msg << std::endl;
  check(contains(msg, "face 12") && contains(msg, "population"), "zero population: message names face 12");
  put(pop, face_descriptor(12), 1.);
  put(pop, face_descriptor(33), -1.);
  msg = expect_throw<DEM::Invalid_input>(run(P::face_population_map(pop)), "negative population");
  check(contains(msg, "face 33"), "negative population: message names face 33");
  put(pop, face_descriptor(33), 1.);
  put(pop, face_descriptor(57), std::numeric_limits<double>::quiet_NaN());
  msg = expect_throw<DEM::Invalid_input>(run(P::face_population_map(pop)), "NaN population");
  std::cout << "NaN population: " << msg << std::endl;
  check(contains(msg, "face 57"), "NaN population: message names face 57");
  put(pop, face_descriptor(57), std::numeric_limits<double>::infinity());
  msg = expect_throw<DEM::Invalid_input>(run(P::face_population_map(pop)), "infinite population");
  check(contains(msg, "face 57"), "infinite population: message names face 57");
  put(pop, face_descriptor(57), 1.);

  for(double dt : {0., -0.1, std::numeric_limits<double>::quiet_NaN()}) {
    msg = expect_throw<DEM::Invalid_input>(run(P::time_step(dt)), "time_step " + std::to_string(dt));
    check(contains(msg, "time_step"), "time_step " + std::to_string(dt) + ": message names time_step (" + msg + ")");
  }
  for(double t : {0., 1., -0.5, 1.5}) {
    msg = expect_throw<DEM::Invalid_input>(run(P::truncation(t)), "truncation " + std::to_string(t));
    check(contains(msg, "truncation"), "truncation " + std::to_string(t) + ": message names truncation");
  }
  msg = expect_throw<DEM::Invalid_input>(run(P::stopping_tolerance(0.)), "tolerance 0");
  check(contains(msg, "stopping_tolerance"), "stopping_tolerance 0: message names it");
  check(untouched(m, out), "bad input: nothing written to the output map");

  // a mesh the foundation rejects (open) is rejected here too
  Mesh open = open_icosphere(2);
  Point_map oo = output_map(open, "v:out");
  msg = expect_throw<DEM::Invalid_input>([&] { DEM::spherical_density_equalizing_map(open, oo); }, "open mesh");
  check(contains(msg, "boundary"), "open mesh: message says boundary (" + msg + ")");
}

// ---------------------------------------------------------------------------
// LSDEM

void test_lsdem_bad_input()
{
  Mesh m = icosphere(2);
  Point_map out = output_map(m, "v:out");
  Landmarks lm = {{vertex_descriptor(0), Point(1, 0, 0)}, {vertex_descriptor(100000), Point(0, 1, 0)}};
  std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "landmark out of range");
  std::cout << "landmark out of range: " << msg << std::endl;
  check(contains(msg, "out of range") && contains(msg, "100000"), "landmark vertex out of range: message names it");

  lm = {{vertex_descriptor(0), Point(1, 0, 0)}, {vertex_descriptor(5), Point(0, 1.5, 0)}};
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "target off the sphere");
  std::cout << "target off the sphere: " << msg << std::endl;
  check(contains(msg, "landmark 1") && contains(msg, "unit sphere"), "target not on the unit sphere: message names landmark 1");

  lm = {{vertex_descriptor(0), Point(std::numeric_limits<double>::quiet_NaN(), 0, 0)}};
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "NaN target");
  check(contains(msg, "landmark 0"), "NaN landmark target: message names landmark 0");

  lm.clear();
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "no landmarks");
  check(contains(msg, "landmark"), "no landmarks: rejected");

  lm = {{vertex_descriptor(0), Point(1, 0, 0)}};
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out, P::landmark_weight(-1.)); },
    "negative weight");
  check(contains(msg, "weight") || contains(msg, "gamma"), "negative landmark_weight: rejected");
  check(untouched(m, out), "LSDEM bad input: nothing written");
}

/// Targets for 8 spread vertices of an icosphere, each displaced by 0.15 rad
/// along a vertex-dependent tangent direction, so that no rotation aligns them.
Landmarks displaced_landmarks(const Mesh& m)
{
  Landmarks lm;
  for(int k = 0; k < 8; ++k) {
    const vertex_descriptor v(k);
    const Eigen::Vector3d p(m.point(v).x(), m.point(v).y(), m.point(v).z());
    Eigen::Vector3d t = p.cross(Eigen::Vector3d(std::cos(k), std::sin(k), 0.3 * k - 1)).normalized();
    const Eigen::Vector3d q = (std::cos(0.15) * p + std::sin(0.15) * t).normalized();
    lm.emplace_back(v, Point(q.x(), q.y(), q.z()));
  }
  return lm;
}

double mean_landmark_distance(const Point_map& out, const Landmarks& lm)
{
  double err = 0;
  for(const auto& l : lm) err += std::sqrt(CGAL::squared_distance(get(out, l.first), l.second));
  return err / lm.size();
}

/// Each term of LSDEM's flow does its job: with a population 5x denser on a
/// cap, the density variance of the output falls as the density weight alpha
/// grows, the landmark error as the landmark weight gamma grows, and the
/// conformal distortion as the harmonic weight beta grows (the other two
/// weights at the paper's 1, 2, 5). Measured: Var(vertex density) 0.54, 0.13,
/// 0.026 for alpha = 0, 1, 4; landmark error 0.078, 0.045, 0.035 for gamma =
/// 0.5, 5, 20; mean |mu| 0.19, 0.11, 0.081 for beta = 0, 2, 8.
void test_lsdem_weights()
{
  Mesh m = icosphere(3);
  const Face_values pop = cap_population(m, 5.);
  const Landmarks lm = displaced_landmarks(m);
  Point_map out = output_map(m, "v:lsdem_weights");
  struct Outcome { double variance, landmark_error, mu; };
  auto run = [&](double alpha, double beta, double gamma) {
    const DEM::Map_report r = DEM::landmark_aligned_spherical_density_equalizing_map(
      m, lm, out,
      P::combine(P::density_weight(alpha), P::harmonic_weight(beta), P::landmark_weight(gamma),
                 P::face_population_map(pop)));
    const std::string what = "LSDEM (alpha, beta, gamma) = (" + std::to_string(alpha) + ", " + std::to_string(beta) +
                             ", " + std::to_string(gamma) + ")";
    check_bijective_on_sphere(m, out, r, what);
    const Outcome o = {DEM::density_variance(m, out, P::face_population_map(pop)).vertex,
                       mean_landmark_distance(out, lm), DEM::map_distortion(m, out).mean_abs_mu};
    std::cout << what << ": Var(vertex density) " << o.variance << ", landmark error " << o.landmark_error
              << ", mean|mu| " << o.mu << std::endl;
    return o;
  };
  const double initial = DEM::density_variance(m, m.points(), P::face_population_map(pop)).vertex;
  const Outcome paper = run(1., 2., 5.); // the paper's weights, the middle of each series
  const Outcome alpha_0 = run(0., 2., 5.), alpha_4 = run(4., 2., 5.);
  check(paper.variance < 0.6 * alpha_0.variance && alpha_4.variance < 0.6 * paper.variance,
        "LSDEM: Var(vertex density) falls as alpha grows (0, 1, 4)");
  check(alpha_4.variance < initial / 20, "LSDEM alpha = 4: Var(vertex density) reduced twentyfold");
  const Outcome gamma_low = run(1., 2., 0.5), gamma_high = run(1., 2., 20.);
  check(paper.landmark_error < 0.9 * gamma_low.landmark_error && gamma_high.landmark_error < 0.9 * paper.landmark_error,
        "LSDEM: landmark error falls as gamma grows (0.5, 5, 20)");
  const Outcome beta_0 = run(1., 0., 5.), beta_8 = run(1., 8., 5.);
  check(paper.mu < 0.9 * beta_0.mu && beta_8.mu < 0.9 * paper.mu, "LSDEM: mean |mu| falls as beta grows (0, 2, 8)");
}

void test_lsdem()
{
  Mesh m = icosphere(3); // 642 vertices
  const Landmarks lm = displaced_landmarks(m);
  Point_map out = output_map(m, "v:lsdem");
  // default population (area): the landmark term competes with the harmonic
  // and area terms only. (With a population 10x denser on a cap, alpha = 1 and
  // gamma = 5, the density term wins and the landmark error stays ~0.1.)
  const DEM::Map_report r = DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out);
  check_bijective_on_sphere(m, out, r, "LSDEM icosphere 8 landmarks");
  const double err = mean_landmark_distance(out, lm);
  const DEM::Distortion_statistics d = DEM::map_distortion(m, out);
  std::cout << "LSDEM: landmark error " << r.landmark_error << " (recomputed " << err << "), mean|mu| "
            << d.mean_abs_mu << ", mean|d_area| " << d.mean_abs_darea << std::endl;
  check(std::abs(err - r.landmark_error) <= 1e-12, "LSDEM: report.landmark_error is the mean landmark distance");
  check(err <= 0.01, "LSDEM: mean landmark error <= 0.01 (targets displaced by 0.15)");
  check(d.mean_abs_mu <= 0.15, "LSDEM: mean |mu| <= 0.15");
  check(d.mean_abs_darea <= 0.15, "LSDEM: mean |d_area| <= 0.15 (area population)");
}

} // namespace

// The stage names a progress display shows (named parameter stage_callback):
// every stage of the run is announced once, in the order it runs, and the
// iterations come after the initial map they start from.
void test_stage_callback()
{
  Mesh m = icosphere(3);
  const Face_values pop = cap_population(m, 10.);
  std::vector<std::string> stages;
  auto record = [&](const std::string& name) { stages.push_back(name); };
  Point_map out = output_map(m, "v:sdem_stages");
  DEM::spherical_density_equalizing_map(m, out, P::combine(P::stage_callback(record), P::face_population_map(pop)));
  const std::vector<std::string> expected = {"validation", "harmonic map (cotangent Laplacian, sparse Cholesky)",
                                             "south-chart LBS correction", "Moebius area correction",
                                             "density-equalizing iterations"};
  check(stages == expected, "SDEM announces validation, harmonic map, south-chart LBS, Moebius correction and the "
                            "iterations, in this order (" + std::to_string(stages.size()) + " stages)");
  stages.clear();
  Point_map sphere = output_map(m, "v:scm_stages");
  DEM::spherical_conformal_map(m, sphere, P::combine(P::mobius_area_correction(true), P::stage_callback(record)));
  check(stages.size() == 5 && stages[3] == "Moebius area correction" && stages[4] == "exact fold-over count",
        "the conformal map announces the Moebius correction and the exact fold-over count");
}

int main()
{
  Stopwatch total;
  test_stage_callback();
  test_smooth_cap_population();
  test_step_cap_population();
  test_extreme_population();
  test_area_preserving();
  test_vertex_density();
  test_initial_map();
  test_progress_callback();
  test_bad_input();
  test_lsdem_bad_input();
  test_lsdem();
  test_lsdem_weights();
  std::cout << "total " << total.seconds() << " s" << std::endl;
  return finish("test_spherical_density_equalizing");
}
