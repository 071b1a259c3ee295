// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PROJECTIONS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PROJECTIONS_H

// Stereographic projections of the unit sphere and of an ellipsoid, the
// toroidal projection, and rotations of the sphere (ALGORITHMS.md 1.10-1.12, 10.1).
// Formulas are arranged to avoid cancellation near the poles.

#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <complex>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

using Complex = std::complex<double>;

/// P^N(X,Y,Z) = (X + iY) / (1 - Z): north pole -> infinity, south pole -> 0.
inline Complex north_stereographic(const Eigen::Vector3d& s)
{
  const double r2 = s.x() * s.x() + s.y() * s.y();
  if(s.z() > 0) { // (X+iY)/(1-Z) = (X+iY)(1+Z)/(X^2+Y^2) on the unit sphere
    if(r2 == 0) return Complex(std::numeric_limits<double>::infinity(), 0);
    return Complex(s.x(), s.y()) * (1 + s.z()) / r2;
  }
  return Complex(s.x(), s.y()) / (1 - s.z());
}

/// (P^S)^{-1}(z) = (2Re z, 2Im z, 1 - |z|^2) / (1 + |z|^2).
inline Eigen::Vector3d inverse_south_stereographic(Complex z)
{
  if(!std::isfinite(z.real()) || !std::isfinite(z.imag())) return Eigen::Vector3d(0, 0, -1);
  const double n = std::norm(z);
  if(n > 1) { // = (P^N)^{-1}(1/conj z) evaluated without overflow
    const Complex w = z / std::norm(z); // = 1 / conj(z), without complex division
    const double m = std::norm(w);
    return Eigen::Vector3d(2 * w.real(), 2 * w.imag(), m - 1) / (1 + m);
  }
  return Eigen::Vector3d(2 * z.real(), 2 * z.imag(), 1 - n) / (1 + n);
}

/// (P^N)^{-1}(z) = (2Re z, 2Im z, |z|^2 - 1) / (1 + |z|^2); infinity -> north pole.
inline Eigen::Vector3d inverse_north_stereographic(Complex z)
{
  if(!std::isfinite(z.real()) || !std::isfinite(z.imag())) return Eigen::Vector3d(0, 0, 1);
  if(std::norm(z) > 1) { // (P^S)^{-1}(1/conj z)
    const Complex w = z / std::norm(z); // = 1 / conj(z), without complex division
    const double m = std::norm(w);
    return Eigen::Vector3d(2 * w.real(), 2 * w.imag(), 1 - m) / (1 + m);
  }
  const double n = std::norm(z);
  return Eigen::Vector3d(2 * z.real(), 2 * z.imag(), n - 1) / (1 + n);
}

/// P^S(X,Y,Z) = (X + iY) / (1 + Z): south pole -> infinity, north pole -> 0.
inline Complex south_stereographic(const Eigen::Vector3d& s)
{
  const double r2 = s.x() * s.x() + s.y() * s.y();
  if(s.z() < 0) {
    if(r2 == 0) return Complex(std::numeric_limits<double>::infinity(), 0);
    return Complex(s.x(), s.y()) * (1 - s.z()) / r2;
  }
  return Complex(s.x(), s.y()) / (1 + s.z());
}

inline Eigen::Vector3d row_vector3(const Matrix& X, Eigen::Index i) { return Eigen::Vector3d(X(i, 0), X(i, 1), X(i, 2)); }

/// Applies P^N to every row of S (n x 3) and returns the complex chart.
inline Complex_vector north_chart(const Matrix& S)
{
  Complex_vector z(S.rows());
  for(Eigen::Index i = 0; i < S.rows(); ++i) z[i] = north_stereographic(row_vector3(S, i));
  return z;
}

inline Matrix inverse_north_chart(const Complex_vector& z)
{
  Matrix S(z.size(), 3);
  for(Eigen::Index i = 0; i < z.size(); ++i) S.row(i) = inverse_north_stereographic(z[i]).transpose();
  return S;
}

