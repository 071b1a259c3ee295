// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_WARP_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_WARP_H

// A smooth warp of the unit sphere that carries a few points exactly onto
// given targets (the registration's landmark correction). The warp is
//   phi(x) = normalize(x + P_x u(x)),   u(x) = sum_j w_j exp(-|x - p_j|^2 / (2 sigma^2)),
// P_x the projection onto the tangent plane at x, the weights w_j (vectors of
// R^3) solved so that u(p_k) = q_k / <p_k, q_k> - p_k, the tangent vector at
// p_k whose tip projects radially onto q_k: then phi(p_k) = q_k exactly.
// A Gaussian interpolant is smooth, so for landmark displacements small
// against sigma the warp is a diffeomorphism of the sphere close to the
// identity; a mapped mesh stays fold-free, which is checked with exact
// predicates after every application (a warp that folds is not applied).

#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// What `warp_landmarks_onto_targets()` did.
struct Landmark_warp_result
{
  double error_before = 0; ///< largest distance between a landmark and its target, before
  double error_after = 0;  ///< the same after the warps that were applied
  std::size_t warps = 0;   ///< warps applied (each checked fold-free)
  bool exact = false;      ///< every landmark reached its target (to rounding)
};

/// Gaussian width of the warp: half the median distance from a landmark to its
/// nearest other landmark, so that each landmark carries its own neighbourhood
/// along and the displacement decays between landmarks (a wider kernel makes the
/// interpolation system ill-conditioned and lets the displacement overshoot).
inline double landmark_warp_width(const Matrix& p)
{
  std::vector<double> nearest;
  for(Eigen::Index a = 0; a < p.rows(); ++a) {
    double best = 2;
    for(Eigen::Index b = 0; b < p.rows(); ++b)
      if(b != a) best = (std::min)(best, (p.row(a) - p.row(b)).norm());
    nearest.push_back(best);
  }
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return 0.5 * nearest[nearest.size() / 2];
}

/// One warp carrying the rows `p` towards the rows `q` (all on the unit sphere) by
/// the fraction `t` of the way (along the great circles), applied to every row of
/// `x`. Returns false if a landmark is 90 degrees or more from its target or the
/// interpolation system is singular (coincident landmarks).
inline bool apply_landmark_warp(const Matrix& x, const Matrix& p, const Matrix& q, double t, Matrix& y)
{
  const Eigen::Index m = p.rows();
  const double sigma = landmark_warp_width(p);
  if(!(sigma > 1e-9)) return false;
  const double inv = 1 / (2 * sigma * sigma);
  Eigen::MatrixXd G(m, m), V(m, 3);
  for(Eigen::Index a = 0; a < m; ++a) {
    for(Eigen::Index b = 0; b < m; ++b) G(a, b) = std::exp(-(p.row(a) - p.row(b)).squaredNorm() * inv);
    const double pq = p.row(a).dot(q.row(a));
    if(!(pq > 1e-6)) return false;
    V.row(a) = t * (q.row(a) / pq - p.row(a)); // tangent at p_a; p_a + V_a lies on the ray through q_a
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(G); // G is positive definite for distinct landmarks
  if(llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd W = llt.solve(V);
  if(!W.allFinite()) return false;
  y.resize(x.rows(), 3);
  for(Eigen::Index i = 0; i < x.rows(); ++i) {
    const Eigen::RowVector3d xi = x.row(i);
    Eigen::RowVector3d u = Eigen::RowVector3d::Zero();
    for(Eigen::Index b = 0; b < m; ++b) u += W.row(b) * std::exp(-(xi - p.row(b)).squaredNorm() * inv);
    u -= u.dot(xi) * xi;
    y.row(i) = (xi + u).normalized();
  }
  return true;
}

/// Moves the map `x` (rows on the unit sphere, fold-free for the faces `F`) by
/// smooth warps of the sphere so that the rows `landmarks` reach `targets`,
/// keeping the map fold-free (exact count after each warp). A warp that would
/// fold is retried for half the way, a quarter, an eighth; the warps repeat from
/// the new positions until the landmarks are at their targets or no fraction
/// keeps the map fold-free. `x` is only changed by fold-free warps.
inline Landmark_warp_result warp_landmarks_onto_targets(Matrix& x, const Index_matrix& F,
                                                         const std::vector<Eigen::Index>& landmarks,
                                                         const Matrix& targets)
{
  const auto landmark_rows = [&](const Matrix& y) {
    Matrix p(Eigen::Index(landmarks.size()), 3);
    for(std::size_t k = 0; k < landmarks.size(); ++k) p.row(Eigen::Index(k)) = y.row(landmarks[k]);
    return p;
  };
  const auto error_of = [&](const Matrix& y) {
    return (landmark_rows(y) - targets).rowwise().norm().maxCoeff();
  };
  Landmark_warp_result r;
  r.error_before = r.error_after = error_of(x);
  const double exact_enough = 1e-12;
  Matrix y;
  for(int round = 0; round < 8 && r.error_after > exact_enough; ++round) {
    const Matrix p = landmark_rows(x);
    bool applied = false;
    for(double t = 1; t >= 0.125 && !applied; t /= 2) {
      if(!apply_landmark_warp(x, p, targets, t, y)) break;
      if(count_inverted_faces_about_center(y, F) == 0) {
        x.swap(y);
        ++r.warps;
        applied = true;
      }
    }
    if(!applied) break;
    r.error_after = error_of(x);
  }
  r.exact = r.error_after <= exact_enough;
  return r;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_WARP_H
