// Properties of the ellipsoidal density-equalizing map (EDEM) and of its
// quasi-conformal variant with radius search (EDEQ) on generated ellipsoid
// meshes (no shared data): bijectivity by the exact fold-over count, points on
// the ellipsoid to 1e-12, density variance reduced, the radii reported and
// searched, and the messages of bad input. The shared-mesh acceptance cases
// are in test_edem_shared.cpp.
#include <dem_test_meshes.h>

#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/measures.h>

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace P = CGAL::Density_equalizing_maps::parameters;
namespace I = CGAL::Density_equalizing_maps::internal;
using namespace dem_test;

typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_values;
typedef std::array<double, 3> Radii;

namespace {

double face_area(const Mesh& m, face_descriptor f)
{
  const auto h = m.halfedge(f);
  return std::sqrt(CGAL::squared_area(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h)))));
}

/// population = area * (1 + (ratio - 1) smoothstep((z/c - 0.2) / 0.6)): the cap
/// z/c > 0.2 becomes up to `ratio` times denser.
Face_values cap_population(Mesh& m, double c, double ratio)
{
  Face_values p = m.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(face_descriptor f : faces(m)) {
    const auto h = m.halfedge(f);
    const double z = (m.point(m.source(h)).z() + m.point(m.target(h)).z() + m.point(m.target(m.next(h))).z()) / 3;
    const double u = std::min(1., std::max(0., (z / c - 0.2) / 0.6));
    put(p, f, face_area(m, f) * (1 + (ratio - 1) * u * u * (3 - 2 * u)));
  }
  return p;
}

void check_output(const Mesh& m, const Point_map& out, const DEM::Map_report& r, const Radii& radii,
                  const std::string& what)
{
  const std::size_t folds = DEM::number_of_fold_overs(m, out);
  const double dev = max_level_deviation(m, out, radii);
  std::cout << what << ": " << r.iterations << " iterations (" << DEM::to_string(r.termination) << "), error "
            << r.initial_error << " -> " << r.final_error << ", repairs " << r.repairs << ", fold-overs "
            << r.fold_overs << "/" << folds << ", max level deviation " << dev
            << (r.message.empty() ? "" : ", note: " + r.message) << std::endl;
  check(r.fold_overs == 0, what + ": report says 0 fold-overs");
  check(folds == 0, what + ": exact count finds 0 fold-overs");
  check(dev <= 1e-12, what + ": points on the ellipsoid (1e-12 relative)");
}

// ---------------------------------------------------------------------------

void test_edem_population()
{
  const Radii radii = {1., 0.8, 1.5};
  Mesh m = ellipsoid(radii[0], radii[1], radii[2], 4); // 2562 vertices
  const Face_values pop = cap_population(m, radii[2], 10.);
  const auto np_pop = P::face_population_map(pop);
  Point_map out = output_map(m, "v:edem");
  const DEM::Map_report r =
    DEM::ellipsoidal_density_equalizing_map(m, out, P::combine(P::ellipsoid_radii(radii), np_pop));
  check_output(m, out, r, radii, "EDEM cap x10");
  check(r.radii.size() == 3 && r.radii[0] == radii[0] && r.radii[1] == radii[1] && r.radii[2] == radii[2],
        "EDEM reports the radii it used");
  check(r.converged(), "EDEM cap x10: converged");
  // the input lies on the same ellipsoid: its density variance is the initial one
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), np_pop);
  const DEM::Density_variance v1 = DEM::density_variance(m, out, np_pop);
  std::cout << "EDEM cap x10: Var(vertex density) " << v0.vertex << " -> " << v1.vertex << ", Var(face density) "
            << v0.face << " -> " << v1.face << std::endl;
  // 0.014 is the bound of issue 5 for the shared meshes (paper 000 Table 1)
  check(v1.face <= 0.014 && v1.face <= v0.face / 10, "EDEM cap x10: Var(face density) <= min(0.014, initial/10)");
  check(v1.vertex <= 0.002, "EDEM cap x10: Var(vertex density) <= 0.002");
}

