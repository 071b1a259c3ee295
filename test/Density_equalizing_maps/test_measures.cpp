// The public measures (measures.h) on maps whose values are known in closed
// form: exact fold-over counts, |mu| of affine maps, log area ratios,
// density variances and the distortion summary.

#include <CGAL/Density_equalizing_maps/measures.h>

#include <CGAL/Simple_cartesian.h>

#include "dem_test_meshes.h"

namespace DEM = CGAL::Density_equalizing_maps;
namespace params = CGAL::Density_equalizing_maps::parameters;
using namespace dem_test;

namespace {

typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_map;

template <class F>
Point_map mapped(Mesh& m, const std::string& name, F f)
{
  Point_map p = m.add_property_map<vertex_descriptor, Point>(name).first;
  for(auto v : m.vertices()) p[v] = f(m.point(v));
  return p;
}

std::size_t valence(const Mesh& m, vertex_descriptor v) { return m.degree(v); }

std::pair<double, double> mean_sd(const std::vector<double>& x)
{
  double mean = 0;
  for(double v : x) mean += v;
  mean /= double(x.size());
  double ss = 0;
  for(double v : x) ss += (v - mean) * (v - mean);
  return {mean, std::sqrt(ss / double(x.size() - 1))};
}

// variance (N - 1) of x / mean(x), straight from the definition
double normalized_variance(const std::vector<double>& x)
{
  const auto ms = mean_sd(x);
  return (ms.second / ms.first) * (ms.second / ms.first);
}

void test_fold_overs()
{
  Mesh m = icosphere(2);
  const std::size_t nf = m.number_of_faces();
  const Point_map id = mapped(m, "v:id", [](const Point& p) { return p; });
  check(DEM::number_of_fold_overs(m, id) == 0, "identity of an outward icosphere: 0 fold-overs");
  const Point_map mirror = mapped(m, "v:mirror", [](const Point& p) { return Point(-p.x(), p.y(), p.z()); });
  check(DEM::number_of_fold_overs(m, mirror) == nf, "mirror image: every face folded");

  // one vertex sent to its antipode: exactly its incident faces are inverted
  const vertex_descriptor v0 = *std::next(m.vertices().begin(), 17);
  Point_map one = mapped(m, "v:one", [](const Point& p) { return p; });
  one[v0] = Point(-one[v0].x(), -one[v0].y(), -one[v0].z());
  check(DEM::number_of_fold_overs(m, one) == valence(m, v0), "antipodal vertex: its " +
                                                                 std::to_string(valence(m, v0)) + " faces folded");
  // a non-finite image counts as folded
  Point_map nan = mapped(m, "v:nan", [](const Point& p) { return p; });
  nan[v0] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  check(DEM::number_of_fold_overs(m, nan) == valence(m, v0), "non-finite vertex: its faces counted as folded");
  // a degenerate image face (vertex at the center) is folded
  Point_map center = mapped(m, "v:center", [](const Point& p) { return p; });
  center[v0] = Point(0, 0, 0);
  check(DEM::number_of_fold_overs(m, center) == valence(m, v0), "vertex at the center: its faces folded");

  // the `center` parameter: a sphere translated far away
  const Point c(5, -1, 2);
  const Point_map moved = mapped(m, "v:moved", [&](const Point& p) { return p + (c - CGAL::ORIGIN); });
  check(DEM::number_of_fold_overs(m, moved, params::center(c)) == 0, "translated sphere about its center: 0");
  const std::size_t about_origin = DEM::number_of_fold_overs(m, moved);
  check(about_origin > 0 && about_origin < nf, "translated sphere about the origin: some faces seen inverted");

  // an inward-oriented input: the count is relative to the input's orientation
  Arrays a = icosphere_arrays(2);
  flip_faces(a);
  Mesh inward = to_mesh(a);
  const Point_map id2 = mapped(inward, "v:id", [](const Point& p) { return p; });
  check(DEM::number_of_fold_overs(inward, id2) == 0, "identity of an inward-oriented mesh: 0 fold-overs");
  const Point_map mirror2 = mapped(inward, "v:mirror", [](const Point& p) { return Point(-p.x(), p.y(), p.z()); });
  check(DEM::number_of_fold_overs(inward, mirror2) == nf, "mirror of an inward-oriented mesh: every face folded");

  // another point type and an ellipsoid image
  typedef CGAL::Simple_cartesian<double>::Point_3 Other_point;
  auto other = m.add_property_map<vertex_descriptor, Other_point>("v:other").first;
  for(auto v : m.vertices()) other[v] = Other_point(m.point(v).x(), 2 * m.point(v).y(), 0.5 * m.point(v).z());
  check(DEM::number_of_fold_overs(m, other) == 0, "ellipsoid image with another point type: 0 fold-overs");
}

void test_planar_fold_overs()
{
  Arrays g = planar_grid_arrays(9, 0.3, 4, 3);
  Mesh m = to_mesh(g);
  auto uv = m.add_property_map<vertex_descriptor, Point_2>("v:uv").first;
  for(auto v : m.vertices()) uv[v] = Point_2(m.point(v).x(), m.point(v).y());
  check(DEM::number_of_planar_fold_overs(m, uv) == 0, "planar identity: 0 fold-overs");
  for(auto v : m.vertices()) uv[v] = Point_2(-m.point(v).x(), m.point(v).y());
  check(DEM::number_of_planar_fold_overs(m, uv) == m.number_of_faces(), "planar mirror: every face folded");
  for(auto v : m.vertices()) uv[v] = Point_2(m.point(v).x(), m.point(v).y());
  const vertex_descriptor v0(4 * 9 + 4); // interior vertex
  uv[v0] = Point_2(std::numeric_limits<double>::infinity(), 0);
  check(DEM::number_of_planar_fold_overs(m, uv) == valence(m, v0), "planar non-finite vertex: its faces folded");
  // a vertex pushed across an edge of its ring: exactly the faces that flip are counted
  uv[v0] = Point_2(m.point(v0).x(), m.point(v0).y());
  uv[v0] = Point_2(uv[v0].x() + 0.4, uv[v0].y() + 0.4);
  std::size_t expected = 0;
  for(auto f : m.faces()) {
    std::vector<Point_2> q;
    for(auto v : vertices_around_face(m.halfedge(f), m)) q.push_back(uv[v]);
    expected += CGAL::orientation(q[0], q[1], q[2]) != CGAL::LEFT_TURN;
  }
  const std::size_t n = DEM::number_of_planar_fold_overs(m, uv);
  check(n == expected && n > 0, "planar vertex pushed out of its ring: " + std::to_string(n) + " folds");
}

void test_beltrami_and_area()
{
  Arrays g = planar_grid_arrays(10, 0.3, 8, 3);
  Mesh m = to_mesh(g);
  Face_map mu = m.add_property_map<face_descriptor, double>("f:mu", -1).first;
  Face_map darea = m.add_property_map<face_descriptor, double>("f:darea", -1).first;

  // a similarity in 3D (rotation, scale, translation): conformal, area-preserving up to scale
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Point_map sim = mapped(m, "v:sim", [&](const Point& p) {
    const Eigen::Vector3d q = 2.5 * R * Eigen::Vector3d(p.x(), p.y(), p.z()) + Eigen::Vector3d(1, 2, 3);
    return Point(q.x(), q.y(), q.z());
  });
  DEM::beltrami_coefficient_magnitudes(m, sim, mu);
  DEM::log_area_ratios(m, sim, darea);
  double max_mu = 0, max_darea = 0;
  for(auto f : m.faces()) { max_mu = std::max(max_mu, mu[f]); max_darea = std::max(max_darea, std::abs(darea[f])); }
  check(max_mu <= 1e-12, "similarity: |mu| = 0 on every face");
  check(max_darea <= 1e-12, "similarity: d_area = 0 on every face");

  // stretch by (2, 1): |mu| = (2 - 1) / (2 + 1) everywhere, areas uniformly doubled
  const Point_map stretch = mapped(m, "v:stretch", [](const Point& p) { return Point(2 * p.x(), p.y(), p.z()); });
  DEM::beltrami_coefficient_magnitudes(m, stretch, mu);
  DEM::log_area_ratios(m, stretch, darea);
  double err_mu = 0;
  max_darea = 0;
  for(auto f : m.faces()) { err_mu = std::max(err_mu, std::abs(mu[f] - 1. / 3)); max_darea = std::max(max_darea, std::abs(darea[f])); }
  check(err_mu <= 1e-12, "stretch (2,1): |mu| = 1/3 on every face");
  check(max_darea <= 1e-12, "stretch (2,1): d_area = 0 on every face");
  // a 2D point map is read with z = 0
  auto uv = m.add_property_map<vertex_descriptor, Point_2>("v:uv").first;
  for(auto v : m.vertices()) uv[v] = Point_2(2 * m.point(v).x(), m.point(v).y());
  DEM::beltrami_coefficient_magnitudes(m, uv, mu);
  err_mu = 0;
  for(auto f : m.faces()) err_mu = std::max(err_mu, std::abs(mu[f] - 1. / 3));
  check(err_mu <= 1e-12, "2D image map: |mu| = 1/3 on every face");

  // an arbitrary smooth map: sum_T (|T| / sum |T|) exp(d_T) = 1 by definition,
  // and map_distortion summarizes the per-face values
  const Point_map wavy = mapped(m, "v:wavy", [](const Point& p) {
    return Point(p.x() + 0.1 * std::sin(3 * p.y()), p.y() + 0.05 * p.x() * p.x(), 0.2 * p.x() * p.y());
  });
  DEM::log_area_ratios(m, wavy, darea);
  DEM::beltrami_coefficient_magnitudes(m, wavy, mu);
  const Vector area = DEM::internal::face_areas(g.X, g.F);
  double s = 0;
  std::vector<double> abs_mu, abs_darea;
  for(auto f : m.faces()) {
    s += area[f.idx()] / area.sum() * std::exp(darea[f]);
    abs_mu.push_back(mu[f]);
    abs_darea.push_back(std::abs(darea[f]));
  }
  check_close(s, 1., 1e-12, "sum of normalized input area times exp(d_area) is 1");
  const DEM::Distortion_statistics d = DEM::map_distortion(m, wavy);
  const auto ms_mu = mean_sd(abs_mu), ms_da = mean_sd(abs_darea);
  check_close(d.mean_abs_mu, ms_mu.first, 1e-14, "map_distortion mean |mu|");
  check_close(d.sd_abs_mu, ms_mu.second, 1e-14, "map_distortion sd |mu|");
  check_close(d.mean_abs_darea, ms_da.first, 1e-14, "map_distortion mean |d_area|");
  check_close(d.sd_abs_darea, ms_da.second, 1e-14, "map_distortion sd |d_area|");
  check(d.mean_abs_mu > 0.01 && d.mean_abs_darea > 0.01, "the wavy map is distorted");

  // vertex_point_map: measured from the wavy positions to themselves, nothing is distorted
  const DEM::Distortion_statistics d0 = DEM::map_distortion(m, wavy, CGAL::parameters::vertex_point_map(wavy));
  check(d0.mean_abs_mu <= 1e-12 && d0.mean_abs_darea <= 1e-12, "vertex_point_map is the input of the measure");
}

void test_density_variance()
{
  Mesh m = icosphere(2);
  const Point_map id = mapped(m, "v:id", [](const Point& p) { return p; });
  const Point_map big = mapped(m, "v:big", [](const Point& p) { return Point(3 * p.x(), 3 * p.y(), 3 * p.z()); });
  DEM::Density_variance v = DEM::density_variance(m, id);
  check(v.face <= 1e-28 && v.vertex <= 1e-28, "identity, population = area: both variances 0");
  v = DEM::density_variance(m, big);
  check(v.face <= 1e-28 && v.vertex <= 1e-28, "scaled map, population = area: both variances 0");

  // population twice the area on every other face: face densities 1 and 2 on the identity map
  const Arrays a = from_mesh(m);
  const Vector area = DEM::internal::face_areas(a.X, a.F);
  Face_map pop = m.add_property_map<face_descriptor, double>("f:pop").first;
  std::vector<double> rho_f;
  for(auto f : m.faces()) {
    pop[f] = area[f.idx()] * (f.idx() % 2 ? 2. : 1.);
    rho_f.push_back(f.idx() % 2 ? 2. : 1.);
  }
  v = DEM::density_variance(m, id, params::face_population_map(pop));
  check_close(v.face, normalized_variance(rho_f), 1e-14, "face density variance from the definition");
  // vertex density: area-weighted average of the incident face densities
  std::vector<double> rho_v;
  for(auto u : m.vertices()) {
    double num = 0, den = 0;
    for(auto f : faces_around_target(m.halfedge(u), m)) { num += area[f.idx()] * rho_f[f.idx()]; den += area[f.idx()]; }
    rho_v.push_back(num / den);
  }
  check_close(v.vertex, normalized_variance(rho_v), 1e-14, "vertex density variance from the definition");
  check(v.vertex < v.face, "averaging lowers the variance");

  // a constant vertex density is the area-preserving population
  auto dens = m.add_property_map<vertex_descriptor, double>("v:dens", 4.).first;
  v = DEM::density_variance(m, id, params::vertex_density_map(dens));
  check(v.face <= 1e-28 && v.vertex <= 1e-28, "constant vertex density: variances 0");

  // invalid populations are rejected
  pop[*m.faces().begin()] = -1;
  const std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DEM::density_variance(m, id, params::face_population_map(pop)); }, "negative population");
  check(contains(msg, "face 0"), "negative population message names the face: " + msg);
}

void test_bad_input()
{
  Mesh q = quad_cube();
  const Point_map id = mapped(q, "v:id", [](const Point& p) { return p; });
  Face_map f = q.add_property_map<face_descriptor, double>("f:x").first;
  const std::string what = "not a pure triangle mesh";
  check(contains(expect_throw<DEM::Invalid_input>([&] { DEM::number_of_fold_overs(q, id); }, "quad fold"), what),
        "number_of_fold_overs rejects quads");
  check(contains(expect_throw<DEM::Invalid_input>([&] { DEM::map_distortion(q, id); }, "quad distortion"), what),
        "map_distortion rejects quads");
  check(contains(expect_throw<DEM::Invalid_input>([&] { DEM::log_area_ratios(q, id, f); }, "quad darea"), what),
        "log_area_ratios rejects quads");
  check(contains(expect_throw<DEM::Invalid_input>([&] { DEM::density_variance(q, id); }, "quad density"), what),
        "density_variance rejects quads");
}

} // namespace

int main()
{
  Stopwatch clock;
  test_fold_overs();
  test_planar_fold_overs();
  test_beltrami_and_area();
  test_density_variance();
  test_bad_input();
  std::cout << "time " << clock.seconds() << " s" << std::endl;
  return finish("test_measures");
}
