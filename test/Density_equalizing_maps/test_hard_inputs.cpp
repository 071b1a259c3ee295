// Hard but valid inputs (issue 14), on generated meshes only:
//   quick (no argument, default suite): the smallest meshes (a tetrahedron, a
//     10-vertex bipyramid) map fold-free with every genus-0 method; an input
//     scaled by 1e+100 and 1e-100 gives the same map as the original; the
//     conformal maps of a mesh with sliver faces (1e-4 of the mean area) are
//     fold-free with the quality of the sliver-free mesh; a fallback is told
//     in the report; a density-only flow that does not converge returns the
//     most uniform of its maps (SDEM, EDEM on a step population of ratio 1e4).
//   `long` (ctest label `hard`): capsules 10:1 and 30:1 and populations of
//     ratio 1e2..1e6 (steps and smooth bumps) for SDEM, EDEM and TDEM: fold-free,
//     honest about convergence, and a run that does not converge returns a map
//     at least as uniform as its start.
//   `known` (label known_failure): the acceptance items of issue 14 that do
//     not hold yet (SDEM, EDEM, TDEM converging on extreme populations within
//     10x the time of a mild one; SDEM converging on sliver meshes).

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include "dem_test_meshes.h"

#include <sys/wait.h>

#include <cstdlib>
#include <functional>

namespace DEM = CGAL::Density_equalizing_maps;
namespace PM = CGAL::Density_equalizing_maps::parameters;
using namespace dem_test;

namespace {

typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_map;
typedef std::vector<std::pair<vertex_descriptor, Point> > Landmarks;

// ---------------------------------------------------------------------------
// Generated hard inputs

/// The bipyramid over a regular k-gon in the plane z = 0 (k + 2 vertices).
Arrays bipyramid_arrays(int k = 8)
{
  std::vector<Eigen::Vector3d> V;
  for(int i = 0; i < k; ++i) V.emplace_back(std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), 0);
  V.emplace_back(0, 0, 1);
  V.emplace_back(0, 0, -1);
  std::vector<Eigen::Vector3i> T;
  for(int i = 0; i < k; ++i) {
    T.emplace_back(i, (i + 1) % k, k);
    T.emplace_back((i + 1) % k, i, k + 1);
  }
  Arrays a = make_arrays(V, T);
  orient_outward(a);
  return a;
}

/// Splits every `stride`-th edge (a, b) (no two on one face) at p = a + ratio (b - a):
/// each face on the edge becomes a sliver of `ratio` times its area and a near
/// copy of itself. p lies on the edge, so the surface is unchanged and the
/// input is its own sliver-free remesh.
Arrays with_slivers(const Arrays& in, double ratio, int stride)
{
  std::vector<Eigen::Vector3d> V;
  for(Eigen::Index i = 0; i < in.X.rows(); ++i) V.push_back(in.X.row(i).transpose());
  std::vector<Eigen::Vector3i> T;
  for(Eigen::Index k = 0; k < in.F.rows(); ++k) T.push_back(in.F.row(k).transpose());
  std::map<std::pair<int, int>, std::vector<int> > edge_faces;
  for(int k = 0; k < int(T.size()); ++k)
    for(int c = 0; c < 3; ++c) {
      const int a = T[k][c], b = T[k][(c + 1) % 3];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(k);
    }
  std::vector<char> used(T.size(), 0);
  int count = 0;
  for(const auto& e : edge_faces) {
    if(count++ % stride != 0) continue;
    const std::vector<int>& fs = e.second;
    if(fs.size() != 2 || used[fs[0]] || used[fs[1]]) continue;
    const int a = e.first.first, b = e.first.second;
    const int p = int(V.size());
    V.push_back(V[a] + ratio * (V[b] - V[a]));
    for(int k : fs) {
      used[k] = 1;
      Eigen::Vector3i t = T[k];
      while(!((t[0] == a && t[1] == b) || (t[0] == b && t[1] == a))) t = Eigen::Vector3i(t[1], t[2], t[0]);
      T[k] = Eigen::Vector3i(t[0], p, t[2]);
      T.emplace_back(p, t[1], t[2]);
    }
  }
  return make_arrays(V, T);
}

