// Closed-form checks of the discrete building blocks (ALGORITHMS.md sections 1
// and 2): cotangent Laplacian, mass, averaging, gradients, Beltrami
// coefficients, the Linear Beltrami Solver, stereographic projections,
// rotations, the sparse solver adapters and Dirichlet elimination.

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>

#include "dem_test_meshes.h"

#include <Eigen/SparseLU>

namespace DEM = CGAL::Density_equalizing_maps;
namespace I = CGAL::Density_equalizing_maps::internal;
using namespace dem_test;
using I::Complex;

namespace {

typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<CGAL::Eigen_sparse_matrix<double>::EigenType> > Ldlt_traits;

double max_abs(const Matrix& M) { return M.size() ? M.cwiseAbs().maxCoeff() : 0.; }

// angle at corner p of triangle (p, q, r), by atan2 (independent of the operators' formula)
double angle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r)
{
  const Eigen::Vector3d a = q - p, b = r - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Vector3d row(const Matrix& X, int i) { return I::row3(X, i); }

// planar mesh in a tilted plane of R^3 with orthonormal frame (e1, e2)
Matrix embed_in_plane(const Matrix& P, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, const Eigen::Vector3d& o)
{
  Matrix X(P.rows(), 3);
  for(Eigen::Index i = 0; i < P.rows(); ++i) X.row(i) = (o + P(i, 0) * e1 + P(i, 1) * e2).transpose();
  return X;
}

void test_cotangent_laplacian()
{
  for(const Arrays& a : {icosphere_arrays(2), bumpy_arrays(2), torus_arrays(3, 1, 20, 10)}) {
    const I::Sparse_matrix L = I::cotangent_laplacian(a.X, a.F);
    const double scale = max_abs(Matrix(L));
    check(max_abs(L * Vector::Ones(a.X.rows())) <= 1e-13 * scale, "L annihilates constants");
    check(max_abs(Matrix(L) - Matrix(L.transpose())) <= 1e-15 * scale, "L is symmetric");
    // L_ij = -(cot alpha + cot beta) / 2 on every edge, angles measured independently
    std::map<std::pair<int, int>, double> expected;
    for(Eigen::Index k = 0; k < a.F.rows(); ++k)
      for(int c = 0; c < 3; ++c) {
        const int i = a.F(k, c), j = a.F(k, (c + 1) % 3), o = a.F(k, (c + 2) % 3);
        const double cot = 1. / std::tan(angle(row(a.X, o), row(a.X, i), row(a.X, j)));
        expected[std::make_pair(std::min(i, j), std::max(i, j))] -= 0.5 * cot;
      }
    double err = 0;
    for(const auto& e : expected) err = std::max(err, std::abs(L.coeff(e.first.first, e.first.second) - e.second));
    check(err <= 1e-12, "L_ij = -(cot a + cot b)/2 on every edge (max error " + std::to_string(err) + ")");
    check(L.nonZeros() == Eigen::Index(a.X.rows() + 2 * expected.size()), "L has the pattern of the edges");
    // PSD: u^T L u >= 0 for a few random u
    std::mt19937 gen(3);
    std::normal_distribution<double> N;
    bool psd = true;
    for(int r = 0; r < 5; ++r) {
      Vector u(a.X.rows());
      for(Eigen::Index i = 0; i < u.size(); ++i) u[i] = N(gen);
      psd = psd && u.dot(L * u) > 0;
    }
    check(psd, "L is positive semidefinite on random vectors");
  }

  // planar mesh (tilted in 3D, and as a 2-column chart): linear functions
  const int n = 12;
  const Arrays g = planar_grid_arrays(n, 0.35, 7);
  const std::vector<char> boundary = planar_grid_boundary(n);
  const Eigen::Vector3d e1 = Eigen::Vector3d(1, 2, 2).normalized();
  const Eigen::Vector3d e2 = e1.cross(Eigen::Vector3d(0, 0, 1)).normalized();
  for(int dim : {2, 3}) {
    const Matrix X = dim == 2 ? g.X : embed_in_plane(g.X, e1, e2, Eigen::Vector3d(0.3, -1, 2));
    const I::Sparse_matrix L = I::cotangent_laplacian(X, g.F);
    const double ca = 1.7, cb = -0.6, cc = 0.25;
    Vector u(X.rows());
    for(Eigen::Index i = 0; i < u.size(); ++i) u[i] = ca * g.X(i, 0) + cb * g.X(i, 1) + cc;
    const double area = I::face_areas(X, g.F).sum();
    check_close(area, 1., 1e-13, "planar grid area is 1");
    check_close(u.dot(L * u), (ca * ca + cb * cb) * area, 1e-12, "u^T L u = Dirichlet energy of a linear u");
    const Vector Lu = L * u;
    double interior = 0;
    for(Eigen::Index i = 0; i < u.size(); ++i) if(!boundary[i]) interior = std::max(interior, std::abs(Lu[i]));
    check(interior <= 1e-13, "L u = 0 at interior vertices for a linear u (" + std::to_string(interior) + ")");
  }
}

void test_mass_and_averaging()
{
  for(const Arrays& a : {icosphere_arrays(2), bumpy_arrays(2), ellipsoid_arrays(1, 1.5, 3, 2)}) {
    const Vector area = I::face_areas(a.X, a.F);
    const Vector A = I::lumped_mass(a.X, a.F);
    check_close(A.sum(), area.sum(), 1e-13 * area.sum(), "lumped mass sums to the total area");
    check(A.minCoeff() > 0, "lumped mass is positive");
    const I::Sparse_matrix M = I::face_to_vertex(area, a.F, a.X.rows());
    check(M.rows() == a.X.rows() && M.cols() == a.F.rows(), "M is n x m");
    check(max_abs(M * Vector::Ones(a.F.rows()) - Vector::Ones(a.X.rows())) <= 1e-14, "rows of M sum to 1");
    // M reproduces a face function that is constant around each vertex only; check the weights
    const Vector c = M * area;
    bool ok = true;
    for(Eigen::Index i = 0; i < a.X.rows(); ++i) ok = ok && c[i] > 0;
    check(ok, "M of a positive face function is positive");
  }
}

void test_gradients()
{
  const Eigen::Vector3d c(0.7, -1.3, 0.4);
  for(const Arrays& a : {icosphere_arrays(2), bumpy_arrays(2)}) {
    Vector g(a.X.rows());
    for(Eigen::Index i = 0; i < g.size(); ++i) g[i] = c.dot(row(a.X, int(i))) + 2.5;
    Index_matrix flipped_F = a.F;
    for(Eigen::Index k = 0; k < a.F.rows(); ++k) std::swap(flipped_F(k, 1), flipped_F(k, 2));
    for(int orientation = 0; orientation < 2; ++orientation) {
      const Index_matrix& F = orientation ? flipped_F : a.F;
      const Matrix G = I::face_gradient(a.X, F, g);
      double err = 0;
      for(Eigen::Index k = 0; k < F.rows(); ++k) {
        const Eigen::Vector3d nrm = I::face_normal(a.X, F, k).normalized();
        const Eigen::Vector3d tangential = c - c.dot(nrm) * nrm;
        err = std::max(err, (G.row(k).transpose() - tangential).norm());
      }
      check(err <= 1e-12, std::string("face_gradient of a linear function is its tangential gradient") +
                            (orientation ? " (flipped faces)" : "") + " (" + std::to_string(err) + ")");
    }
  }
  const Arrays p = planar_grid_arrays(10, 0.35, 5);
  Vector g(p.X.rows());
  for(Eigen::Index i = 0; i < g.size(); ++i) g[i] = 3 * p.X(i, 0) - 2 * p.X(i, 1) + 1;
  for(int orientation = 0; orientation < 2; ++orientation) {
    Index_matrix F = p.F;
    if(orientation) for(Eigen::Index k = 0; k < F.rows(); ++k) std::swap(F(k, 1), F(k, 2));
    const Matrix G = I::planar_face_gradient(p.X, F, g);
    double err = 0;
    for(Eigen::Index k = 0; k < F.rows(); ++k) err = std::max(err, std::abs(G(k, 0) - 3) + std::abs(G(k, 1) + 2));
    check(err <= 1e-12, std::string("planar gradient of a linear function") + (orientation ? " (clockwise)" : ""));
  }
}

// z -> a z + b conj(z) + c on the points of P
Matrix affine_image(const Matrix& P, Complex a, Complex b, Complex c)
{
  Matrix W(P.rows(), 2);
  for(Eigen::Index i = 0; i < P.rows(); ++i) {
    const Complex z(P(i, 0), P(i, 1));
    const Complex w = a * z + b * std::conj(z) + c;
    W(i, 0) = w.real();
    W(i, 1) = w.imag();
  }
  return W;
}

void test_beltrami()
{
  const int n = 11;
  const Arrays p = planar_grid_arrays(n, 0.35, 11);
  const Complex a(1.2, 0.5), b(0.3, -0.4), c(-2, 1);
  const Complex expected = b / a;
  const Matrix W = affine_image(p.X, a, b, c);
  for(int orientation = 0; orientation < 2; ++orientation) {
    Index_matrix F = p.F;
    if(orientation) for(Eigen::Index k = 0; k < F.rows(); ++k) std::swap(F(k, 1), F(k, 2));
    const I::Complex_vector mu = I::beltrami_coefficient(p.X, W, F);
    double err = 0;
    for(Eigen::Index k = 0; k < mu.size(); ++k) err = std::max(err, std::abs(mu[k] - expected));
    check(err <= 1e-13, std::string("BC of an affine map is b/a on every face") + (orientation ? " (clockwise)" : ""));
  }
  // orientation-reversing affine map: |mu| > 1
  {
    const I::Complex_vector mu = I::beltrami_coefficient(p.X, affine_image(p.X, b, a, c), p.F);
    check(mu.cwiseAbs().minCoeff() > 1, "BC of an orientation-reversing affine map has |mu| > 1");
  }
  // |mu| from 3D flattening: (s1 - s2) / (s1 + s2) = |b| / |a| for the affine map (|a| > |b|),
  // the image put in a tilted plane of R^3
  {
    const Eigen::Vector3d e1 = Eigen::Vector3d(0, 1, 1).normalized(), e2 = Eigen::Vector3d(1, 0, 0);
    const Matrix Y = embed_in_plane(W, e1, e2, Eigen::Vector3d(1, 2, 3));
    Matrix X3 = Matrix::Zero(p.X.rows(), 3);
    X3.leftCols(2) = p.X;
    const Vector m = I::beltrami_magnitude_3d(X3, Y, p.F);
    check((m.array() - std::abs(expected)).abs().maxCoeff() <= 1e-12, "3D |mu| of an affine map is |b|/|a|");
    check(I::beltrami_magnitude_3d(X3, X3 * 2.5, p.F).maxCoeff() <= 1e-12, "3D |mu| of a similarity is 0");
  }
  // truncation keeps the argument
  {
    I::Complex_vector mu(2);
    mu << Complex(0.6, 0.8), Complex(0.1, 0);
    I::truncate_beltrami(mu, 0.9);
    check(std::abs(std::abs(mu[0]) - 0.9) < 1e-15 && std::abs(std::arg(mu[0]) - std::atan2(0.8, 0.6)) < 1e-15 &&
            mu[1] == Complex(0.1, 0),
          "truncate_beltrami");
  }

  // metric BC of a planar chart to a curved 3D mesh (height field): |mu| < 1 and the
  // LBS stiffness built from it equals the cotangent stiffness of the 3D mesh
  {
    Matrix X(p.X.rows(), 3);
    for(Eigen::Index i = 0; i < X.rows(); ++i)
      X.row(i) << 1.3 * p.X(i, 0) + 0.2 * p.X(i, 1), p.X(i, 1) - 0.1 * p.X(i, 0),
        0.4 * std::sin(3 * p.X(i, 0)) * std::cos(2 * p.X(i, 1));
    for(int orientation = 0; orientation < 2; ++orientation) {
      Index_matrix F = p.F;
      if(orientation) for(Eigen::Index k = 0; k < F.rows(); ++k) std::swap(F(k, 1), F(k, 2));
      const I::Complex_vector mu = I::metric_beltrami_coefficient(p.X, X, F);
      check(mu.cwiseAbs().maxCoeff() < 1, "metric BC has |mu| < 1");
      const Matrix K = I::beltrami_stiffness_blocks(p.X, F, mu);
      const Matrix C = I::cotangent_stiffness_blocks(X, F);
      const double err = max_abs(K - C) / max_abs(C);
      check(err <= 1e-12, std::string("LBS stiffness of the metric BC = 3D cotangent stiffness") +
                            (orientation ? " (clockwise chart)" : "") + " (" + std::to_string(err) + ")");
    }
    // mu = 0 gives the cotangent stiffness of the chart itself
    const I::Complex_vector zero = I::Complex_vector::Zero(p.F.rows());
    check(max_abs(I::beltrami_stiffness_blocks(p.X, p.F, zero) - I::cotangent_stiffness_blocks(p.X, p.F)) <= 1e-12,
          "LBS stiffness with mu = 0 is the cotangent stiffness");
  }
}

void test_lbs()
{
  const int n = 15;
  const Arrays p = planar_grid_arrays(n, 0.35, 13);
  const std::vector<char> boundary = planar_grid_boundary(n);
  const Complex a(0.9, -0.3), b(0.25, 0.35), c(0.5, 0.5);
  const Matrix W = affine_image(p.X, a, b, c);
  const I::Complex_vector mu = I::Complex_vector::Constant(p.F.rows(), b / a);
  auto solver = I::make_default_spd_solver();
  Matrix w;
  check(I::linear_beltrami_solve(p.X, p.F, mu, boundary, W, *solver, w), "LBS succeeds");
  check(max_abs(w - W) <= 1e-10, "LBS with the BC of an affine map and the boundary pinned reproduces the map (" +
                                   std::to_string(max_abs(w - W)) + ")");

  // landmarks: boundary pinned to the identity, a few interior vertices pinned elsewhere
  std::vector<char> fixed = boundary;
  Matrix values = p.X;
  const int landmarks[3] = {3 * n + 4, 7 * n + 7, 10 * n + 5};
  for(int v : landmarks) {
    fixed[v] = 1;
    values(v, 0) += 0.03;
    values(v, 1) -= 0.02;
  }
  I::Complex_vector mu2(p.F.rows());
  for(Eigen::Index k = 0; k < mu2.size(); ++k) mu2[k] = Complex(0.2 * std::sin(double(k)), 0.1);
  Matrix w2;
  check(I::linear_beltrami_solve(p.X, p.F, mu2, fixed, values, *solver, w2), "LBS with landmarks succeeds");
  double pinned = 0;
  for(Eigen::Index i = 0; i < p.X.rows(); ++i) if(fixed[i]) pinned = std::max(pinned, (w2.row(i) - values.row(i)).norm());
  check(pinned == 0, "LBS keeps the constrained vertices exactly");
  // the free rows of the unmodified stiffness vanish
  const I::Sparse_matrix K = I::Face_block_assembler(p.F, p.X.rows()).assemble(I::beltrami_stiffness_blocks(p.X, p.F, mu2));
  const Matrix r = K * w2;
  double residual = 0;
  for(Eigen::Index i = 0; i < r.rows(); ++i) if(!fixed[i]) residual = std::max(residual, r.row(i).norm());
  check(residual <= 1e-11 * max_abs(Matrix(K)), "LBS solves K_II w_I = -K_IB w_B (" + std::to_string(residual) + ")");
  // the solution of a different solver (sparse LU of the reduced system) agrees
  std::vector<int> free_index(static_cast<std::size_t>(p.X.rows()), -1);
  int nfree = 0;
  for(Eigen::Index i = 0; i < p.X.rows(); ++i) if(!fixed[i]) free_index[i] = nfree++;
  std::vector<I::Triplet> t;
  Matrix rhs = Matrix::Zero(nfree, 2);
  for(int col = 0; col < K.outerSize(); ++col)
    for(I::Sparse_matrix::InnerIterator it(K, col); it; ++it) {
      if(free_index[it.row()] < 0) continue;
      if(free_index[col] >= 0) t.emplace_back(free_index[it.row()], free_index[col], it.value());
      else rhs.row(free_index[it.row()]) -= it.value() * values.row(col);
    }
  I::Sparse_matrix Kii(nfree, nfree);
  Kii.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<I::Sparse_matrix> lu(Kii);
  const Matrix wi = lu.solve(rhs);
  double diff = 0;
  for(Eigen::Index i = 0; i < p.X.rows(); ++i)
    if(!fixed[i]) diff = std::max(diff, (w2.row(i) - wi.row(free_index[i])).norm());
  check(diff <= 1e-12, "LBS agrees with a sparse LU of the reduced system (" + std::to_string(diff) + ")");
}

void test_projections()
{
  std::mt19937 gen(17);
  std::normal_distribution<double> N;
  double err_n = 0, err_s = 0, err_id = 0, err_z = 0;
  for(int r = 0; r < 2000; ++r) {
    Eigen::Vector3d s(N(gen), N(gen), N(gen));
    s.normalize();
    if(r == 0) s = Eigen::Vector3d(0, 0, -1);
    if(r == 1) s = Eigen::Vector3d(1e-9, 0, std::sqrt(1 - 1e-18));
    if(r == 2) s = Eigen::Vector3d(-1e-9, 2e-9, -std::sqrt(1 - 5e-18));
    err_n = std::max(err_n, (I::inverse_north_stereographic(I::north_stereographic(s)) - s).norm());
    err_s = std::max(err_s, (I::inverse_south_stereographic(I::south_stereographic(s)) - s).norm());
    // P^S o (P^N)^{-1}(z) = 1 / conj(z), P^N o (P^S)^{-1}(z) likewise
    const double scale = std::pow(10., (r % 13) - 6);
    const Complex z = scale * Complex(N(gen), N(gen));
    const Complex expected = 1. / std::conj(z);
    err_id = std::max(err_id, std::abs(I::south_stereographic(I::inverse_north_stereographic(z)) - expected) /
                                std::abs(expected));
    err_id = std::max(err_id, std::abs(I::north_stereographic(I::inverse_south_stereographic(z)) - expected) /
                                std::abs(expected));
    err_z = std::max(err_z, std::abs(I::north_stereographic(I::inverse_north_stereographic(z)) - z) / std::abs(z));
    err_z = std::max(err_z, std::abs(I::south_stereographic(I::inverse_south_stereographic(z)) - z) / std::abs(z));
  }
  check(err_n <= 1e-15 * 4, "(P^N)^{-1}(P^N(s)) = s (" + std::to_string(err_n) + ")");
  check(err_s <= 1e-15 * 4, "(P^S)^{-1}(P^S(s)) = s (" + std::to_string(err_s) + ")");
  check(err_id <= 1e-14, "P^S((P^N)^{-1}(z)) = 1/conj(z) (relative " + std::to_string(err_id) + ")");
  check(err_z <= 1e-14, "P^N((P^N)^{-1}(z)) = z over 13 orders of magnitude");
  // poles and infinity
  check((I::inverse_north_stereographic(Complex(0, 0)) - Eigen::Vector3d(0, 0, -1)).norm() == 0, "(P^N)^{-1}(0) = S");
  check((I::inverse_north_stereographic(Complex(INFINITY, 0)) - Eigen::Vector3d(0, 0, 1)).norm() == 0,
        "(P^N)^{-1}(inf) = N");
  check(std::isinf(std::abs(I::north_stereographic(Eigen::Vector3d(0, 0, 1)))), "P^N(N) = infinity");
  check(std::abs(I::south_stereographic(Eigen::Vector3d(0, 0, 1))) == 0, "P^S(N) = 0");
  // orientation: P^S preserves outward orientation, P^N reverses it
  {
    const Arrays a = icosphere_arrays(2);
    Matrix Pn(a.X.rows(), 2), Ps(a.X.rows(), 2);
    for(Eigen::Index i = 0; i < a.X.rows(); ++i) {
      const Complex zn = I::north_stereographic(row(a.X, int(i))), zs = I::south_stereographic(row(a.X, int(i)));
      Pn.row(i) << zn.real(), zn.imag();
      Ps.row(i) << zs.real(), zs.imag();
    }
    // faces away from the projection pole
    int pos_s = 0, neg_n = 0, tested = 0;
    const Vector sn = I::signed_areas_2(Pn, a.F), ss = I::signed_areas_2(Ps, a.F);
    for(Eigen::Index k = 0; k < a.F.rows(); ++k) {
      double zc = 0;
      for(int c = 0; c < 3; ++c) zc += a.X(a.F(k, c), 2) / 3;
      if(std::abs(zc) > 0.5) continue;
      ++tested;
      pos_s += ss[k] > 0;
      neg_n += sn[k] < 0;
    }
    check(tested > 0 && pos_s == tested && neg_n == tested, "P^S keeps and P^N reverses the outward orientation");
  }
  // ellipsoidal inverse projection lands on the ellipsoid
  {
    const Eigen::Vector3d radii(1, 1.5, 3);
    double err = 0;
    for(int r = 0; r < 100; ++r) {
      const Complex z(N(gen), N(gen));
      const Eigen::Vector3d q = I::inverse_ellipsoidal_north_stereographic(z, radii);
      err = std::max(err, std::abs(q.cwiseQuotient(radii).squaredNorm() - 1));
    }
    check(err <= 1e-14, "(P^N_abc)^{-1} lands on the ellipsoid");
  }
}

void test_rotation()
{
  std::mt19937 gen(19);
  std::normal_distribution<double> N;
  std::vector<Eigen::Vector3d> cs = {{0, 0, 1}, {0, 0, -1}, {1e-17, 0, -1}, {0, 0, 5}, {3, 0, 0}, {0, 1e-9, -1}};
  for(int r = 0; r < 100; ++r) cs.emplace_back(N(gen), N(gen), N(gen));
  double err_c = 0, err_o = 0, err_det = 0;
  for(const Eigen::Vector3d& c : cs) {
    const Eigen::Matrix3d R = I::rotation_to_north_pole(c);
    err_c = std::max(err_c, (R * c.normalized() - Eigen::Vector3d(0, 0, 1)).norm());
    err_o = std::max(err_o, (R.transpose() * R - Eigen::Matrix3d::Identity()).norm());
    err_det = std::max(err_det, std::abs(R.determinant() - 1));
  }
  check(err_c <= 1e-14, "rotation_to_north_pole maps c to e_z (" + std::to_string(err_c) + ")");
  check(err_o <= 1e-14 && err_det <= 1e-14, "rotation_to_north_pole is a rotation");
}

// a Dirichlet Laplace problem on the bumpy sphere with a few pinned vertices
struct Laplace_problem
{
  I::Sparse_matrix K;
  Matrix rhs;
  std::vector<char> fixed;
  Matrix values;
};

Laplace_problem laplace_problem(double shift)
{
  const Arrays a = bumpy_arrays(3);
  Laplace_problem p;
  p.K = I::cotangent_laplacian(a.X, a.F);
  p.fixed.assign(static_cast<std::size_t>(a.X.rows()), 0);
  p.values = Matrix::Zero(a.X.rows(), 2);
  for(Eigen::Index i = 0; i < a.X.rows(); i += 37) {
    p.fixed[i] = 1;
    p.values(i, 0) = a.X(i, 0) + shift;
    p.values(i, 1) = a.X(i, 1) * a.X(i, 2);
  }
  p.rhs = Matrix::Zero(a.X.rows(), 2);
  p.rhs.col(1) = I::lumped_mass(a.X, a.F) * shift;
  return p;
}

void test_solvers_and_dirichlet()
{
  Laplace_problem p = laplace_problem(0.);
  const I::Sparse_matrix K0 = p.K;
  const Matrix rhs0 = p.rhs;
  I::apply_dirichlet(p.K, p.rhs, p.fixed, p.values);
  check(p.K.nonZeros() == K0.nonZeros(), "apply_dirichlet keeps the sparsity pattern");
  check(max_abs(Matrix(p.K) - Matrix(p.K.transpose())) == 0, "apply_dirichlet keeps the matrix symmetric");
  // independent reference: dense solve of the reduced system
  const Eigen::Index n = K0.rows();
  std::vector<Eigen::Index> free_rows;
  for(Eigen::Index i = 0; i < n; ++i) if(!p.fixed[i]) free_rows.push_back(i);
  const Matrix D = Matrix(K0);
  Matrix Kii(free_rows.size(), free_rows.size()), b(free_rows.size(), 2);
  for(std::size_t r = 0; r < free_rows.size(); ++r) {
    for(std::size_t s = 0; s < free_rows.size(); ++s) Kii(r, s) = D(free_rows[r], free_rows[s]);
    b.row(r) = rhs0.row(free_rows[r]);
    for(Eigen::Index j = 0; j < n; ++j) if(p.fixed[j]) b.row(r) -= D(free_rows[r], j) * p.values.row(j);
  }
  const Matrix xi = Kii.ldlt().solve(b);
  Matrix reference(n, 2);
  for(Eigen::Index i = 0; i < n; ++i) if(p.fixed[i]) reference.row(i) = p.values.row(i);
  for(std::size_t r = 0; r < free_rows.size(); ++r) reference.row(free_rows[r]) = xi.row(r);

  std::unique_ptr<I::Spd_solver> solvers[3] = {
    I::make_default_spd_solver(),                                     // CHOLMOD if available, else SimplicialLDLT
    I::make_spd_solver(Ldlt_traits()),                                // Eigen traits adapter (symbolic reuse)
    std::unique_ptr<I::Spd_solver>(new I::Generic_traits_spd_solver<Ldlt_traits>()) // generic concept adapter
  };
  const char* names[3] = {"default solver", "Eigen_solver_traits<SimplicialLDLT>", "generic traits adapter"};
  Matrix first;
  for(int s = 0; s < 3; ++s) {
    Matrix x;
    const bool ok = solvers[s]->factor(p.K) && solvers[s]->solve(p.rhs, x);
    check(ok, std::string(names[s]) + " factors and solves");
    if(!ok) continue;
    const double e = max_abs(x - reference) / max_abs(reference);
    check(e <= 1e-9, std::string(names[s]) + " matches the dense reduced solve (" + std::to_string(e) + ")");
    // a second matrix with the same pattern and other values: the reused
    // symbolic analysis must give the new solution
    Laplace_problem q = laplace_problem(0.5);
    I::Sparse_matrix K2 = q.K;
    K2 *= 3.;
    I::apply_dirichlet(K2, q.rhs, q.fixed, q.values);
    Matrix x2;
    const bool ok2 = solvers[s]->factor(K2) && solvers[s]->solve(q.rhs, x2);
    check(ok2 && max_abs(Matrix(K2) * x2 - q.rhs) <= 1e-9 * max_abs(q.rhs),
          std::string(names[s]) + " refactors a matrix with the same pattern");
    // clone gives an independent solver of the same kind
    auto c = solvers[s]->clone();
    Matrix x3;
    check(c->factor(p.K) && c->solve(p.rhs, x3) && max_abs(x3 - x) <= 1e-12 * max_abs(x),
          std::string(names[s]) + " clone solves the same system");
    if(s == 0) first = x;
    else check(max_abs(x - first) <= 1e-10 * max_abs(first), std::string(names[s]) + " agrees with the default");
  }
}

} // namespace

int main()
{
  Stopwatch clock;
  test_cotangent_laplacian();
  test_mass_and_averaging();
  test_gradients();
  test_beltrami();
  test_lbs();
  test_projections();
  test_rotation();
  test_solvers_and_dirichlet();
  std::cout << "time " << clock.seconds() << " s" << std::endl;
  return finish("test_operators");
}
