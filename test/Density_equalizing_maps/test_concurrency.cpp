// The parallel loops (named parameter concurrency_tag): every method gives
// the same map to the last bit serially (CGAL::Sequential_tag, the default)
// and with CGAL::Parallel_tag on one thread or on two (TBB arenas), and the
// building blocks (block sums, first offending index) do not depend on the
// number of threads. Without TBB the parallel tag runs the serial loops and the
// comparisons hold trivially (the program says so).

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>
#include <CGAL/Density_equalizing_maps/internal/point_location.h>

#include "dem_test_meshes.h"

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/task_arena.h>
#endif

#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace PM = DEM::parameters;
namespace I = DEM::internal;
using namespace dem_test;

namespace {

// f() inside an arena of `threads` threads (0: the caller's own, serially).
void run_on(int threads, const std::function<void()>& f)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(threads > 0) {
    tbb::task_arena arena(threads);
    arena.execute(f);
    return;
  }
#endif
  (void)threads;
  f();
}

struct Run
{
  std::vector<double> coordinates; // x, y, z of every vertex
  DEM::Map_report report;
};

bool same_bits(const Run& a, const Run& b)
{
  return a.coordinates == b.coordinates && a.report.iterations == b.report.iterations &&
         a.report.fold_overs == b.report.fold_overs &&
         (a.report.final_error == b.report.final_error ||
          (std::isnan(a.report.final_error) && std::isnan(b.report.final_error)));
}

// `map(mesh, out, concurrency_np)` on a copy of m (a population is a
// property of it) serially, then with Parallel_tag on one and on two threads.
template <class Map>
void check_thread_independence(const std::string& name, const Mesh& m, const Map& map)
{
  auto run = [&](auto tag, int threads) {
    Run r;
    Mesh copy = m;
    auto out = copy.add_property_map<vertex_descriptor, Point>("v:out").first;
    run_on(threads, [&] { r.report = map(copy, out, PM::concurrency_tag(tag)); });
    for(vertex_descriptor v : copy.vertices())
      for(int c = 0; c < 3; ++c) r.coordinates.push_back(out[v][c]);
    return r;
  };
  const Run serial = run(CGAL::Sequential_tag(), 0);
  const Run one = run(CGAL::Parallel_tag(), 1);
  const Run two = run(CGAL::Parallel_tag(), 2);
  check(serial.report.fold_overs == 0, name + ": the map is bijective");
  check(same_bits(serial, one), name + ": Parallel_tag on one thread gives the serial map to the last bit");
  check(same_bits(serial, two), name + ": Parallel_tag on two threads gives the serial map to the last bit");
}

Mesh::Property_map<face_descriptor, double> bumpy_population(Mesh& m)
{
  auto pop = m.add_property_map<face_descriptor, double>("f:population").first;
  for(face_descriptor f : m.faces()) {
    const auto h = m.halfedge(f);
    const Point& p = m.point(m.source(h));
    const Point& q = m.point(m.target(h));
    const Point& r = m.point(m.target(m.next(h)));
    const Point c = CGAL::centroid(p, q, r);
    pop[f] = std::sqrt(CGAL::squared_area(p, q, r)) * (1 + 0.7 * std::sin(3 * c.x()) * std::cos(2 * c.z()));
  }
  return pop;
}

void test_building_blocks()
{
  const Eigen::Index n = 10 * I::parallel_block + 123;
  auto term = [](Eigen::Index i) { return 1. / double(i + 1) - 1e-3 * std::sin(double(i)); };
  auto first_negative = [n](Eigen::Index i) { return i == n - 5 || i == 7 * I::parallel_block + 3; };
  double sums[3];
  Eigen::Index firsts[3];
  for(int threads = 0; threads < 3; ++threads)
    run_on(threads, [&] {
      const I::Concurrency_scope scope(threads > 0);
      sums[threads] = I::parallel_sum(n, term);
      firsts[threads] = I::first_index_where(n, first_negative);
    });
  check(sums[0] == sums[1] && sums[0] == sums[2], "parallel_sum: the same bits on 0, 1 and 2 threads");
  check(firsts[0] == 7 * I::parallel_block + 3 && firsts[1] == firsts[0] && firsts[2] == firsts[0],
        "first_index_where: the least index, whoever finds it");
  {
    const I::Concurrency_scope outer(true);
    check(I::parallel_loops_requested() == I::parallel_loops_available(), "a parallel scope asks for parallel loops");
    {
      const I::Concurrency_scope inner(false);
      check(!I::parallel_loops_requested(), "a nested serial scope asks for serial loops");
    }
    check(I::parallel_loops_requested() == I::parallel_loops_available(), "the outer scope is restored");
    {
      const I::Concurrency_scope inherited = I::concurrency_scope_from_parameters(PM::default_values());
      check(I::parallel_loops_requested() == I::parallel_loops_available(),
            "a map called without concurrency_tag inside a parallel one keeps its loops");
    }
    {
      const I::Concurrency_scope serial =
        I::concurrency_scope_from_parameters(PM::concurrency_tag(CGAL::Sequential_tag()));
      check(!I::parallel_loops_requested(), "an explicit Sequential_tag gives serial loops");
    }
  }
  check(!I::parallel_loops_requested(), "serial loops outside every scope");
}