/// Capsule of radius 1 and length `length` along z (hemispherical caps), with
/// near-equilateral triangles of side about 2 pi / ring.
Arrays capsule_arrays(double length, int ring = 24)
{
  const double h = 2 * M_PI / ring, half = length / 2 - 1;
  std::vector<std::pair<double, double> > rows; // (z, radius)
  const int cap = std::max(2, int(std::lround(M_PI / 2 / h)));
  for(int i = 1; i < cap; ++i) {
    const double th = -M_PI / 2 + i * (M_PI / 2) / cap;
    rows.emplace_back(-half + std::sin(th), std::cos(th));
  }
  const int body = std::max(1, int(std::lround((length - 2) / h)));
  for(int i = 0; i <= body; ++i) rows.emplace_back(-half + i * (length - 2) / body, 1.);
  for(int i = 1; i < cap; ++i) {
    const double th = i * (M_PI / 2) / cap;
    rows.emplace_back(half + std::sin(th), std::cos(th));
  }
  std::vector<Eigen::Vector3d> V = {Eigen::Vector3d(0, 0, -length / 2)};
  for(std::size_t j = 0; j < rows.size(); ++j)
    for(int k = 0; k < ring; ++k) {
      const double ph = 2 * M_PI * (k + 0.5 * double(j % 2)) / ring;
      V.emplace_back(rows[j].second * std::cos(ph), rows[j].second * std::sin(ph), rows[j].first);
    }
  const int top = int(V.size());
  V.emplace_back(0, 0, length / 2);
  auto at = [ring](std::size_t j, int k) { return 1 + int(j) * ring + (k % ring); };
  std::vector<Eigen::Vector3i> T;
  for(int k = 0; k < ring; ++k) T.emplace_back(0, at(0, k + 1), at(0, k));
  for(std::size_t j = 0; j + 1 < rows.size(); ++j)
    for(int k = 0; k < ring; ++k) {
      if(j % 2 == 0) { T.emplace_back(at(j, k), at(j, k + 1), at(j + 1, k)); T.emplace_back(at(j, k + 1), at(j + 1, k + 1), at(j + 1, k)); }
      else { T.emplace_back(at(j, k), at(j + 1, k + 1), at(j + 1, k)); T.emplace_back(at(j, k), at(j, k + 1), at(j + 1, k + 1)); }
    }
  for(int k = 0; k < ring; ++k) T.emplace_back(top, at(rows.size() - 1, k), at(rows.size() - 1, k + 1));
  Arrays a = make_arrays(V, T);
  orient_outward(a);
  return a;
}

Arrays scaled(Arrays a, double s) { a.X *= s; return a; }

/// Population = density * area with the density a step (ratio on x > 0.3,
/// 1 elsewhere) or a smooth bump exp(log(ratio) g), g a Gaussian around (1,0,0).
Face_map population(Mesh& m, double ratio, bool step, double unit = 1)
{
  Face_map p = m.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(auto f : m.faces()) {
    std::vector<Eigen::Vector3d> c;
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      c.emplace_back(m.point(v).x(), m.point(v).y(), m.point(v).z());
    const Eigen::Vector3d g = (c[0] + c[1] + c[2]) / (3 * unit);
    const double area = 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm();
    const double rho = step ? (g.x() > 0.3 ? ratio : 1.)
                            : std::exp(std::log(ratio) * std::exp(-((g - Eigen::Vector3d(1, 0, 0)).squaredNorm()) / 0.18));
    p[f] = rho * area;
  }
  return p;
}

Point_map fresh(Mesh& m, const std::string& name) { return m.add_property_map<vertex_descriptor, Point>(name).first; }

double max_distance(const Mesh& m, Point_map a, Point_map b)
{
  double e = 0;
  for(auto v : m.vertices()) e = std::max(e, std::sqrt(CGAL::squared_distance(a[v], b[v])));
  return e;
}

/// The report agrees with the exact count, and the map is fold-free.
bool fold_free(const Mesh& m, Point_map out, const DEM::Map_report& r, const std::string& what)
{
  const std::size_t folds = DEM::number_of_fold_overs(m, out);
  const bool ok = check(folds == 0, what + ": 0 fold-overs (exact count " + std::to_string(folds) + ")");
  check(r.fold_overs == folds, what + ": report.fold_overs is the exact count");
  return ok;
}

