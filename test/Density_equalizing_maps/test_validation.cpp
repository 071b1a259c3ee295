// Bad input: every validation error throws Invalid_input with a message that
// names the problem, and nothing is written to the output map. Thin slivers
// are valid input and map without fold-over.

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include "dem_test_meshes.h"

namespace DEM = CGAL::Density_equalizing_maps;
using namespace dem_test;

namespace {

const Point sentinel(7, -7, 7);

// Runs spherical_conformal_map on a bad mesh: it must throw Invalid_input whose
// message contains `expected`, and leave the sentinel-filled output untouched.
void expect_rejected(Mesh m, const std::string& expected, const std::string& name)
{
  Mesh::Property_map<vertex_descriptor, Point> out =
    m.add_property_map<vertex_descriptor, Point>("v:dem_test_out", sentinel).first;
  for(auto v : m.vertices()) out[v] = sentinel;
  const std::string msg = expect_throw<DEM::Invalid_input>([&] { DEM::spherical_conformal_map(m, out); }, name);
  std::cout << name << ": \"" << msg << "\"" << std::endl;
  check(contains(msg, expected), name + ": message \"" + msg + "\" lacks \"" + expected + "\"");
  bool untouched = true;
  for(auto v : m.vertices()) untouched = untouched && out[v] == sentinel;
  check(untouched, name + ": the output map was written");
}

void expect_rejected_arrays(const Arrays& a, long euler, const std::string& expected, const std::string& name)
{
  const std::string msg =
    expect_throw<DEM::Invalid_input>([&] { DEM::internal::validate_closed_surface(a.X, a.F, euler, 4); }, name);
  std::cout << name << ": \"" << msg << "\"" << std::endl;
  check(contains(msg, expected), name + ": message \"" + msg + "\" lacks \"" + expected + "\"");
}

} // namespace

