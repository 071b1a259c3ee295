// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H

// The quantities of the papers' tables (ALGORITHMS.md section 11).

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <cmath>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Sample mean and standard deviation (N - 1 normalization, as MATLAB).
struct Mean_sd { double mean = 0, sd = 0; };

inline Mean_sd mean_sd(const Vector& v)
{
  Mean_sd r;
  if(v.size() == 0) return r;
  r.mean = v.mean();
  if(v.size() > 1) r.sd = std::sqrt((v.array() - r.mean).square().sum() / double(v.size() - 1));
  return r;
}

/// sd / mean.
inline double relative_sd(const Vector& v) { const Mean_sd m = mean_sd(v); return m.sd / m.mean; }

/// Variance of v / mean(v) (N - 1 normalization).
inline double normalized_variance(const Vector& v) { const double r = relative_sd(v); return r * r; }

/// d_area(T) = log( (|f(T)| / sum |f|) / (|T| / sum |T|) ), flat triangle areas.
inline Vector log_area_ratio(const Vector& source_area, const Vector& image_area)
{
  const double ss = source_area.sum(), si = image_area.sum();
  Vector d(source_area.size());
  for(Eigen::Index k = 0; k < d.size(); ++k) d[k] = std::log((image_area[k] / si) / (source_area[k] / ss));
  return d;
}

/// Face density rho_F = population / area and vertex density rho_V = M rho_F.
struct Densities { Vector face, vertex; };

inline Densities densities(const Vector& population, const Vector& area, const Sparse_matrix& M)
{
  Densities d;
  d.face = population.cwiseQuotient(area);
  d.vertex = M * d.face;
  return d;
}

// ---------------------------------------------------------------------------
// Array-level forms of the public measures (measures.h).

/// Sign of the volume enclosed by a closed mesh (sum of x_i . (x_j x x_k) / 6):
/// +1 for outward-oriented faces, -1 for inward-oriented ones.
inline int enclosed_volume_sign(const Matrix& X, const Index_matrix& F)
{
  double v = 0;
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    v += row3(X, F(k, 0)).dot(row3(X, F(k, 1)).cross(row3(X, F(k, 2))));
  return v < 0 ? -1 : 1;
}

/// Faces of the map Y of a closed star-shaped image (sphere, ellipsoid) whose
/// exact orientation about `center` is not `expected` (+1 or -1). A face with
/// a non-finite corner is counted as folded (it has no valid image).
inline std::size_t count_fold_overs_about_center(const Matrix& Y, const Index_matrix& F, int expected,
                                                 const Eigen::Vector3d& center)
{
  std::vector<char> finite(static_cast<std::size_t>(Y.rows()));
  std::vector<Epick::Point_3> P(static_cast<std::size_t>(Y.rows()));
  for(Eigen::Index i = 0; i < Y.rows(); ++i) {
    finite[i] = std::isfinite(Y(i, 0)) && std::isfinite(Y(i, 1)) && std::isfinite(Y(i, 2));
    if(finite[i]) P[i] = Epick::Point_3(Y(i, 0), Y(i, 1), Y(i, 2));
  }
  const Epick::Point_3 c(center.x(), center.y(), center.z());
  const CGAL::Orientation want = expected < 0 ? CGAL::NEGATIVE : CGAL::POSITIVE;
  std::size_t n = 0;
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    const int i = F(k, 0), j = F(k, 1), l = F(k, 2);
    if(!finite[i] || !finite[j] || !finite[l] || CGAL::orientation(c, P[i], P[j], P[l]) != want) ++n;
  }
  return n;
}

/// Planar version: faces of the chart W (n x 2) whose exact orientation is not
/// `expected` (+1 counter-clockwise); non-finite corners count as folded.
inline std::size_t count_planar_fold_overs_checked(const Matrix& W, const Index_matrix& F, int expected)
{
  std::vector<char> finite(static_cast<std::size_t>(W.rows()));
  std::vector<Epick::Point_2> P(static_cast<std::size_t>(W.rows()));
  for(Eigen::Index i = 0; i < W.rows(); ++i) {
    finite[i] = std::isfinite(W(i, 0)) && std::isfinite(W(i, 1));
    if(finite[i]) P[i] = Epick::Point_2(W(i, 0), W(i, 1));
  }
  std::size_t n = 0;
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    const int i = F(k, 0), j = F(k, 1), l = F(k, 2);
    if(!finite[i] || !finite[j] || !finite[l] || static_cast<int>(CGAL::orientation(P[i], P[j], P[l])) != expected)
      ++n;
  }
  return n;
}

/// Variances of the normalized face density rho_F = population / |f(T)| and of
/// the normalized vertex density rho_V = M(f) rho_F on the map Y (ALGORITHMS.md 11).
struct Density_variances { double vertex = 0, face = 0; };

inline Density_variances density_variances(const Matrix& Y, const Index_matrix& F, const Vector& population)
{
  const Vector area = face_areas(Y, F);
  const Densities d = densities(population, area, face_to_vertex(area, F, Y.rows()));
  Density_variances v;
  v.face = normalized_variance(d.face);
  v.vertex = normalized_variance(d.vertex);
  return v;
}

/// Mean and sd of |mu| (isometric flattening, 1.7) and of |d_area| (1.9) from X to Y.
struct Distortion { Mean_sd abs_mu, abs_darea; };

inline Distortion distortion(const Matrix& X, const Matrix& Y, const Index_matrix& F)
{
  Distortion d;
  d.abs_mu = mean_sd(beltrami_magnitude_3d(X, Y, F));
  d.abs_darea = mean_sd(log_area_ratio(face_areas(X, F), face_areas(Y, F)).cwiseAbs());
  return d;
}

/// Remeshing quality (paper 000 eqs. 43-45, ALGORITHMS.md 1.8 and 11):
/// delta_size = ln(A_max / A_min) over the faces (natural log; infinite if a
/// face is degenerate) and delta_shape = mean over the faces of the face
/// irregularity R_T = sum_a |l_a / (l_1 + l_2 + l_3) - 1/3| (0 for equilateral).
struct Mesh_uniformity
{
  double delta_size = 0;
  double delta_shape = 0;
};

inline Mesh_uniformity mesh_uniformity(const Matrix& X, const Index_matrix& F)
{
  Mesh_uniformity q;
  if(F.rows() == 0) return q;
  const Vector area = face_areas(X, F);
  q.delta_size = std::log(area.maxCoeff() / area.minCoeff());
  q.delta_shape = face_irregularity(X, F).mean();
  return q;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MEASURES_H