void test_edem_area_and_default_radii()
{
  Mesh m = to_mesh(bumpy_arrays(3, 0.2, 1.6)); // a bumpy ellipsoid-like surface
  Point_map out = output_map(m, "v:edem");
  // no radii: the bounding-box radii of the input (mean 1)
  const DEM::Map_report r = DEM::ellipsoidal_density_equalizing_map(m, out);
  check(r.radii.size() == 3, "EDEM default radii reported");
  if(r.radii.size() != 3) return;
  const Radii radii = {r.radii[0], r.radii[1], r.radii[2]};
  std::cout << "EDEM default radii " << radii[0] << " " << radii[1] << " " << radii[2] << std::endl;
  check(std::abs((radii[0] + radii[1] + radii[2]) / 3 - 1) < 1e-9, "EDEM default radii have mean 1");
  check_output(m, out, r, radii, "EDEM area-preserving bumpy");
  const DEM::Distortion_statistics d = DEM::map_distortion(m, out);
  std::cout << "EDEM area-preserving bumpy: mean|d_area| " << d.mean_abs_darea << ", mean|mu| " << d.mean_abs_mu
            << std::endl;
  check(d.mean_abs_darea <= 0.05, "EDEM area-preserving bumpy: mean|d_area| <= 0.05");
}

void test_edem_bad_input()
{
  Mesh m = ellipsoid(1, 1, 1.5, 2);
  Point_map out = output_map(m, "v:out");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for(const Radii& r : {Radii{0., 1., 1.}, Radii{1., -1., 1.}, Radii{1., 1., nan}, Radii{-1., -1., -1.}}) {
    const std::string what = "radii (" + std::to_string(r[0]) + ", " + std::to_string(r[1]) + ", " +
                             std::to_string(r[2]) + ")";
    std::string msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::ellipsoidal_density_equalizing_map(m, out, P::ellipsoid_radii(r)); }, "EDEM " + what);
    std::cout << "EDEM " << what << ": " << msg << std::endl;
    check(contains(msg, "radi"), "EDEM " + what + ": message names the radii");
    msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::ellipsoid_radii(r)); }, "EDEQ " + what);
    check(contains(msg, "radi"), "EDEQ " + what + ": message names the radii");
  }
  Face_values pop = m.add_property_map<face_descriptor, double>("f:pop", 1.).first;
  put(pop, face_descriptor(21), -3.);
  std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_map(m, out, P::face_population_map(pop)); }, "EDEM negative population");
  check(contains(msg, "face 21"), "EDEM negative population: message names face 21 (" + msg + ")");
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::face_population_map(pop)); },
    "EDEQ negative population");
  check(contains(msg, "face 21"), "EDEQ negative population: message names face 21");
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_map(m, out, P::time_step(0.)); }, "EDEM time_step 0");
  check(contains(msg, "time_step"), "EDEM time_step 0: message names time_step");
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::beltrami_weight(-1.)); },
    "EDEQ negative beltrami_weight");
  check(contains(msg, "beltrami_weight"), "EDEQ negative beltrami_weight: message names it");

  // a folded initial map (mirror image)
  Point_map mirror = m.add_property_map<vertex_descriptor, Point>("v:mirror").first;
  for(vertex_descriptor v : vertices(m)) put(mirror, v, Point(-m.point(v).x(), m.point(v).y(), m.point(v).z()));
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_map(m, out, P::initial_map(mirror)); }, "EDEM mirrored initial map");
  check(contains(msg, "not bijective"), "EDEM mirrored initial map: message says not bijective (" + msg + ")");
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::initial_map(mirror)); },
    "EDEQ mirrored initial map");
  check(contains(msg, "not bijective"), "EDEQ mirrored initial map: message says not bijective (" + msg + ")");
  // one vertex sent to its antipode: a few folded faces only
  Point_map folded = m.add_property_map<vertex_descriptor, Point>("v:folded").first;
  for(vertex_descriptor v : vertices(m)) put(folded, v, m.point(v));
  const Point p40 = m.point(vertex_descriptor(40));
  put(folded, vertex_descriptor(40), Point(-p40.x(), -p40.y(), -p40.z()));
  msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::combine(P::ellipsoid_radii(Radii{1., 1., 1.5}), P::initial_map(folded))); },
    "EDEQ folded initial map");
  check(contains(msg, "not bijective") && contains(msg, "fold-over"),
        "EDEQ folded initial map: message says not bijective, with the fold-over count (" + msg + ")");
  put(folded, vertex_descriptor(40), Point(std::numeric_limits<double>::infinity(), 0, 0));
  for(int method = 0; method < 2; ++method) {
    const std::string name = method == 0 ? "EDEM" : "EDEQ";
    msg = expect_throw<DEM::Invalid_input>(
      [&] {
        if(method == 0) DEM::ellipsoidal_density_equalizing_map(m, out, P::initial_map(folded));
        else DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, P::initial_map(folded));
      },
      name + " non-finite initial map");
    check(contains(msg, "non-finite"), name + " non-finite initial map: message says non-finite (" + msg + ")");
  }
  check(untouched(m, out), "EDEM/EDEQ bad input: nothing written");

  Mesh open = open_icosphere(2);
  Point_map oo = output_map(open, "v:out");
  msg = expect_throw<DEM::Invalid_input>([&] { DEM::ellipsoidal_density_equalizing_map(open, oo); }, "EDEM open mesh");
  check(contains(msg, "boundary"), "EDEM open mesh: message says boundary");
}

