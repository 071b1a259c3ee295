// Honest failures (issue 15): the caller's mistakes throw Invalid_input, the
// methods' own numerical failures throw Algorithm_failure (a different type,
// not a subclass), and neither writes to the output map. Also the API gaps:
// duplicate landmark vertices, radii out of the sane range, solver clones
// that keep the user's settings, and mobius_area_correction's input checks.
// Generated meshes only.

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Eigen_vector.h>

#include <Eigen/IterativeLinearSolvers>

#include "dem_test_meshes.h"

#include <array>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace DEM = CGAL::Density_equalizing_maps;
namespace PM = DEM::parameters;
namespace I = DEM::internal;
using namespace dem_test;

typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef std::vector<std::pair<vertex_descriptor, Point> > Landmarks;

static_assert(!std::is_base_of<DEM::Invalid_input, DEM::Algorithm_failure>::value,
              "an algorithm failure is not the caller's fault");
static_assert(!std::is_base_of<DEM::Algorithm_failure, DEM::Invalid_input>::value, "distinct types");

namespace {

/// A model of SparseLinearAlgebraWithFactorTraits_d whose every factorization
/// and solve fails: on valid input, a method that depends on a linear solve
/// can then only fail by its own fault.
struct Failing_solver_traits
{
  typedef double NT;
  typedef CGAL::Eigen_sparse_matrix<double> Matrix;
  typedef CGAL::Eigen_vector<double> Vector;
  bool factor(const Matrix&, NT&) { return false; }
  bool linear_solver(const Vector&, Vector&) { return false; }
  bool linear_solver(const Matrix&, const Vector&, Vector&, NT&) { return false; }
};

/// A generic traits model with a setting of its own (as a user's solver would
/// have a tolerance), to check that the adapter's clones keep it.
struct Configured_traits
{
  typedef double NT;
  typedef CGAL::Eigen_sparse_matrix<double> Matrix;
  typedef CGAL::Eigen_vector<double> Vector;
  double tolerance = 1e-10;
  bool factor(const Matrix&, NT&) { return true; }
  bool linear_solver(const Vector& b, Vector& x)
  {
    for(int i = 0; i < int(b.size()); ++i) x.set(i, b(i));
    return true;
  }
};

template <class E, class F>
std::string expect_nothing_written(Mesh& m, Point_map out, F f, const std::string& name)
{
  const std::string msg = expect_throw<E>(f, name);
  std::cout << name << ": \"" << msg << "\"" << std::endl;
  check(untouched(m, out), name + ": the output map was written");
  return msg;
}

void algorithm_failures_are_not_invalid_input()
{
  Mesh m = bumpy(2);
  Point_map out = output_map(m, "v:out");
  const auto failing = PM::sparse_linear_solver(Failing_solver_traits());
  std::string msg = expect_nothing_written<DEM::Algorithm_failure>(
    m, out, [&] { DEM::spherical_conformal_map(m, out, failing); }, "spherical conformal, failing solver");
  check(contains(msg, "spherical conformal map failed"), "FLASH failure: the message says what failed");

  msg = expect_nothing_written<DEM::Algorithm_failure>(
    m, out, [&] { DEM::spherical_density_equalizing_map(m, out, failing); }, "SDEM, failing solver");
  check(!msg.empty(), "SDEM: the computed initial map failed -> Algorithm_failure");

  msg = expect_nothing_written<DEM::Algorithm_failure>(
    m, out, [&] { DEM::ellipsoidal_conformal_map(m, out, failing); }, "FECM, failing solver");
  check(!msg.empty(), "FECM: Algorithm_failure");

  msg = expect_nothing_written<DEM::Algorithm_failure>(
    m, out,
    [&] {
      DEM::ellipsoidal_density_equalizing_map(
        m, out, PM::combine(failing, PM::ellipsoid_radii(std::array<double, 3>{1, 1, 1.5})));
    },
    "EDEM, failing solver");
  check(!msg.empty(), "EDEM: Algorithm_failure");

  Landmarks lm = {{vertex_descriptor(0), Point(1, 0, 0)}};
  msg = expect_nothing_written<DEM::Algorithm_failure>(
    m, out, [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out, failing); },
    "LSDEM, failing solver");
  check(contains(msg, "could not be factored"), "LSDEM: the message says the harmonic system failed");