inline Matrix inverse_south_chart(const Complex_vector& z)
{
  Matrix S(z.size(), 3);
  for(Eigen::Index i = 0; i < z.size(); ++i) S.row(i) = inverse_south_stereographic(z[i]).transpose();
  return S;
}

inline Matrix to_planar(const Complex_vector& z)
{
  Matrix P(z.size(), 2);
  P.col(0) = z.real();
  P.col(1) = z.imag();
  return P;
}

inline Complex_vector to_complex(const Matrix& P)
{
  Complex_vector z(P.rows());
  for(Eigen::Index i = 0; i < P.rows(); ++i) z[i] = Complex(P(i, 0), P(i, 1));
  return z;
}

/// Normalizes every row to unit length.
inline void normalize_rows(Matrix& S)
{
  for(Eigen::Index i = 0; i < S.rows(); ++i) S.row(i) /= S.row(i).norm();
}

/// A rotation R with R c = e_z (c need not be normalized): Rodrigues about c x e_z;
/// identity at the north pole, half-turn about x at the south pole.
/// sin and cos of the angle are read off c directly (not from 1 + c.e_z, which
/// cancels near the south pole), so R is orthonormal and R c = e_z to rounding.
inline Eigen::Matrix3d rotation_to_north_pole(Eigen::Vector3d c)
{
  c.normalize();
  const double sine = std::hypot(c.x(), c.y()), cosine = c.z();
  if(sine == 0) {
    if(cosine > 0) return Eigen::Matrix3d::Identity();
    return Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  const Eigen::Vector3d k(c.y() / sine, -c.x() / sine, 0.); // unit axis c x e_z / |c x e_z|
  const double one_minus_cos = cosine > 0 ? sine * sine / (1 + cosine) : 1 - cosine;
  Eigen::Matrix3d K;
  K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
  return cosine * Eigen::Matrix3d::Identity() + sine * K + one_minus_cos * k * k.transpose();
}

/// sqrt(x^2/a^2 + y^2/b^2 + z^2/c^2): 1 exactly on the ellipsoid.
inline double ellipsoid_level(const Eigen::Vector3d& p, const Eigen::Vector3d& radii)
{
  return p.cwiseQuotient(radii).norm();
}

/// Radial scaling onto the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1.
inline void project_to_ellipsoid(Matrix& X, const Eigen::Vector3d& radii)
{
  for(Eigen::Index i = 0; i < X.rows(); ++i)
    X.row(i) /= ellipsoid_level(X.row(i).transpose(), radii);
}

/// max_i |level(x_i) - 1|: the relative distance of the points from the ellipsoid.
inline double max_ellipsoid_deviation(const Matrix& X, const Eigen::Vector3d& radii)
{
  double d = 0;
  for(Eigen::Index i = 0; i < X.rows(); ++i)
    d = std::max(d, std::abs(ellipsoid_level(X.row(i).transpose(), radii) - 1));
  return d;
}

/// (P^N_abc)^{-1}(x+iy) = (2ax, 2by, c(|z|^2 - 1)) / (1 + |z|^2).
inline Eigen::Vector3d inverse_ellipsoidal_north_stereographic(Complex z, const Eigen::Vector3d& radii)
{
  return inverse_north_stereographic(z).cwiseProduct(radii);
}

/// The toroidal projection phi(u, v) onto the torus with radii R > r.
inline Eigen::Vector3d torus_point(double u, double v, double R, double r)
{
  const double w = R + r * std::cos(v / r);
  return Eigen::Vector3d(w * std::cos(u / R), w * std::sin(u / R), r * std::sin(v / r));
}

/// The inverse toroidal projection: u in [0, 2 pi R), v in [-pi r, pi r].
inline Eigen::Vector2d torus_coordinates(const Eigen::Vector3d& p, double R, double r)
{
  double t = std::atan2(p.y(), p.x());
  if(t < 0) t += 2 * M_PI;
  return Eigen::Vector2d(R * t, r * std::atan2(p.z(), std::hypot(p.x(), p.y()) - R));
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PROJECTIONS_H
