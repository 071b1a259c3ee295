// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BELTRAMI_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BELTRAMI_H

// Beltrami coefficients of piecewise-linear maps (ALGORITHMS.md 1.5-1.7) and
// the Linear Beltrami Solver (section 2).

#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>

#include <Eigen/Geometry> // cross products

#include <complex>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

using Complex = std::complex<double>;

/// The x- and y-derivative weights of the three corners of a planar source
/// triangle: dg/dx = sum dx[a] g_a, dg/dy = sum dy[a] g_a.
struct Planar_derivative
{
  double dx[3], dy[3];
  double signed_area;
};

inline Planar_derivative planar_derivative(const Eigen::Vector2d p[3])
{
  Planar_derivative d;
  d.signed_area = 0.5 * ((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
  for(int a = 0; a < 3; ++a) {
    const Eigen::Vector2d e = p[(a + 2) % 3] - p[(a + 1) % 3]; // edge opposite corner a
    d.dx[a] = -e.y() / (2 * d.signed_area);
    d.dy[a] = e.x() / (2 * d.signed_area);
  }
  return d;
}

inline Planar_derivative planar_derivative(const Matrix& P, const Index_matrix& F, Eigen::Index k)
{
  Eigen::Vector2d p[3];
  for(int a = 0; a < 3; ++a) p[a] = Eigen::Vector2d(P(F(k, a), 0), P(F(k, a), 1));
  return planar_derivative(p);
}

/// mu = w_zbar / w_z from the partial derivatives of w = u + iv.
inline Complex beltrami_from_derivatives(Complex wx, Complex wy)
{
  const Complex I(0, 1);
  const Complex wz = 0.5 * (wx - I * wy), wzbar = 0.5 * (wx + I * wy);
  const double n = std::norm(wz);
  if(n == 0) return Complex(1, 0); // degenerate image
  const Complex p = wzbar * std::conj(wz);
  const Complex mu(p.real() / n, p.imag() / n); // avoids the slow generic complex division
  return std::isfinite(mu.real()) && std::isfinite(mu.imag()) ? mu : Complex(1, 0);
}

/// Beltrami coefficient per face of the planar PL map P -> W (both n x 2).
/// |mu| < 1: orientation kept, > 1: flipped, = 1: degenerate image.
inline Complex_vector beltrami_coefficient(const Matrix& P, const Matrix& W, const Index_matrix& F)
{
  Complex_vector mu(F.rows());
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) {
      const Planar_derivative d = planar_derivative(P, F, k);
      Complex wx(0, 0), wy(0, 0);
      for(int a = 0; a < 3; ++a) {
        const Complex w(W(F(k, a), 0), W(F(k, a), 1));
        wx += d.dx[a] * w; wy += d.dy[a] * w;
      }
      mu[k] = beltrami_from_derivatives(wx, wy);
    }
  });
  return mu;
}

/// Beltrami coefficient of a map from a planar chart P (n x 2) to a surface X
/// (n x 3), from the first fundamental form: mu = (E - G + 2iF) / (E + G + 2 sqrt(EG - F^2)).
/// It is the coefficient that makes the LBS stiffness equal the surface's
/// cotangent stiffness, so LBS with it reproduces a harmonic map of X.
inline Complex_vector metric_beltrami_coefficient(const Matrix& P, const Matrix& X, const Index_matrix& F)
{
  Complex_vector mu(F.rows());
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) {
      const Planar_derivative d = planar_derivative(P, F, k);
      Eigen::Vector3d Xx = Eigen::Vector3d::Zero(), Xy = Eigen::Vector3d::Zero();
      for(int a = 0; a < 3; ++a) {
        const Eigen::Vector3d x(X(F(k, a), 0), X(F(k, a), 1), X(F(k, a), 2));
        Xx += d.dx[a] * x; Xy += d.dy[a] * x;
      }
      const double E = Xx.squaredNorm(), Fm = Xx.dot(Xy), G = Xy.squaredNorm();
      const double det = std::max(E * G - Fm * Fm, 0.);
      mu[k] = Complex(E - G, 2 * Fm) / (E + G + 2 * std::sqrt(det));
    }
  });
  return mu;
}

/// |mu| per face of the PL maps from a fixed 3D triangle mesh X to meshes Y
/// with the same connectivity: (s1 - s2) / (s1 + s2) with s1 >= s2 the
/// singular values of the affine map between the triangles. Blind to
/// orientation. Each triangle is flattened isometrically into its own plane;
/// those of X, and their derivative weights, are computed once (EDEQ measures
/// its Beltrami term from the same starting map on every candidate).
class Beltrami_magnitude_from_reference
{
public:
  Beltrami_magnitude_from_reference(const Matrix& X, const Index_matrix& F) : m_F(F)
  {
    m_derivatives.resize(static_cast<std::size_t>(F.rows()));
    parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index k = begin; k < end; ++k) m_derivatives[static_cast<std::size_t>(k)] = flat_derivative(X, F, k);
    });
  }

  Vector operator()(const Matrix& Y) const
  {
    Vector m(m_F.rows());
    parallel_for(m_F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index k = begin; k < end; ++k) m[k] = magnitude(m_derivatives[static_cast<std::size_t>(k)], Y, m_F, k);
    });
    return m;
  }

  /// the derivative weights of face k of Z, flattened
  static Planar_derivative flat_derivative(const Matrix& Z, const Index_matrix& F, Eigen::Index k)
  {
    Eigen::Vector2d p[3];
    flatten(Z, F, k, p);
    return planar_derivative(p);
  }

  /// |mu| of face k from the flattened source triangle (weights d) to Y
  static double magnitude(const Planar_derivative& d, const Matrix& Y, const Index_matrix& F, Eigen::Index k)
  {
    Eigen::Vector2d q[3];
    flatten(Y, F, k, q);
    Complex wx(0, 0), wy(0, 0);
    for(int a = 0; a < 3; ++a) {
      const Complex w(q[a].x(), q[a].y());
      wx += d.dx[a] * w; wy += d.dy[a] * w;
    }
    return std::min(1., std::sqrt(std::norm(beltrami_from_derivatives(wx, wy)))); // std::abs calls hypot: slow
  }