  Mesh t = torus(3, 1, 24, 10);
  Point_map tout = output_map(t, "v:out");
  msg = expect_nothing_written<DEM::Algorithm_failure>(
    t, tout,
    [&] {
      DEM::toroidal_parameterization(t, tout, PM::combine(failing, PM::torus_radii(std::array<double, 2>{3, 1})));
    },
    "toroidal parameterization, failing solver");
  check(contains(msg, "periodic harmonic map"), "toroidal parameterization: the message says what failed");

  // The same methods with the default solver succeed on the same meshes:
  // the failure above is the solver's, not the input's.
  const DEM::Map_report r = DEM::spherical_conformal_map(m, out);
  check(r.fold_overs == 0, "spherical conformal with the default solver: 0 fold-overs");
}

void user_initial_map_is_the_callers_fault()
{
  Mesh m = icosphere(2);
  Point_map init = m.add_property_map<vertex_descriptor, Point>("v:init").first;
  for(vertex_descriptor v : vertices(m)) { const Point& p = m.point(v); init[v] = Point(p.x(), -p.y(), p.z()); }
  Point_map out = output_map(m, "v:out");
  const std::string msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::spherical_density_equalizing_map(m, out, PM::initial_map(init)); }, "SDEM mirrored initial map");
  check(contains(msg, "initial map is not bijective"), "SDEM: a user's folded initial map is Invalid_input");
  init[vertex_descriptor(3)] = Point(0, 0, 0);
  const std::string msg0 = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::spherical_density_equalizing_map(m, out, PM::initial_map(init)); }, "SDEM initial map at 0");
  check(contains(msg0, "vertex 3") && contains(msg0, "center"), "SDEM: initial map at the center names vertex 3");
}

void duplicate_landmarks_are_refused()
{
  Mesh m = icosphere(2);
  Point_map out = output_map(m, "v:out");
  Landmarks lm = {{vertex_descriptor(0), Point(1, 0, 0)},
                  {vertex_descriptor(7), Point(0, 1, 0)},
                  {vertex_descriptor(7), Point(0, 0, 1)}};
  std::string msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "LSDEM duplicate landmark");
  check(contains(msg, "vertex 7") && contains(msg, "more than once") && contains(msg, "landmark 2"),
        "LSDEM: the duplicate landmark message names vertex 7 and landmark 2");
  lm[2].second = lm[1].second; // same target twice: still refused (it would count twice)
  msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::landmark_aligned_spherical_density_equalizing_map(m, lm, out); }, "LSDEM repeated landmark");
  check(contains(msg, "vertex 7"), "LSDEM: a repeated identical landmark is refused too");

  // FEQCM, for completeness (it refused them before)
  const std::array<double, 3> radii = DEM::bounding_box_ellipsoid_radii(m);
  Landmarks lq = {{vertex_descriptor(5), Point(0, 0, radii[2])}, {vertex_descriptor(5), Point(0, 0, -radii[2])}};
  msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::ellipsoidal_quasiconformal_map(m, lq, out); }, "FEQCM duplicate landmark");
  check(contains(msg, "vertex 5"), "FEQCM: duplicate landmark names vertex 5");
}