void test_edem_initial_map()
{
  // the input itself as the initial map: it lies on the ellipsoid
  const Radii radii = {1., 0.8, 1.5};
  Mesh m = ellipsoid(radii[0], radii[1], radii[2], 3);
  const Face_values pop = cap_population(m, radii[2], 5.);
  Point_map out = output_map(m, "v:edem");
  const DEM::Map_report r = DEM::ellipsoidal_density_equalizing_map(
    m, out, P::combine(P::ellipsoid_radii(radii), P::initial_map(m.points()), P::face_population_map(pop)));
  check_output(m, out, r, radii, "EDEM from the identity");
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), P::face_population_map(pop));
  const DEM::Density_variance v1 = DEM::density_variance(m, out, P::face_population_map(pop));
  std::cout << "EDEM from the identity: Var(face density) " << v0.face << " -> " << v1.face << std::endl;
  check(v1.face <= v0.face / 10, "EDEM from the identity: Var(face density) reduced tenfold");

  std::size_t calls = 0;
  auto stop_at_2 = [&](std::size_t it, double) { ++calls; return it < 2; };
  const DEM::Map_report rc = DEM::ellipsoidal_density_equalizing_map(
    m, out, P::combine(P::ellipsoid_radii(radii), P::progress_callback(stop_at_2), P::face_population_map(pop)));
  check(rc.termination == DEM::Termination::CANCELLED && rc.iterations == 2 && calls == 2,
        "EDEM: the progress callback cancels after the second iteration");
  check_output(m, out, rc, radii, "EDEM cancelled");
}

/// The EDEQ energy E = E_density + alpha E_BC of a map (the quantity the radius search lowers).
double edeq_energy(const Mesh& m, const Point_map& map, const Point_map& reference, const Face_values& pop,
                   double alpha)
{
  const auto a = I::closed_surface_arrays(m, CGAL::parameters::default_values(), 2);
  I::Vector p(a.F.rows());
  for(std::size_t k = 0; k < a.faces.size(); ++k) p[k] = get(pop, a.faces[k]);
  const auto solver = I::solver_from_parameters(CGAL::parameters::default_values());
  I::Radii_search_flow flow(a.F, p, I::read_points(a, reference), alpha, 0.1, *solver);
  return flow.energy(I::read_points(a, map));
}