// The genus-0 methods, by name, on a mesh; `radii` for the ellipsoidal ones.
enum class Method { SCM, FECM, FECM_OPT, FEQCM, SDEM, LSDEM, EDEM, EDEQ };
const char* name_of(Method k)
{
  switch(k) {
    case Method::SCM: return "SCM"; case Method::FECM: return "FECM"; case Method::FECM_OPT: return "FECM(opt radii)";
    case Method::FEQCM: return "FEQCM"; case Method::SDEM: return "SDEM"; case Method::LSDEM: return "LSDEM";
    case Method::EDEM: return "EDEM"; default: return "EDEQ";
  }
}

DEM::Map_report run(Method k, Mesh& m, Point_map out, const std::array<double, 3>& radii = {1, 1, 1})
{
  const vertex_descriptor v0 = *m.vertices().begin();
  switch(k) {
    case Method::SCM: return DEM::spherical_conformal_map(m, out);
    case Method::FECM: return DEM::ellipsoidal_conformal_map(m, out, PM::ellipsoid_radii(radii));
    case Method::FECM_OPT: return DEM::ellipsoidal_conformal_map(m, out, PM::optimize_radii(true));
    case Method::FEQCM: {
      const Landmarks lm = {{v0, Point(radii[0], 0, 0)}};
      return DEM::ellipsoidal_quasiconformal_map(m, lm, out, PM::ellipsoid_radii(radii));
    }
    case Method::SDEM: return DEM::spherical_density_equalizing_map(m, out);
    case Method::LSDEM: {
      const Landmarks lm = {{v0, Point(1, 0, 0)}};
      return DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out);
    }
    case Method::EDEM: return DEM::ellipsoidal_density_equalizing_map(m, out, PM::ellipsoid_radii(radii));
    default: return DEM::ellipsoidal_density_equalizing_quasiconformal_map(m, out, PM::ellipsoid_radii(radii));
  }
}

const Method all_methods[] = {Method::SCM, Method::FECM, Method::FECM_OPT, Method::FEQCM,
                              Method::SDEM, Method::LSDEM, Method::EDEM, Method::EDEQ};

// ---------------------------------------------------------------------------
// quick

void test_smallest_meshes()
{
  const std::pair<std::string, Arrays> meshes[] = {{"tetrahedron", tetrahedron_arrays()},
                                                   {"bipyramid", bipyramid_arrays()}};
  for(const auto& nm : meshes)
    for(Method k : all_methods) {
      Mesh m = to_mesh(nm.second);
      Point_map out = fresh(m, "v:out");
      const DEM::Map_report r = run(k, m, out);
      fold_free(m, out, r, nm.first + " " + name_of(k));
      // a fold-free FEQCM output whose landmark is far from its target is not
      // the map asked for: the report must say that the landmarks were given up
      if(k == Method::FEQCM)
        check(r.landmark_error < 0.1 || r.landmarks_given_up,
              nm.first + " FEQCM: landmark error " + std::to_string(r.landmark_error) + " is reported as given up");
      if(!r.fallback.empty()) std::cout << "  " << nm.first << " " << name_of(k) << " fallback: " << r.fallback << "\n";
    }
  // FECM on the tetrahedron folds 2 faces before the repair: the report must say so
  Mesh t = to_mesh(tetrahedron_arrays());
  Point_map out = fresh(t, "v:out");
  const DEM::Map_report r = DEM::ellipsoidal_conformal_map(t, out, PM::ellipsoid_radii(std::array<double, 3>{1, 1, 1}));
  check(!r.fallback.empty(), "tetrahedron FECM: the replaced map is reported in fallback (" + r.fallback + ")");
}