void radii_out_of_range_are_refused()
{
  Mesh m = bumpy(2);
  Point_map out = output_map(m, "v:out");
  auto ellipsoid = [&](std::array<double, 3> r) {
    return expect_nothing_written<DEM::Invalid_input>(
      m, out, [&] { DEM::ellipsoidal_conformal_map(m, out, PM::ellipsoid_radii(r)); },
      "FECM radii out of range");
  };
  check(contains(ellipsoid({1e300, 1e300, 1e300}), "range"), "radii 1e300: out of the supported range");
  check(contains(ellipsoid({1e-200, 1e-200, 1e-200}), "range"), "radii 1e-200: out of the supported range");
  check(contains(ellipsoid({1, 1, 2e6}), "too unequal"), "radii 1 1 2e6: too unequal");
  check(contains(ellipsoid({1, -1, 1}), "positive"), "negative radius refused");
  std::string msg = expect_nothing_written<DEM::Invalid_input>(
    m, out,
    [&] { DEM::ellipsoidal_density_equalizing_map(m, out, PM::ellipsoid_radii(std::array<double, 3>{1e120, 1, 1})); },
    "EDEM radii 1e120");
  check(contains(msg, "ellipsoid radii"), "EDEM: radii out of range refused");

  // In range: the extremes of the range are accepted (the check is on the
  // domain, whatever the scale of the mesh).
  bool accepted = true;
  try { I::check_radii(Eigen::Vector3d(1e-100, 1e-100, 0.9e-94)); I::check_radii(Eigen::Vector3d(1e100, 1e100, 1e95)); }
  catch(const DEM::Invalid_input& e) { accepted = false; std::cerr << e.what() << std::endl; }
  check(accepted, "radii at the ends of the range are accepted");
  // The default radii do not depend on the mesh scale.
  Mesh big = bumpy(2), small = bumpy(2);
  for(vertex_descriptor v : vertices(big)) big.point(v) = Point(1e8 * big.point(v).x(), 1e8 * big.point(v).y(), 1e8 * big.point(v).z());
  for(vertex_descriptor v : vertices(small)) small.point(v) = Point(1e-8 * small.point(v).x(), 1e-8 * small.point(v).y(), 1e-8 * small.point(v).z());
  const std::array<double, 3> rb = DEM::bounding_box_ellipsoid_radii(big), rs = DEM::bounding_box_ellipsoid_radii(small);
  check_close(rb[2], rs[2], 1e-9, "default radii are scale-invariant");

  // Torus radii
  Mesh t = torus(3, 1, 24, 10);
  Point_map tout = output_map(t, "v:out");
  auto torus_case = [&](double R, double r) {
    return expect_nothing_written<DEM::Invalid_input>(
      t, tout, [&] { DEM::toroidal_parameterization(t, tout, PM::torus_radii(std::array<double, 2>{R, r})); },
      "torus radii out of range");
  };
  check(contains(torus_case(1e300, 1), "range"), "torus R = 1e300 refused");
  check(contains(torus_case(2e6, 1), "too unequal"), "torus R/r = 2e6 refused");
  check(contains(torus_case(1, 2), "R > r"), "torus R < r refused");
}