void test_edeq()
{
  // an ellipsoid (1, 0.8, 1.6) mesh, searched from the initial radii (1, 1, 1.2)
  Mesh m = ellipsoid(1, 0.8, 1.6, 3); // 642 vertices
  const Face_values pop = cap_population(m, 1.6, 5.);
  const Radii r0 = {1., 1., 1.2};
  Point_map out = output_map(m, "v:edeq");
  const DEM::Map_report r = DEM::ellipsoidal_density_equalizing_quasiconformal_map(
    m, out, P::combine(P::ellipsoid_radii(r0), P::face_population_map(pop)));
  check(r.radii.size() == 3, "EDEQ reports 3 radii");
  if(r.radii.size() != 3) return;
  const Radii rf = {r.radii[0], r.radii[1], r.radii[2]};
  std::cout << "EDEQ radii (1, 1, 1.2) -> (" << rf[0] << ", " << rf[1] << ", " << rf[2] << ")" << std::endl;
  check(rf[0] == r0[0], "EDEQ keeps a (the scale is free)");
  check(rf[1] != r0[1] || rf[2] != r0[2], "EDEQ changed b or c");
  check(rf[1] > 0 && rf[2] > 0, "EDEQ radii positive");
  check_output(m, out, r, rf, "EDEQ");
  const DEM::Density_variance v0 = DEM::density_variance(m, m.points(), P::face_population_map(pop));
  const DEM::Density_variance v1 = DEM::density_variance(m, out, P::face_population_map(pop));
  const DEM::Distortion_statistics d = DEM::map_distortion(m, out);
  std::cout << "EDEQ: Var(face density) " << v0.face << " -> " << v1.face << ", mean|mu| " << d.mean_abs_mu
            << std::endl;
  check(v1.face <= v0.face / 5, "EDEQ: Var(face density) reduced fivefold");
  check(d.mean_abs_mu <= 0.25, "EDEQ: mean |mu| <= 0.25");

  // The energy the search lowers: E = E_density + 5 E_BC, the Beltrami term
  // measured from the starting map. E_BC grows while the density equalizes,
  // so E along the run is not monotone (measured here: 41.9 -> 141); but each
  // search keeps the radii of lowest E, so the radii found must beat the
  // initial ones on the final map: E(final map) < E(final map rescaled
  // axis-wise back onto the initial radii).
  Point_map start = output_map(m, "v:start");
  const DEM::Map_report rs = DEM::ellipsoidal_conformal_map(m, start, P::ellipsoid_radii(r0));
  check(rs.fold_overs == 0, "EDEQ: the starting FECM map is bijective");
  Point_map back = output_map(m, "v:rescaled");
  for(vertex_descriptor v : vertices(m)) {
    const Point& p = get(out, v);
    put(back, v, Point(p.x() * r0[0] / rf[0], p.y() * r0[1] / rf[1], p.z() * r0[2] / rf[2]));
  }
  const double e_start = edeq_energy(m, start, start, pop, 5.), e_final = edeq_energy(m, out, start, pop, 5.),
               e_back = edeq_energy(m, back, start, pop, 5.);
  std::cout << "EDEQ energy: start " << e_start << ", final " << e_final << ", final map on the initial radii "
            << e_back << std::endl;
  check(e_final < e_back, "EDEQ: the radii found lower E on the final map against the initial radii");
  // with alpha = 0 only the density term drives the search: the output must
  // still be bijective and on the ellipsoid it reports
  const DEM::Map_report r_a0 = DEM::ellipsoidal_density_equalizing_quasiconformal_map(
    m, out, P::combine(P::ellipsoid_radii(r0), P::face_population_map(pop), P::beltrami_weight(0.)));
  if(check(r_a0.radii.size() == 3, "EDEQ alpha = 0 reports 3 radii")) {
    std::cout << "EDEQ alpha = 0: radii (" << r_a0.radii[0] << ", " << r_a0.radii[1] << ", " << r_a0.radii[2] << ")"
              << std::endl;
    check_output(m, out, r_a0, {r_a0.radii[0], r_a0.radii[1], r_a0.radii[2]}, "EDEQ alpha = 0");
    // the search is driven by the energy: another Beltrami weight, other radii
    check(r_a0.radii[0] == r0[0] && (r_a0.radii[1] != rf[1] || r_a0.radii[2] != rf[2]),
          "EDEQ: the radii found depend on the energy's Beltrami weight");
  }
}

} // namespace

int main()
{
  Stopwatch total;
  test_edem_population();
  test_edem_area_and_default_radii();
  test_edem_bad_input();
  test_edem_initial_map();
  test_edeq();
  std::cout << "total " << total.seconds() << " s" << std::endl;
  return finish("test_ellipsoidal_density_equalizing");
}