void test_scale()
{
  const Arrays base = bumpy_arrays(3, 0.2);
  for(Method k : {Method::SCM, Method::FECM, Method::SDEM, Method::EDEM, Method::EDEQ}) {
    Mesh m = to_mesh(base);
    Point_map ref = fresh(m, "v:ref");
    const DEM::Map_report r0 = run(k, m, ref);
    fold_free(m, ref, r0, std::string(name_of(k)) + " at unit scale");
    for(double s : {1e100, 1e-100}) {
      Mesh ms = to_mesh(scaled(base, s));
      Point_map out = fresh(ms, "v:out");
      std::string what = std::string(name_of(k)) + " at scale " + (s > 1 ? "1e+100" : "1e-100");
      DEM::Map_report r;
      try { r = run(k, ms, out); }
      catch(const std::exception& e) { check(false, what + " throws: " + e.what()); continue; }
      fold_free(ms, out, r, what);
      // the same map: the property maps hold the same vertex indices
      double e = 0;
      auto rv = m.vertices().begin();
      for(auto v : ms.vertices()) e = std::max(e, std::sqrt(CGAL::squared_distance(out[v], ref[*rv++])));
      // 1e+100 is not a power of two: the scaled coordinates are rounded
      // (relative 1e-16), and the Moebius area correction's Nelder-Mead search
      // that starts SDEM, EDEM and EDEQ stops on an objective tolerance of 1e-8,
      // which moves its stopping point by up to ~1e-5 (measured 8e-6; SCM and
      // FECM, without that search: below 1e-6). Without the normalization the
      // scaled runs throw or return NaN.
      const double tolerance = (k == Method::SCM || k == Method::FECM) ? 1e-6 : 1e-4;
      check(e < tolerance, what + ": the same map as at unit scale (max distance " + std::to_string(e) + ")");
      check(r.iterations == r0.iterations, what + ": the same iteration count");
    }
  }
}

void test_sliver_conformal()
{
  const Arrays clean = bumpy_arrays(4, 0.15);
  const Arrays sliver = with_slivers(clean, 1e-4, 25);
  std::cout << "  sliver mesh: " << sliver.F.rows() - clean.F.rows() << " sliver faces of 1e-4 of their face's area\n";
  for(Method k : {Method::SCM, Method::FECM}) {
    Mesh mc = to_mesh(clean), ms = to_mesh(sliver);
    Point_map oc = fresh(mc, "v:out"), os = fresh(ms, "v:out");
    const DEM::Map_report rc = run(k, mc, oc, {1, 1, 1}), rs = run(k, ms, os, {1, 1, 1});
    const std::string what = std::string(name_of(k)) + " on slivers";
    fold_free(ms, os, rs, what);
    check(rs.fallback.empty(), what + ": no fallback (" + rs.fallback + ")");
    const double mu_clean = DEM::map_distortion(mc, oc).mean_abs_mu, mu_sliver = DEM::map_distortion(ms, os).mean_abs_mu;
    check(std::abs(mu_sliver - mu_clean) <= 0.1 * mu_clean,
          what + ": mean |mu| " + std::to_string(mu_sliver) + " within 10% of the sliver-free " + std::to_string(mu_clean));
    (void)rc;
  }
}

void test_honest_non_convergence()
{
  // 3 iterations cannot equalize a bump of ratio 1e4: not converged, and the
  // report says how far it got
  Mesh m = to_mesh(icosphere_arrays(3));
  Face_map p = population(m, 1e4, false);
  Point_map out = fresh(m, "v:out");
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(m, out, PM::combine(PM::face_population_map(p), PM::number_of_iterations(3)));
  fold_free(m, out, r, "SDEM, 3 iterations on a 1e4 bump");
  check(!r.converged() && r.termination == DEM::Termination::MAXIMUM_ITERATIONS,
        "SDEM, 3 iterations on a 1e4 bump: not converged, maximum iterations");
  check(r.final_error < r.initial_error, "SDEM, 3 iterations: the stopping quantity decreased");
}

/// Var of the normalized re-coupled vertex density of a map (paper 001's measure).
double vertex_variance(const Mesh& m, Point_map mapped, Face_map p)
{
  return DEM::density_variance(m, mapped, PM::face_population_map(p)).vertex;
}