int main()
{
  Stopwatch clock;

  // the generators themselves are valid where they should be
  check(DEM::internal::validate_closed_surface(icosphere_arrays(2).X, icosphere_arrays(2).F, 2, 4).edges == 480,
        "icosphere(2) is a valid sphere with 480 edges");
  {
    const Arrays t = torus_arrays(3, 1, 24, 12);
    check(DEM::internal::validate_closed_surface(t.X, t.F, 0, 7).genus() == 1, "torus generator has genus 1");
    const Arrays d = double_torus_arrays();
    check(DEM::internal::validate_closed_surface(d.X, d.F, -2, 7).genus() == 2, "double torus generator has genus 2");
  }

  // --- through the public function (Surface_mesh)
  expect_rejected(quad_cube(), "not a pure triangle mesh", "quad mesh");
  expect_rejected(open_icosphere(), "open boundary", "open mesh");
  expect_rejected(pinched_tetrahedra(), "non-manifold", "non-manifold vertex");
  expect_rejected(torus(3, 1, 24, 12), "Euler characteristic", "torus (genus 1)");
  expect_rejected(torus(3, 1, 24, 12), "genus 1", "torus (genus 1) names the genus");
  expect_rejected(to_mesh(double_torus_arrays()), "genus 2", "double torus (genus 2)");
  expect_rejected(octahedron_with_collinear_face(), "degenerate", "collinear face");
  expect_rejected(icosphere_with_nan(), "non-finite", "NaN coordinate");
  expect_rejected(two_sided_triangle(), "too few vertices", "3 vertices");
  expect_rejected(two_tetrahedra(), "not connected", "two tetrahedra");
  expect_rejected(icosphere_with_isolated_vertex(), "isolated vertex", "isolated vertex");
  {
    Arrays a = icosphere_arrays(1);
    a.X(5, 2) = std::numeric_limits<double>::infinity();
    expect_rejected(to_mesh(a), "non-finite", "infinite coordinate");
  }

  // a Surface_mesh with a removed vertex and no collect_garbage(): its built-in
  // index map has a hole, which must be reported, not written through
  {
    Mesh m;
    const vertex_descriptor extra = m.add_vertex(Point(5, 5, 5));
    const Arrays a = icosphere_arrays(1);
    std::vector<vertex_descriptor> v;
    for(Eigen::Index i = 0; i < a.X.rows(); ++i) v.push_back(m.add_vertex(Point(a.X(i, 0), a.X(i, 1), a.X(i, 2))));
    for(Eigen::Index k = 0; k < a.F.rows(); ++k) m.add_face(v[a.F(k, 0)], v[a.F(k, 1)], v[a.F(k, 2)]);
    m.remove_vertex(extra);
    check(m.has_garbage(), "mesh with garbage built");
    expect_rejected(m, "collect_garbage", "Surface_mesh with garbage");
    m.collect_garbage();
    auto out = m.add_property_map<vertex_descriptor, Point>("v:s").first;
    check(DEM::spherical_conformal_map(m, out).fold_overs == 0, "after collect_garbage() the mesh maps");
  }

  // no faces at all: ten vertices, and nothing
  {
    Mesh m;
    for(int i = 0; i < 10; ++i) m.add_vertex(Point(i, i * i, 0.5 * i));
    expect_rejected(m, "no faces", "mesh with no faces");
    expect_rejected(Mesh(), "too few vertices", "empty mesh");
  }

  // a user vertex_index_map that does not number the vertices 0..n-1
  {
    Mesh m = icosphere(1);
    auto index = m.add_property_map<vertex_descriptor, std::size_t>("v:bad_index", 0).first;
    std::size_t i = 0;
    for(vertex_descriptor v : vertices(m)) index[v] = i++;
    index[vertex_descriptor(7)] = 3; // index 3 twice, 7 missing
    auto out = m.add_property_map<vertex_descriptor, Point>("v:out", sentinel).first;
    std::string msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::spherical_conformal_map(m, out, CGAL::parameters::vertex_index_map(index)); }, "duplicate index");
    std::cout << "vertex_index_map with a duplicate index: \"" << msg << "\"" << std::endl;
    check(contains(msg, "vertex index map") && contains(msg, "index 3"),
          "vertex_index_map with a duplicate index: message names the map and the index (" + msg + ")");
    index[vertex_descriptor(7)] = 1000;
    msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::spherical_conformal_map(m, out, CGAL::parameters::vertex_index_map(index)); }, "index out of range");
    check(contains(msg, "vertex index map") && contains(msg, "index 1000"),
          "vertex_index_map out of range: message names the map and the index (" + msg + ")");
    msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::number_of_fold_overs(m, m.points(), CGAL::parameters::vertex_index_map(index)); },
      "measures: index out of range");
    check(contains(msg, "vertex index map"), "number_of_fold_overs with a bad vertex_index_map: rejected (" + msg + ")");
    bool untouched = true;
    for(auto v : m.vertices()) untouched = untouched && out[v] == sentinel;
    check(untouched, "bad vertex_index_map: nothing written");
    // a valid user numbering (reversed) gives the same map as the built-in one
    i = m.number_of_vertices();
    for(vertex_descriptor v : vertices(m)) index[v] = --i;
    auto a = m.add_property_map<vertex_descriptor, Point>("v:a").first;
    DEM::spherical_conformal_map(m, a, CGAL::parameters::vertex_index_map(index));
    check(DEM::number_of_fold_overs(m, a) == 0, "a reversed vertex_index_map maps without fold-over");
  }

  // the same through mobius_area_correction (it validates the mesh too)
  {
    const Mesh m = open_icosphere();
    auto in = get(CGAL::vertex_point, m);
    Mesh copy = m;
    auto out = copy.add_property_map<vertex_descriptor, Point>("v:out", sentinel).first;
    const std::string msg = expect_throw<DEM::Invalid_input>(
      [&] { DEM::mobius_area_correction(m, in, out); }, "mobius_area_correction on an open mesh");
    check(contains(msg, "open boundary"), "mobius_area_correction names the open boundary: " + msg);
  }

  // --- arrays only: cases a halfedge structure cannot hold
  expect_rejected_arrays(non_manifold_edge_arrays(), 2, "non-manifold edge", "non-manifold edge");
  {
    Arrays a = icosphere_arrays(1);
    std::swap(a.F(3, 1), a.F(3, 2));
    expect_rejected_arrays(a, 2, "inconsistent face orientation", "one face flipped");
  }
  {
    Arrays a = icosphere_arrays(1);
    a.F(2, 1) = a.F(2, 0);
    expect_rejected_arrays(a, 2, "degenerate", "face with a repeated vertex");
  }
  {
    Arrays a = icosphere_arrays(1);
    a.F(0, 2) = int(a.X.rows()) + 3;
    expect_rejected_arrays(a, 2, "out of range", "vertex index out of range");
  }
  expect_rejected_arrays(torus_arrays(3, 1, 24, 12), 2, "Euler characteristic", "torus as arrays");
  expect_rejected_arrays(double_torus_arrays(), 0, "genus 2", "double torus for a genus-1 method");
  expect_rejected_arrays(icosphere_arrays(1), 0, "genus 0", "sphere for a genus-1 method");

  // --- population validation
  {
    const std::string msg = expect_throw<DEM::Invalid_input>(
      [] { DEM::internal::validate_population(Vector::Constant(5, 1.), 6); }, "short population");
    check(contains(msg, "5 values") && contains(msg, "6 faces"), "short population message: " + msg);
    Vector p = Vector::Constant(6, 1.);
    p[4] = -1;
    const std::string msg2 =
      expect_throw<DEM::Invalid_input>([&] { DEM::internal::validate_population(p, 6); }, "negative population");
    check(contains(msg2, "non-positive") && contains(msg2, "face 4"), "negative population message: " + msg2);
  }

  // --- thin slivers are valid input.
  // Needles: a vertex of an icosphere moved to within `t` of its edge length of a
  // neighbour (inside its convex 1-ring, so the surface stays embedded): the
  // incident faces have ~t of the mean area and the map has no fold-over.
  for(double t : {1e-4, 1e-6}) {
    Arrays a = icosphere_arrays(3);
    const int v = a.F(0, 0), p = a.F(0, 1);
    a.X.row(v) = a.X.row(p) + t * (a.X.row(v) - a.X.row(p));
    const Vector area = DEM::internal::face_areas(a.X, a.F);
    const double ratio = area.minCoeff() / area.mean();
    const std::string name = "needle sliver (min area / mean " + std::to_string(ratio) + ")";
    check(ratio < 2 * t && ratio > t / 20, name + " is thin");
    Mesh m = to_mesh(a);
    auto out = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
    try {
      const DEM::Map_report r = DEM::spherical_conformal_map(m, out);
      check(r.fold_overs == 0, name + ": maps without fold-over (report: " + std::to_string(r.fold_overs) + ")");
      check(DEM::number_of_fold_overs(m, out) == 0, name + ": 0 fold-overs by the measure");
    } catch(const std::exception& e) {
      check(false, name + " rejected: " + e.what());
    }
  }
  // Caps: a vertex moved almost onto the opposite edge (angle near 180 degrees).
  // Valid input too. The cotangent weight of that edge is then hugely negative
  // and the image's orientation is decided by second-order terms, so a cap
  // thinner than ~1e-2 may fold in FLASH's harmonic step (it does at 1e-4 on
  // icosphere(3)); the output must be bijective all the same.
  for(double t : {1e-2, 1e-4}) {
    Arrays a = icosphere_arrays(3);
    const int v = a.F(0, 0), p = a.F(0, 1), q = a.F(0, 2);
    const Eigen::RowVector3d mid = 0.5 * (a.X.row(p) + a.X.row(q));
    a.X.row(v) = mid + t * (a.X.row(v) - mid);
    const Vector area = DEM::internal::face_areas(a.X, a.F);
    const std::string name = "cap sliver (area / mean " + std::to_string(area[0] / area.mean()) + ")";
    Mesh m = to_mesh(a);
    auto out = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
    try {
      const DEM::Map_report r = DEM::spherical_conformal_map(m, out);
      const std::size_t n = DEM::number_of_fold_overs(m, out);
      std::cout << name << ": " << n << " fold-over(s)" << std::endl;
      check(r.fold_overs == n, name + ": the report gives the exact fold-over count");
      check(n == 0, name + ": no fold-over (a folded FLASH map is repaired from the Tutte embedding)");
    } catch(const std::exception& e) {
      check(false, name + " rejected: " + e.what());
    }
    a.X.row(v) = mid + 1e-10 * (a.X.row(v) - mid) / t; // still not collinear
    check(DEM::internal::validate_closed_surface(a.X, a.F, 2, 4).euler_characteristic == 2,
          "a 1e-10 cap is valid input");
  }

  std::cout << "time " << clock.seconds() << " s" << std::endl;
  return finish("test_validation");
}