void solver_clones_keep_the_settings()
{
  typedef Eigen::ConjugateGradient<I::Sparse_matrix, Eigen::Lower | Eigen::Upper> Cg;
  typedef CGAL::Eigen_solver_traits<Cg> Cg_traits;
  Cg_traits cg;
  cg.solver().setTolerance(1e-3);
  cg.solver().setMaxIterations(17);
  const std::unique_ptr<I::Spd_solver> original = I::make_spd_solver(cg);
  const std::unique_ptr<I::Spd_solver> copy = original->clone();
  const auto& cloned = dynamic_cast<const I::Eigen_traits_spd_solver<Cg_traits>&>(*copy).traits();
  Cg& cloned_solver = const_cast<Cg_traits&>(cloned).solver();
  check(cloned_solver.tolerance() == 1e-3, "CG clone keeps the tolerance 1e-3 (got " +
                                             std::to_string(cloned_solver.tolerance()) + ")");
  check(I::Eigen_solver_protected_settings<Cg>::max_iterations(cloned_solver) == 17,
        "CG clone keeps the iteration limit 17");
  check(&cloned_solver != &cg.solver(), "CG clone owns its solver (its own factorization)");
  // an unset iteration limit stays unset (Eigen's default: twice the size)
  Cg_traits plain;
  const auto plain_copy = I::make_spd_solver(plain)->clone();
  Cg& plain_solver =
    const_cast<Cg_traits&>(dynamic_cast<const I::Eigen_traits_spd_solver<Cg_traits>&>(*plain_copy).traits()).solver();
  check(I::Eigen_solver_protected_settings<Cg>::max_iterations(plain_solver) < 0, "unset iteration limit stays unset");

  // Behaviour: a clone with a 1-iteration limit solves a system only roughly,
  // exactly like the original; a default CG clone would solve it to 1e-16.
  I::Sparse_matrix A(30, 30);
  std::vector<Eigen::Triplet<double> > entries;
  for(int i = 0; i < 30; ++i) {
    entries.emplace_back(i, i, 2.5);
    if(i > 0) { entries.emplace_back(i, i - 1, -1); entries.emplace_back(i - 1, i, -1); }
  }
  A.setFromTriplets(entries.begin(), entries.end());
  I::Matrix B = I::Matrix::Ones(30, 1), X;
  Cg_traits rough;
  rough.solver().setMaxIterations(1);
  const auto rough_clone = I::make_spd_solver(rough)->clone();
  rough_clone->factor(A);
  rough_clone->solve(B, X);
  const double residual = (A * X - B).norm() / B.norm();
  check(residual > 1e-3, "a clone of a 1-iteration CG stops after one iteration (relative residual " +
                           std::to_string(residual) + ")");

  typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<I::Sparse_matrix> > Ldlt_traits;
  Ldlt_traits shifted;
  shifted.solver().setShift(0.5, 2.);
  const auto ldlt_copy = I::make_spd_solver(shifted)->clone();
  double offset = 0, scale = 0;
  I::Eigen_solver_protected_settings<Eigen::SimplicialLDLT<I::Sparse_matrix> >::simplicial_shift(
    const_cast<Ldlt_traits&>(dynamic_cast<const I::Eigen_traits_spd_solver<Ldlt_traits>&>(*ldlt_copy).traits()).solver(),
    offset, scale);
  check(offset == 0.5 && scale == 2., "LDLT clone keeps the shift (0.5, 2)");

  Configured_traits configured;
  configured.tolerance = 1e-3;
  const auto generic_copy = I::make_spd_solver(configured)->clone();
  check(dynamic_cast<const I::Generic_traits_spd_solver<Configured_traits>&>(*generic_copy).traits().tolerance == 1e-3,
        "generic traits clone keeps the user's setting");

#ifdef CGAL_DEM_USE_CHOLMOD
  // Ordering effort: the conformal maps' solvers ask CHOLMOD for AMD alone,
  // the default (thorough) leaves CHOLMOD's choice, a user's choice of
  // methods is kept, a clone keeps the effort, and the solutions agree.
  {
    typedef DEM::Default_sparse_solver_traits Cholmod_traits;
    auto cholmod_of = [](const I::Spd_solver& s) -> cholmod_common& {
      return const_cast<Cholmod_traits&>(dynamic_cast<const I::Eigen_traits_spd_solver<Cholmod_traits>&>(s).traits())
        .solver()
        .cholmod();
    };
    const std::unique_ptr<I::Spd_solver> thorough = I::make_default_spd_solver();
    const std::unique_ptr<I::Spd_solver> fast = I::clone_with_fast_ordering(*thorough);
    const std::unique_ptr<I::Spd_solver> fast_copy = fast->clone();
    I::Matrix X_thorough, X_fast, X_copy;
    check(thorough->factor(A) && thorough->solve(B, X_thorough), "CHOLMOD, thorough ordering: solved");
    check(fast->factor(A) && fast->solve(B, X_fast), "CHOLMOD, fast ordering: solved");
    check(fast_copy->factor(A) && fast_copy->solve(B, X_copy), "CHOLMOD, clone of the fast solver: solved");
    check(cholmod_of(*thorough).nmethods == 0, "thorough ordering leaves CHOLMOD's choice (nmethods 0)");
    check(cholmod_of(*fast).nmethods == 1 && cholmod_of(*fast).method[0].ordering == CHOLMOD_AMD,
          "fast ordering asks CHOLMOD for AMD alone");
    check(cholmod_of(*fast_copy).nmethods == 1 && cholmod_of(*fast_copy).method[0].ordering == CHOLMOD_AMD,
          "a clone of a fast-ordering solver keeps the effort");
    check((X_fast - X_thorough).norm() <= 1e-12 * X_thorough.norm() && (X_copy - X_fast).norm() == 0,
          "the orderings give the same solution");
    Cholmod_traits chosen;
    chosen.solver().cholmod().nmethods = 2; // the user's choice: AMD and METIS... kept
    const std::unique_ptr<I::Spd_solver> user = I::make_spd_solver(chosen);
    user->set_ordering_effort(I::Ordering_effort::fast);
    check(user->factor(A) && cholmod_of(*user).nmethods == 2, "fast ordering keeps a user's choice of methods");
  }
  // The diffusion solver's lagged factorization: simplicial LDL^T for small
  // systems, the supernodal default from supernodal_diffusion_from unknowns
  // on (a simplicial factorization of 1M faces costs ~30 s), split by a
  // separator from bisection_diffusion_from on; a clone keeps the rule, and all solve.
  {
    typedef I::Eigen_traits_spd_solver<I::Simplicial_ldlt_traits> Simplicial;
    typedef I::Eigen_traits_spd_solver<DEM::Default_sparse_solver_traits> Supernodal;
    auto path = [](Eigen::Index n) {
      I::Sparse_matrix P(n, n);
      std::vector<Eigen::Triplet<double> > t;
      for(Eigen::Index i = 0; i < n; ++i) {
        t.emplace_back(int(i), int(i), 2.5);
        if(i > 0) { t.emplace_back(int(i), int(i - 1), -1.); t.emplace_back(int(i - 1), int(i), -1.); }
      }
      P.setFromTriplets(t.begin(), t.end());
      return P;
    };
    const std::unique_ptr<I::Spd_solver> lagged = I::make_lagged_diffusion_factorization();
    const std::unique_ptr<I::Spd_solver> lagged_copy = lagged->clone();
    for(const I::Spd_solver* prototype : {lagged.get(), lagged_copy.get()}) {
      std::unique_ptr<I::Spd_solver> s = prototype->clone();
      auto& dispatch = dynamic_cast<I::Size_dispatched_spd_solver&>(*s);
      for(Eigen::Index n : {Eigen::Index(30), I::supernodal_diffusion_from - 1, I::supernodal_diffusion_from,
                            I::bisection_diffusion_from - 1, I::bisection_diffusion_from}) {
        const I::Sparse_matrix P = path(n);
        const I::Matrix rhs = I::Matrix::Ones(n, 2);
        I::Matrix sol;
        check(s->factor(P) && s->solve(rhs, sol) && (P * sol - rhs).norm() <= 1e-12 * rhs.norm(),
              "lagged diffusion factorization solves " + std::to_string(n) + " unknowns");
        const bool simplicial = dynamic_cast<const Simplicial*>(dispatch.active()) != nullptr;
        const auto* large = dynamic_cast<const I::Size_dispatched_spd_solver*>(dispatch.active());
        const bool supernodal = large && dynamic_cast<const Supernodal*>(large->active()) != nullptr;
        const bool bisection = large && dynamic_cast<const I::Bisection_cholesky*>(large->active()) != nullptr;
        const char* expected = n < I::supernodal_diffusion_from  ? "simplicial"
                               : n < I::bisection_diffusion_from ? "supernodal"
                                                                 : "split by a separator";
        check(n < I::supernodal_diffusion_from ? simplicial : n < I::bisection_diffusion_from ? supernodal : bisection,
              "lagged diffusion factorization of " + std::to_string(n) + " unknowns is " + expected);
      }
    }
  }
#endif

  // End to end: a configured CG solver is usable by a method that clones it.
  Mesh m = icosphere(2);
  Point_map out = output_map(m, "v:out");
  Cg_traits good;
  good.solver().setTolerance(1e-12);
  const DEM::Map_report r = DEM::spherical_conformal_map(m, out, PM::sparse_linear_solver(good));
  check(r.fold_overs == 0, "spherical conformal map with a configured CG solver: 0 fold-overs");
}