/// A density-only flow (SDEM, EDEM, TDEM) that does not converge returns the
/// most uniform of its maps: never a density less uniform than the start's.
/// `run(out, iterations)` maps with the given iteration limit (0: the initial map).
template <class Run>
void check_most_uniform(Mesh& m, Face_map p, const std::string& what, const Run& run, bool on_sphere = true)
{
  Point_map start = fresh(m, "v:start"), out = fresh(m, "v:out");
  run(start, 0);
  Stopwatch clock;
  const DEM::Map_report r = run(out, -1);
  const double v0 = vertex_variance(m, start, p), v1 = vertex_variance(m, out, p);
  std::cout << "  " << what << ": " << clock.seconds() << " s, " << r.iterations << " iterations, "
            << DEM::to_string(r.termination) << ", Var(vertex) " << v0 << " -> " << v1 << "; " << r.message << "\n";
  // number_of_fold_overs() counts about the centre (sphere, ellipsoid); the
  // torus report's count is that of the flat-torus layout (exact predicates)
  check(r.fold_overs == 0 && (!on_sphere || DEM::number_of_fold_overs(m, out) == 0),
        what + ": 0 fold-overs (exact count)");
  if(!r.converged()) {
    check(v1 <= v0, what + ": not converged, and the returned map is at least as uniform as the start (Var(vertex) " +
                      std::to_string(v0) + " -> " + std::to_string(v1) + ")");
    check(!contains(r.message, "less uniform"), what + ": no regression reported (" + r.message + ")");
  }
  m.remove_property_map(start);
  m.remove_property_map(out);
}

/// SDEM's start is Moebius-corrected towards the population when that is
/// closer to uniform density: on a smooth bump of ratio 1e4 the start is far
/// more uniform than the area-corrected conformal map (whose Var(vertex) is
/// ~58) and the flow converges in few iterations; on a step of ratio 1e4 the
/// area-corrected map is kept (never a less uniform start).
void test_population_mobius_start()
{
  Mesh sphere = to_mesh(icosphere_arrays(3));
  Point_map area_start = fresh(sphere, "v:area_start"), start = fresh(sphere, "v:start"), out = fresh(sphere, "v:out");
  DEM::spherical_conformal_map(sphere, area_start, PM::mobius_area_correction(true));
  for(bool step : {false, true}) {
    Face_map p = population(sphere, 1e4, step);
    const std::string what = std::string("SDEM ") + (step ? "step" : "bump") + " 1e4";
    const DEM::Map_report r0 = DEM::spherical_density_equalizing_map(
      sphere, start, PM::combine(PM::face_population_map(p), PM::number_of_iterations(0)));
    const std::string expected = step ? "conformal" : "conformal_population_moebius";
    check(r0.start == expected, what + ": Map_report::start is " + expected + " (" + r0.start + ")");
    const double v_area = vertex_variance(sphere, area_start, p), v_start = vertex_variance(sphere, start, p);
    std::cout << "  " << what << ": Var(vertex) of the area-corrected start " << v_area << ", of SDEM's start "
              << v_start << "\n";
    check(v_start <= v_area * (1 + 1e-9), what + ": the start is at least as uniform as the area-corrected map");
    if(!step) {
      check(v_start < 0.1 * v_area, what + ": the population-corrected start carries most of the contrast");
      const DEM::Map_report r = DEM::spherical_density_equalizing_map(sphere, out, PM::face_population_map(p));
      check(r.converged() && r.iterations <= 60,
            what + ": converges from it in at most 60 iterations (" + std::to_string(r.iterations) + ")");
    }
    sphere.remove_property_map(p);
  }
  sphere.remove_property_map(area_start);
  sphere.remove_property_map(start);
  sphere.remove_property_map(out);
}

/// SDEM or EDEM (radii 1, 1, 1) on `sphere` with population `p`, as a
/// `run(out, iterations)` of check_most_uniform().
std::function<DEM::Map_report(Point_map, int)> sphere_flow(Method k, Mesh& sphere, Face_map p)
{
  return [k, &sphere, p](Point_map out, int iterations) {
    const auto np = PM::combine(PM::face_population_map(p), PM::ellipsoid_radii(std::array<double, 3>{1, 1, 1}));
    if(iterations >= 0) {
      const auto np0 = PM::combine(np, PM::number_of_iterations(iterations));
      return k == Method::SDEM ? DEM::spherical_density_equalizing_map(sphere, out, np0)
                               : DEM::ellipsoidal_density_equalizing_map(sphere, out, np0);
    }
    return k == Method::SDEM ? DEM::spherical_density_equalizing_map(sphere, out, np)
                             : DEM::ellipsoidal_density_equalizing_map(sphere, out, np);
  };
}