private:
  static void flatten(const Matrix& Z, const Index_matrix& F, Eigen::Index k, Eigen::Vector2d q[3])
  {
    const Eigen::Vector3d a = row3(Z, F(k, 0)), b = row3(Z, F(k, 1)), c = row3(Z, F(k, 2));
    const Eigen::Vector3d u = b - a, w = c - a;
    const double lu = u.norm();
    const double x = u.dot(w) / lu, y = u.cross(w).norm() / lu;
    q[0] = Eigen::Vector2d(0, 0); q[1] = Eigen::Vector2d(lu, 0); q[2] = Eigen::Vector2d(x, y);
  }

  Index_matrix m_F;
  std::vector<Planar_derivative> m_derivatives;
};

/// The same for a single map X -> Y, without storing X's weights.
inline Vector beltrami_magnitude_3d(const Matrix& X, const Matrix& Y, const Index_matrix& F)
{
  typedef Beltrami_magnitude_from_reference B;
  Vector m(F.rows());
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) m[k] = B::magnitude(B::flat_derivative(X, F, k), Y, F, k);
  });
  return m;
}

/// mu with its modulus shrunk to at most `bound` (< 1), its argument kept.
inline Complex truncated_beltrami(Complex mu, double bound)
{
  return std::norm(mu) > bound * bound ? mu * (bound / std::abs(mu)) : mu;
}

/// truncated_beltrami() of every entry.
inline void truncate_beltrami(Complex_vector& mu, double bound)
{
  for(Eigen::Index k = 0; k < mu.size(); ++k) mu[k] = truncated_beltrami(mu[k], bound);
}

/// Local LBS stiffness blocks (m x 9) of grad.(A(mu) grad) on the source chart P.
/// mu = 0 gives the cotangent stiffness of P.
inline Matrix beltrami_stiffness_blocks(const Matrix& P, const Index_matrix& F, const Complex_vector& mu)
{
  Matrix B(F.rows(), 9);
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) {
      const double rho = mu[k].real(), tau = mu[k].imag();
      const double s = 1 - std::norm(mu[k]);
      const double a1 = ((1 - rho) * (1 - rho) + tau * tau) / s;
      const double a2 = -2 * tau / s;
      const double a3 = ((1 + rho) * (1 + rho) + tau * tau) / s;
      Eigen::Vector2d eta[3];
      for(int a = 0; a < 3; ++a) {
        const int b = F(k, (a + 1) % 3), c = F(k, (a + 2) % 3);
        eta[a] = Eigen::Vector2d(P(b, 1) - P(c, 1), P(c, 0) - P(b, 0));
      }
      const double area = std::abs(0.5 * ((P(F(k, 1), 0) - P(F(k, 0), 0)) * (P(F(k, 2), 1) - P(F(k, 0), 1)) -
                                          (P(F(k, 1), 1) - P(F(k, 0), 1)) * (P(F(k, 2), 0) - P(F(k, 0), 0))));
      for(int a = 0; a < 3; ++a)
        for(int b = 0; b < 3; ++b)
          B(k, 3 * a + b) = (a1 * eta[a].x() * eta[b].x() + a2 * (eta[a].x() * eta[b].y() + eta[a].y() * eta[b].x()) +
                             a3 * eta[a].y() * eta[b].y()) / (4 * area);
    }
  });
  return B;
}

/// Linear Beltrami Solver: the planar map w (n x 2) of the source chart P whose
/// Beltrami coefficient approximates mu (|mu| < 1), with w = fixed_values on
/// the vertices where is_fixed is set. `right_hand_side`, if given (n x 2), is
/// added to the load (periodic maps use it for the lattice terms).
/// Returns false if the factorization or the solve fails.
inline bool linear_beltrami_solve(const Matrix& P, const Index_matrix& F, const Complex_vector& mu,
                                  const std::vector<char>& is_fixed, const Matrix& fixed_values,
                                  Spd_solver& solver, Matrix& w, const Face_block_assembler* assembler = nullptr,
                                  const Matrix* right_hand_side = nullptr)
{
  Face_block_assembler local;
  if(!assembler) { local.build(F, P.rows()); assembler = &local; }
  Sparse_matrix K = assembler->assemble(beltrami_stiffness_blocks(P, F, mu));
  Matrix rhs = right_hand_side ? *right_hand_side : Matrix(Matrix::Zero(P.rows(), 2));
  apply_dirichlet(K, rhs, is_fixed, fixed_values);
  if(!solver.factor(K)) return false;
  return solver.solve(rhs, w);
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BELTRAMI_H
