// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_FLOW_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_FLOW_H

// LSDEM (paper 001 section 3.2, ALGORITHMS.md section 8): the density flow
// plus a harmonic term and a landmark term, with the optimal rotation of the
// sphere taken in closed form before every step.

#include <CGAL/Density_equalizing_maps/internal/density_engine.h>

#include <Eigen/SVD>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// The rotation R minimizing sum_k |R s_k - q_k|^2 (Kabsch): the global
/// minimizer that the paper approaches by gradient descent on Euler angles.
inline Eigen::Matrix3d optimal_rotation(const Matrix& s, const Matrix& q)
{
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for(Eigen::Index k = 0; k < s.rows(); ++k) H += row3(s, k) * row3(q, k).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d U = svd.matrixU(), V = svd.matrixV();
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (V * U.transpose()).determinant() < 0 ? -1 : 1;
  return V * D * U.transpose();
}

struct Landmark_flow
{
  std::vector<Eigen::Index> vertices; // landmark vertices
  Matrix targets;                     // their targets on the unit sphere (rows)
  double alpha = 1, beta = 2, gamma = 5;

  Matrix landmark_positions(const Matrix& x) const
  {
    Matrix p(static_cast<Eigen::Index>(vertices.size()), 3);
    for(std::size_t k = 0; k < vertices.size(); ++k) p.row(k) = x.row(vertices[k]);
    return p;
  }

  void before_step(Matrix& x)
  {
    const Eigen::Matrix3d R = optimal_rotation(landmark_positions(x), targets);
    x = x * R.transpose();
  }

  /// alpha (density) + beta (tangential Laplacian smoothing, descent of the
  /// harmonic energy: paper sign) + gamma (pull landmarks to their targets)
  void direction(const Flow_state& st, Matrix& d)
  {
    d *= alpha;
    Matrix h = -(st.stiffness * st.x);
    for(Eigen::Index i = 0; i < h.rows(); ++i) {
      h.row(i) /= st.mass[i];
      const Eigen::RowVector3d r = st.x.row(i);
      h.row(i) -= h.row(i).dot(r) * r;
    }
    d += beta * h;
    for(std::size_t k = 0; k < vertices.size(); ++k)
      d.row(vertices[k]) -= gamma * (st.x.row(vertices[k]) - targets.row(k));
  }

  /// stop on the update norm max_i |dx_i|_1 (MATLAB's matrix infinity norm)
  double stop_measure(const Matrix& x_old, const Matrix& x_new, double)
  {
    return (x_new - x_old).cwiseAbs().rowwise().sum().maxCoeff();
  }
  template <class Domain>
  void after_step(std::size_t, Matrix&, Domain&) {}

  double mean_landmark_error(const Matrix& x) const
  {
    if(vertices.empty()) return 0;
    return (landmark_positions(x) - targets).rowwise().norm().mean();
  }
};

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_LANDMARK_FLOW_H