// interpolate_at_vertex_queries() walks in fixed blocks of the vertex order:
// on a jittered planar grid of more than two blocks of vertices, with a breadth-first
// order (walks from the parent's answer) and without parents (from the
// previous answer), an affine field is reproduced at every query inside the
// square, the queries outside get the outside map and are counted, and the
// result has the same bits on 0, 1 and 2 threads.
void test_planar_interpolation_in_blocks()
{
  const Arrays grid = planar_grid_arrays(121); // 14,641 vertices: four blocks
  const I::Matrix& P = grid.X;
  const I::Index_matrix& F = grid.F;
  const Eigen::Index n = P.rows();
  I::Matrix values(n, 2), queries(n, 2);
  for(Eigen::Index v = 0; v < n; ++v) {
    values.row(v) << 2 * P(v, 0) - 3 * P(v, 1) + 1, 0.5 * P(v, 0) + P(v, 1);
    // a smooth displacement of up to 0.03: some queries leave the unit square
    queries.row(v) << P(v, 0) + 0.03 * std::sin(7 * P(v, 1)), P(v, 1) + 0.03 * std::cos(5 * P(v, 0));
  }
  std::vector<Eigen::Index> order, parent;
  I::breadth_first_vertex_order(F, n, order, parent);
  const Eigen::Vector2d far_value(-7, -7);
  auto outside_map = [&](const Eigen::Vector2d&) { return far_value; };
  for(const bool with_parents : {true, false}) {
    const std::vector<Eigen::Index> no_parent;
    const std::vector<Eigen::Index>& parents = with_parents ? parent : no_parent;
    I::Matrix out[3];
    std::size_t outside[3];
    for(int threads = 0; threads < 3; ++threads)
      run_on(threads, [&] {
        const I::Concurrency_scope scope(threads > 0);
        const I::Planar_point_locator locator(P, F);
        out[threads] = I::interpolate_at_vertex_queries(locator, values, queries, order, parents, outside_map,
                                                         &outside[threads]);
      });
    const std::string what = with_parents ? " (walks from the parent)" : " (walks from the previous answer)";
    std::size_t expected_outside = 0;
    double error = 0;
    bool outside_rows_right = true;
    for(Eigen::Index v = 0; v < n; ++v) {
      const double x = queries(v, 0), y = queries(v, 1);
      if(x < 0 || x > 1 || y < 0 || y > 1) {
        ++expected_outside;
        outside_rows_right = outside_rows_right && out[0].row(v) == far_value.transpose();
        continue;
      }
      error = std::max(error, std::abs(out[0](v, 0) - (2 * x - 3 * y + 1)));
      error = std::max(error, std::abs(out[0](v, 1) - (0.5 * x + y)));
    }
    check(expected_outside > 0 && outside[0] == expected_outside && outside_rows_right,
          "interpolate_at_vertex_queries: the queries outside the domain get the outside map and are counted" + what);
    check(error < 1e-12, "interpolate_at_vertex_queries: an affine field is reproduced inside the domain" + what +
                           " (max error " + std::to_string(error) + ")");
    check(out[1] == out[0] && out[2] == out[0] && outside[1] == outside[0] && outside[2] == outside[0],
          "interpolate_at_vertex_queries: the same bits on 0, 1 and 2 threads" + what);
    if(!with_parents) { // the same walks on the queries gathered in walk order
      I::Matrix Q(n, 2);
      for(Eigen::Index p = 0; p < n; ++p) Q.row(p) = queries.row(order[p]);
      I::Matrix at_points;
      run_on(2, [&] {
        const I::Concurrency_scope scope(true);
        const I::Planar_point_locator locator(P, F);
        at_points = I::interpolate_at_points(locator, values, Q, [&](Eigen::Index p) { return order[p]; },
                                             outside_map);
      });
      bool same = true;
      for(Eigen::Index p = 0; p < n; ++p) same = same && at_points.row(p) == out[0].row(order[p]);
      check(same, "interpolate_at_points: the values of the per-vertex walks, row by row");
    }
  }
}

} // namespace

int main()
{
  if(!I::parallel_loops_available())
    std::cout << "built without TBB: Parallel_tag runs the serial loops" << std::endl;
  test_building_blocks();
  test_planar_interpolation_in_blocks();

  // 20,480 faces: five blocks of the face loops, more than one of the vertex loops
  const Mesh sphere = bumpy(5);
  check_thread_independence("spherical conformal map with Moebius correction", sphere,
                            [](Mesh& m, auto out, const auto& np) {
                              return DEM::spherical_conformal_map(
                                m, out, PM::combine(PM::mobius_area_correction(true), np));
                            });
  check_thread_independence("ellipsoidal conformal map, optimized radii", sphere,
                            [](Mesh& m, auto out, const auto& np) {
                              return DEM::ellipsoidal_conformal_map(m, out,
                                                                    PM::combine(PM::optimize_radii(true), np));
                            });
  check_thread_independence("SDEM with a population", sphere, [](Mesh& m, auto out, const auto& np) {
    return DEM::spherical_density_equalizing_map(m, out,
                                                 PM::combine(PM::face_population_map(bumpy_population(m)), np));
  });
  check_thread_independence("EDEM with a population", sphere, [](Mesh& m, auto out, const auto& np) {
    return DEM::ellipsoidal_density_equalizing_map(
      m, out, PM::combine(PM::ellipsoid_radii(std::array<double, 3>{1.2, 1, 0.8}),
                          PM::face_population_map(bumpy_population(m)), np));
  });
  const Mesh ring = torus(3, 1, 128, 64); // 16,384 faces
  check_thread_independence("TDEM with a population", ring, [](Mesh& m, auto out, const auto& np) {
    return DEM::toroidal_density_equalizing_map(
      m, out, PM::combine(PM::torus_radii(std::array<double, 2>{3, 1}),
                          PM::face_population_map(bumpy_population(m)), np));
  });
  return finish("test_concurrency");
}