void test_most_uniform_map()
{
  // a step population of ratio 1e4 on icosphere(3): EDEM's last map is less
  // uniform than its start (sd/mean 1.30 -> 1.42 after 300 iterations)
  Mesh sphere = to_mesh(icosphere_arrays(3));
  Face_map p = population(sphere, 1e4, true);
  for(Method k : {Method::SDEM, Method::EDEM})
    check_most_uniform(sphere, p, std::string(name_of(k)) + " step 1e4", sphere_flow(k, sphere, p));
  sphere.remove_property_map(p);
}

/// The dem tool tells a fallback and a non-converged run: the summary line
/// and the metrics JSON carry `fallback` and `repairs`, stderr has a warning.
std::string read_text(const std::string& file)
{
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int run_dem(const std::string& args, std::string& out, std::string& err)
{
  const std::string cmd = std::string("\"") + DEM_CLI + "\" " + args + " > hard_stdout.txt 2> hard_stderr.txt";
  const int status = std::system(cmd.c_str());
  out = read_text("hard_stdout.txt");
  err = read_text("hard_stderr.txt");
  return (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
}

void write_off(const Arrays& a, const std::string& file)
{
  std::ofstream o(file);
  o.precision(17);
  o << "OFF\n" << a.X.rows() << " " << a.F.rows() << " 0\n";
  for(Eigen::Index i = 0; i < a.X.rows(); ++i) o << a.X(i, 0) << " " << a.X(i, 1) << " " << a.X(i, 2) << "\n";
  for(Eigen::Index k = 0; k < a.F.rows(); ++k) o << "3 " << a.F(k, 0) << " " << a.F(k, 1) << " " << a.F(k, 2) << "\n";
}

void test_cli_honesty()
{
  std::string out, err;
  write_off(tetrahedron_arrays(), "hard_tetra.off");
  int code = run_dem("ellipsoidal-conformal hard_tetra.off --radii 1 1 1 --metrics hard_tetra.json", out, err);
  const std::string json = read_text("hard_tetra.json");
  check(code == 0, "dem FECM tetrahedron: exit 0 (fold-free after the fallback), got " + std::to_string(code));
  check(contains(json, "\"fallback\": \"") && contains(json, "\"repairs\": "),
        "dem FECM tetrahedron: metrics JSON names the fallback and the repairs");
  check(contains(out, "fallback: "), "dem FECM tetrahedron: the summary line names the fallback");
  check(contains(err, "warning") && contains(err, "fallback"), "dem FECM tetrahedron: a warning on stderr");

  write_off(icosphere_arrays(2), "hard_sphere.off");
  code = run_dem("sdem hard_sphere.off --metrics hard_sphere.json", out, err);
  check(contains(read_text("hard_sphere.json"), "\"fallback\": null"), "dem SDEM: fallback null when none");
  check(contains(read_text("hard_sphere.json"), "\"start\": \"conformal\""), "dem SDEM: the metrics name the start");
  check(!contains(err, "warning"), "dem SDEM on a sphere: no warning");
  // a run cut short: converged false in the JSON, and a warning on stderr
  Mesh m = to_mesh(icosphere_arrays(2));
  Face_map p = population(m, 1e4, false);
  {
    std::ofstream o("hard_sphere_population.txt");
    o.precision(17);
    for(auto f : m.faces()) o << p[f] << "\n";
  }
  code = run_dem("sdem hard_sphere.off --population hard_sphere_population.txt --max-iterations 3 --metrics "
                 "hard_sphere.json", out, err);
  const std::string j2 = read_text("hard_sphere.json");
  check(contains(j2, "\"converged\": false"), "dem SDEM cut short: converged false");
  check(code == 4 || contains(err, "did not converge"), "dem SDEM cut short: exit 4 or a warning on stderr (" + err + ")");
}

/// Elongated shapes (issue 14 item 3): the conformal start crowds (a 100:1
/// capsule's FLASH map folds, a 30:1 one leaves density ratios the flow stalls
/// on), so SDEM and EDEM start along the axis. Fold-free and converged, and the
/// report says which start was taken.
void test_elongated_starts()
{
  for(double L : {10., 30., 100.}) {
    const Arrays cap = capsule_arrays(L);
    const std::array<double, 3> fit = {1, 1, L / 2};
    for(Method k : {Method::SDEM, Method::EDEM}) {
      if(k == Method::EDEM && L > 30) continue; // 100:1: the EDEM flow is slow along 50 radii (RESULTS.md)
      Mesh m = to_mesh(cap);
      Point_map out = fresh(m, "v:out");
      const std::string what = "capsule " + std::to_string(int(L)) + ":1 " + name_of(k);
      Stopwatch clock;
      DEM::Map_report r;
      try { r = run(k, m, out, fit); }
      catch(const std::exception& e) { check(false, what + " throws: " + e.what()); continue; }
      std::cout << "  " << what << ": " << clock.seconds() << " s, " << r.iterations << " iterations, "
                << DEM::to_string(r.termination) << ", sd/mean " << r.initial_error << " -> " << r.final_error << "\n";
      fold_free(m, out, r, what);
      check(r.converged(), what + ": converges (" + DEM::to_string(r.termination) + ")");
      if(L >= 30) {
        check(contains(r.message, "along the principal axis"), what + ": the axial start is reported");
        check(r.start == "axial", what + ": Map_report::start is \"axial\" (" + r.start + ")");
      }
    }
  }
}

// ---------------------------------------------------------------------------
// long (label hard)

void test_capsules()
{
  for(double L : {10., 30.}) {
    const Arrays cap = capsule_arrays(L);
    const std::array<double, 3> fit = {1, 1, L / 2};
    for(Method k : {Method::SCM, Method::FECM_OPT, Method::SDEM, Method::EDEM, Method::EDEQ}) {
      if(k == Method::FECM_OPT && L > 10) continue; // the issue asks FECM for 10:1 only
      Mesh m = to_mesh(cap);
      Point_map out = fresh(m, "v:out");
      const std::string what = "capsule " + std::to_string(int(L)) + ":1 " + name_of(k);
      Stopwatch clock;
      const DEM::Map_report r = run(k, m, out, fit);
      std::cout << "  " << what << ": " << clock.seconds() << " s, " << r.iterations << " iterations, "
                << DEM::to_string(r.termination) << ", final error " << r.final_error << "\n";
      fold_free(m, out, r, what);
    }
  }
}

void test_extreme_populations()
{
  // not converged yet (issue 14 item 2, see the `known` mode), but fold-free
  // and never ending less uniform than the start
  Mesh sphere = to_mesh(icosphere_arrays(3));
  for(double ratio : {1e2, 1e4, 1e6})
    for(bool step : {true, false}) {
      const std::string kind = std::string(step ? "step" : "bump") + " 1e" + std::to_string(int(std::log10(ratio)));
      Face_map p = population(sphere, ratio, step);
      for(Method k : {Method::SDEM, Method::EDEM})
        check_most_uniform(sphere, p, std::string(name_of(k)) + " " + kind, sphere_flow(k, sphere, p));
      sphere.remove_property_map(p);
    }
  Mesh torus = to_mesh(torus_arrays(3, 1, 40, 20));
  for(double ratio : {1e2, 1e4, 1e6})
    for(bool step : {true, false}) {
      Face_map p = population(torus, ratio, step, 3);
      const std::string what = std::string("TDEM ") + (step ? "step" : "bump") + " 1e" + std::to_string(int(std::log10(ratio)));
      check_most_uniform(torus, p, what, [&](Point_map out, int iterations) {
        const auto np = PM::combine(PM::torus_radii(std::array<double, 2>{3, 1}), PM::face_population_map(p));
        if(iterations >= 0)
          return DEM::toroidal_density_equalizing_map(torus, out, PM::combine(np, PM::number_of_iterations(iterations)));
        return DEM::toroidal_density_equalizing_map(torus, out, np);
      }, false);
      torus.remove_property_map(p);
    }
}

// ---------------------------------------------------------------------------
// known failures (issue 14 items that do not hold yet)

void test_known_failures()
{
  // issue 14 item 2: SDEM, EDEM and TDEM converge on steps and bumps of ratio
  // 1e2..1e6, within 10x the time of a mild population (a bump of ratio 2) on
  // the same mesh. The sphere runs take seconds; TDEM's the longest (up to
  // minutes at 1000 iterations), so it gets the two hardest cases only.
  Mesh sphere = to_mesh(icosphere_arrays(3));
  for(Method k : {Method::SDEM, Method::EDEM}) {
    auto map = [&](Face_map p, Point_map out) {
      const auto np = PM::combine(PM::face_population_map(p), PM::ellipsoid_radii(std::array<double, 3>{1, 1, 1}));
      return k == Method::SDEM ? DEM::spherical_density_equalizing_map(sphere, out, np)
                               : DEM::ellipsoidal_density_equalizing_map(sphere, out, np);
    };
    Point_map out = fresh(sphere, "v:out");
    Face_map mild = population(sphere, 2, false);
    Stopwatch uniform_clock;
    map(mild, out);
    const double uniform = std::max(uniform_clock.seconds(), 0.05);
    sphere.remove_property_map(mild);
    for(double ratio : {1e2, 1e4, 1e6})
      for(bool step : {true, false}) {
        if(!step && ratio < 1e6) continue; // bumps 1e2 and 1e4 converge (long mode)
        Face_map p = population(sphere, ratio, step);
        const std::string what = std::string(name_of(k)) + (step ? " step" : " bump") + " 1e" +
                                 std::to_string(int(std::log10(ratio)));
        Stopwatch clock;
        const DEM::Map_report r = map(p, out);
        const double t = clock.seconds();
        check(r.converged(), what + " converges (" + DEM::to_string(r.termination) + ")");
        check(t <= 10 * uniform, what + ": time " + std::to_string(t) + " s within 10x of a mild population's (" +
                                   std::to_string(uniform) + " s)");
        sphere.remove_property_map(p);
      }
    sphere.remove_property_map(out);
  }
  Mesh torus = to_mesh(torus_arrays(3, 1, 40, 20));
  auto tdem = [&](Face_map p, Point_map out) {
    return DEM::toroidal_density_equalizing_map(
      torus, out, PM::combine(PM::torus_radii(std::array<double, 2>{3, 1}), PM::face_population_map(p)));
  };
  Point_map tout = fresh(torus, "v:out");
  Face_map mild = population(torus, 2, false, 3);
  Stopwatch uniform_clock;
  tdem(mild, tout);
  const double uniform = std::max(uniform_clock.seconds(), 0.05);
  torus.remove_property_map(mild);
  for(bool step : {true, false}) {
    Face_map p = population(torus, step ? 1e4 : 1e6, step, 3);
    const std::string what = step ? "TDEM step 1e4" : "TDEM bump 1e6";
    Stopwatch clock;
    const DEM::Map_report r = tdem(p, tout);
    const double t = clock.seconds();
    check(r.converged(), what + " converges (" + DEM::to_string(r.termination) + ")");
    check(t <= 10 * uniform, what + ": time " + std::to_string(t) + " s within 10x of a mild population's (" +
                               std::to_string(uniform) + " s)");
    torus.remove_property_map(p);
  }
  Mesh ms = to_mesh(with_slivers(bumpy_arrays(4, 0.15), 1e-4, 25));
  Point_map os = fresh(ms, "v:out");
  const DEM::Map_report r = DEM::spherical_density_equalizing_map(ms, os);
  check(r.converged(), std::string("SDEM on slivers converges (") + DEM::to_string(r.termination) + ")");
}

} // namespace

int main(int argc, char** argv)
{
  const std::string mode = argc > 1 ? argv[1] : "quick";
  Stopwatch clock;
  if(mode == "quick") {
    test_smallest_meshes();
    test_scale();
    test_sliver_conformal();
    test_honest_non_convergence();
    test_most_uniform_map();
    test_population_mobius_start();
    test_cli_honesty();
    test_elongated_starts();
  } else if(mode == "long") {
    test_capsules();
    test_extreme_populations();
  } else if(mode == "known") {
    test_known_failures();
  } else {
    std::cerr << "usage: test_hard_inputs [quick|long|known]\n";
    return 2;
  }
  std::cout << "test_hard_inputs " << mode << ": " << clock.seconds() << " s\n";
  return finish(("test_hard_inputs " + mode).c_str());
}