/// A side x side grid Laplacian plus `mass` times the identity; the edge
/// between vertices v < u weighs weight(v, u).
template <class Weight>
I::Sparse_matrix grid_diffusion_matrix(int side, double mass, Weight weight)
{
  const int n = side * side;
  std::vector<Eigen::Triplet<double> > t;
  for(int v = 0; v < n; ++v) {
    t.emplace_back(v, v, mass);
    const int i = v / side, j = v % side;
    for(int d = 0; d < 2; ++d) {
      const int ni = i + (d == 0), nj = j + (d == 1);
      if(ni >= side || nj >= side) continue;
      const int u = ni * side + nj;
      const double w = weight(v, u);
      t.emplace_back(v, v, w); t.emplace_back(u, u, w); t.emplace_back(v, u, -w); t.emplace_back(u, v, -w);
    }
  }
  I::Sparse_matrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/// The same with unit edge weights.
I::Sparse_matrix grid_diffusion_matrix(int side, double mass)
{
  return grid_diffusion_matrix(side, mass, [](int, int) { return 1.; });
}

// The factorization whose ordering puts a trailing set last (the spherical
// conformal map's one factorization for two systems): it solves the whole
// system, and the principal subsystem on the other unknowns with the same
// factor, as a separate factorization of that subsystem does. Only the
// package's default solver has it; a user's solver gets none (the map then
// factors twice).
void factorization_with_trailing_set_solves_both_systems()
{
  const int side = 30, n = side * side; // grid Laplacian plus a small mass: SPD
  const I::Sparse_matrix A =
    grid_diffusion_matrix(side, 0.01, [](int v, int u) { return 1. + 0.1 * ((v * 7 + u) % 5); });
  std::vector<char> trailing(n, 0);
  for(int v = 0; v < n; ++v) trailing[v] = (v % 11 == 3) || (v / side >= side - 4); // scattered and a band
  std::vector<int> leading;
  for(int v = 0; v < n; ++v) if(!trailing[v]) leading.push_back(v);
  const I::Matrix B = I::Matrix::Random(n, 3);

#ifdef CGAL_DEM_USE_CHOLMOD
  std::unique_ptr<I::Factorization_with_trailing_set> f =
    I::factorization_with_trailing_set_like(*I::make_default_spd_solver());
  check(f != nullptr, "the default solver has a factorization with a trailing set");
  if(!f) return;
  check(f->factor(A, trailing), "factorization with a trailing set succeeds");
  I::Matrix X, XL;
  check(f->solve(B, X) && (A * X - B).norm() <= 1e-10 * B.norm(), "it solves the whole system");
  check(f->solve_leading(B, XL), "it solves the leading subsystem");
  // the subsystem A_RR x_R = b_R factored on its own
  I::Sparse_matrix ARR(I::Sparse_matrix::Index(leading.size()), I::Sparse_matrix::Index(leading.size()));
  {
    std::vector<int> position(n, -1);
    for(std::size_t k = 0; k < leading.size(); ++k) position[leading[k]] = int(k);
    std::vector<Eigen::Triplet<double> > r;
    for(int c = 0; c < n; ++c)
      for(I::Sparse_matrix::InnerIterator it(A, c); it; ++it)
        if(position[it.row()] >= 0 && position[c] >= 0) r.emplace_back(position[it.row()], position[c], it.value());
    ARR.setFromTriplets(r.begin(), r.end());
  }
  Eigen::SimplicialLDLT<I::Sparse_matrix> ldlt(ARR);
  I::Matrix BR(I::Matrix::Index(leading.size()), 3);
  for(std::size_t k = 0; k < leading.size(); ++k) BR.row(I::Matrix::Index(k)) = B.row(leading[k]);
  const I::Matrix XR = ldlt.solve(BR);
  double error = 0, trailing_part = 0;
  for(std::size_t k = 0; k < leading.size(); ++k)
    error = std::max(error, (XL.row(leading[k]) - XR.row(I::Matrix::Index(k))).norm());
  for(int v = 0; v < n; ++v) if(trailing[v]) trailing_part = std::max(trailing_part, XL.row(v).norm());
  check(error <= 1e-9 * XR.norm(), "the leading solve is the subsystem's solution (" + std::to_string(error) + ")");
  check(trailing_part == 0, "the leading solve is 0 on the trailing set");
  // the halves: Y = G^-1 B_R with A_RR = G G^T, so Y^T Y = B_R^T A_RR^-1 B_R
  // (the Schur complements of the spherical conformal map's south step), and
  // the backward half of Y, whatever its trailing rows hold, is the leading solve
  I::Matrix Y, XH;
  check(f->forward_leading(B, Y), "it runs the forward half of the leading solve");
  const I::Matrix gram = Y.transpose() * Y, expected = BR.transpose() * XR;
  check((gram - expected).norm() <= 1e-9 * expected.norm(),
        "the forward half's Gram matrix is B_R^T A_RR^-1 B_R (" + std::to_string((gram - expected).norm()) + ")");
  const I::Index_matrix::Index leading_count = I::Index_matrix::Index(leading.size());
  Y.bottomRows(n - leading_count).setConstant(1e3); // the factor's order: R first, T last
  check(f->backward_leading(Y, XH) && (XH - XL).norm() <= 1e-12 * XL.norm(),
        "the backward half gives the leading solve and ignores the trailing rows");
  check(!f->factor(A, std::vector<char>(3, 0)), "a trailing set of the wrong size is refused");
  check(!f->solve_leading(B, XL), "nothing is solved after a refused factorization");
#endif
  typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<CGAL::Eigen_sparse_matrix<double>::EigenType> > Ldlt;
  check(I::factorization_with_trailing_set_like(*I::make_spd_solver(Ldlt())) == nullptr,
        "a user's solver has no factorization with a trailing set");
}

/// The factorization split by a separator (bisection_cholesky.h) on a
/// 50 x 50 grid Laplacian plus a small mass: the separator splits the graph,
/// the solution is that of the whole system, sequential and parallel solves
/// agree to the bit, a refactorization with new values solves the new
/// system, and a disconnected pattern is factored whole.
void bisection_cholesky_solves_and_refactors()
{
#ifdef CGAL_DEM_USE_CHOLMOD
  const int side = 50, n = side * side;
  auto grid = [&](double mass, double scale) {
    return grid_diffusion_matrix(side, mass, [scale](int v, int u) { return scale * (1. + 0.1 * ((v * 7 + u) % 5)); });
  };
  const I::Sparse_matrix A = grid(0.01, 1.), A2 = grid(0.5, 3.);
  std::vector<signed char> side_of;
  check(I::level_structure_bisection(A, side_of), "bisection: the grid has a separator");
  std::size_t separator = 0, coupled = 0, count[2] = {0, 0};
  for(int c = 0; c < n; ++c) {
    if(side_of[c] == 2) ++separator; else ++count[side_of[c]];
    for(I::Sparse_matrix::InnerIterator it(A, c); it; ++it)
      if(side_of[c] != 2 && side_of[it.row()] != 2 && side_of[c] != side_of[it.row()]) ++coupled;
  }
  check(coupled == 0, "bisection: no entry couples the two halves");
  check(separator > 0 && separator <= std::size_t(2 * side) && count[0] > std::size_t(n / 4) && count[1] > std::size_t(n / 4),
        "bisection: a short separator between halves of comparable size (" + std::to_string(separator) + ")");

  const I::Matrix B = I::Matrix::Random(n, 3);
  I::Matrix X[2];
  for(int parallel = 0; parallel < 2; ++parallel) {
    const I::Concurrency_scope scope(parallel == 1);
    I::Bisection_cholesky solver;
    check(solver.factor(A) && solver.separator_size() == separator, "bisection: factors the grid on the separator");
    check(solver.solve(B, X[parallel]) && (A * X[parallel] - B).norm() <= 1e-10 * B.norm(),
          "bisection: solves the whole system (" + std::string(parallel ? "parallel" : "sequential") + ")");
    I::Matrix X2;
    check(solver.factor(A2) && solver.solve(B, X2) && (A2 * X2 - B).norm() <= 1e-10 * B.norm(),
          "bisection: a refactorization with new values solves the new system");
  }
  check(X[0] == X[1], "bisection: sequential and parallel solutions agree to the bit");

  // two disconnected grids: no separator, factored whole
  I::Sparse_matrix D(2 * n, 2 * n);
  {
    std::vector<Eigen::Triplet<double> > t;
    for(int part = 0; part < 2; ++part)
      for(int c = 0; c < n; ++c)
        for(I::Sparse_matrix::InnerIterator it(A, c); it; ++it) t.emplace_back(part * n + it.row(), part * n + c, it.value());
    D.setFromTriplets(t.begin(), t.end());
    D.makeCompressed();
  }
  I::Bisection_cholesky whole;
  const I::Matrix BD = I::Matrix::Random(2 * n, 2);
  I::Matrix XD;
  check(whole.factor(D) && whole.separator_size() == 0 && whole.solve(BD, XD) && (D * XD - BD).norm() <= 1e-10 * BD.norm(),
        "bisection: a disconnected pattern is factored whole and solved");
#endif
}

/// The diffusion systems' conjugate gradients, preconditioned by a
/// factorization, stop at their step budget: a broken preconditioner makes
/// the solve fail instead of running a step per unknown (at a million faces:
/// minutes per solve). A correct one solves in a few steps.
void diffusion_cg_fails_fast_on_a_broken_preconditioner()
{
  const I::Sparse_matrix A = grid_diffusion_matrix(80, 1e-3);
  // "solves" every system with the identity: symmetric positive definite, so
  // CG still converges with it, in thousands of steps
  struct Identity_solver : I::Spd_solver
  {
    bool factor(const I::Sparse_matrix&) override { return true; }
    bool solve(const I::Matrix& B, I::Matrix& X) override { X = B; return true; }
    std::unique_ptr<I::Spd_solver> clone() const override { return std::make_unique<Identity_solver>(); }
  };
  const I::Matrix B = I::Matrix::Random(A.rows(), 1);
  I::Matrix X;
  I::Diffusion_pcg_solver broken(std::make_unique<Identity_solver>(), /*jacobi_below=*/0);
  check(broken.factor(A) && !broken.solve(B, X),
        "diffusion CG: a broken preconditioner fails within the step budget");
  I::Diffusion_pcg_solver sound(I::make_default_spd_solver(), /*jacobi_below=*/0);
  check(sound.factor(A) && sound.solve(B, X) && (A * X - B).norm() <= 1e-8 * B.norm(),
        "diffusion CG: the factorization solves");
}

/// The lagged factorization of a matrix far from the current one (a mass
/// 10^4 times larger: CG would need about a hundred steps) is redone inside
/// the solve once it has taken twice the refactoring threshold's steps, not
/// after the step budget.
void diffusion_cg_refactors_a_stale_factorization_at_once()
{
  struct Counting_solver : I::Spd_solver
  {
    std::unique_ptr<I::Spd_solver> exact = I::make_default_spd_solver();
    int* factorizations; int* applications;
    Counting_solver(int* f, int* a) : factorizations(f), applications(a) {}
    bool factor(const I::Sparse_matrix& M) override { ++*factorizations; return exact->factor(M); }
    bool solve(const I::Matrix& B, I::Matrix& X) override { ++*applications; return exact->solve(B, X); }
    std::unique_ptr<I::Spd_solver> clone() const override { return nullptr; }
  };
  const I::Sparse_matrix before = grid_diffusion_matrix(80, 1e-3), after = grid_diffusion_matrix(80, 10.);
  const I::Matrix B = I::Matrix::Random(before.rows(), 1);
  I::Matrix X;
  int factorizations = 0, applications = 0;
  const int refactor_steps = 12;
  I::Diffusion_pcg_solver pcg(std::make_unique<Counting_solver>(&factorizations, &applications),
                              /*jacobi_below=*/0, 1e-8, refactor_steps);
  const bool first = pcg.factor(before) && pcg.solve(B, X);
  applications = 0;
  const bool second = pcg.factor(after) && pcg.solve(B, X);
  check(first && second && (after * X - B).norm() <= 1e-8 * B.norm(), "diffusion CG: the stale sequence solves");
  check(factorizations == 2 && applications <= 2 * refactor_steps + 5,
        "diffusion CG: a stale factorization is redone within its solve (" + std::to_string(factorizations) +
          " factorizations, " + std::to_string(applications) + " preconditioner applications)");
}

void mobius_validates_its_input()
{
  Mesh m = bumpy(2);
  Point_map sphere = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
  const DEM::Map_report r0 = DEM::spherical_conformal_map(m, sphere);
  check(r0.fold_overs == 0, "conformal map for the Moebius test: 0 fold-overs");
  Point_map out = output_map(m, "v:out");

  Point_map bad = m.add_property_map<vertex_descriptor, Point>("v:bad").first;
  for(vertex_descriptor v : vertices(m)) bad[v] = sphere[v];
  bad[vertex_descriptor(4)] = Point(0, 0, 0);
  std::string msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::mobius_area_correction(m, bad, out); }, "Moebius: point at the origin");
  check(contains(msg, "vertex 4") && contains(msg, "center"), "Moebius: the point at the origin is named");

  bad[vertex_descriptor(4)] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::mobius_area_correction(m, bad, out); }, "Moebius: NaN point");
  check(contains(msg, "vertex 4") && contains(msg, "non-finite"), "Moebius: the non-finite point is named");

  for(vertex_descriptor v : vertices(m)) bad[v] = Point(sphere[v].x(), -sphere[v].y(), sphere[v].z());
  msg = expect_nothing_written<DEM::Invalid_input>(
    m, out, [&] { DEM::mobius_area_correction(m, bad, out); }, "Moebius: mirrored map");
  check(contains(msg, "not bijective"), "Moebius: a folded input map is refused");

  const DEM::Map_report r = DEM::mobius_area_correction(m, sphere, out);
  check(r.fold_overs == 0 && max_sphere_deviation(m, out) < 1e-12, "Moebius on a valid map: 0 fold-overs, on the sphere");
}

} // namespace

int main()
{
  algorithm_failures_are_not_invalid_input();
  user_initial_map_is_the_callers_fault();
  duplicate_landmarks_are_refused();
  radii_out_of_range_are_refused();
  solver_clones_keep_the_settings();
  factorization_with_trailing_set_solves_both_systems();
  bisection_cholesky_solves_and_refactors();
  diffusion_cg_fails_fast_on_a_broken_preconditioner();
  diffusion_cg_refactors_a_stale_factorization_at_once();
  mobius_validates_its_input();
  return finish("test_failures");
}
