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
  /// the landmark term are part of the objective:
  /// a run that does not converge returns its last map (see Density_flow)
  static constexpr bool returns_most_uniform_map = false;
  std::vector<Eigen::Index> vertices; // landmark vertices
  Matrix targets;                     // their targets on the unit sphere (rows)
  double alpha = 1, beta = 2, gamma = 5;
  double time_step = 0.01;
  Vector source_mass;
  std::unique_ptr<Spd_solver> smoother;
  Sparse_matrix m_matrix; // kept alive: the solver may refer to it
  Sparse_matrix m_dirichlet_load;
  std::vector<char> m_is_landmark;

  Matrix landmark_positions(const Matrix& x) const
  {
    Matrix p(static_cast<Eigen::Index>(vertices.size()), 3);
    for(std::size_t k = 0; k < vertices.size(); ++k) p.row(k) = x.row(vertices[k]);
    return p;
  }

  const Map_diffusion* diffusion_on(const Matrix&) const { return nullptr; }

  void before_step(Matrix& x)
  {
    const Eigen::Matrix3d R = optimal_rotation(landmark_positions(x), targets);
    x = x * R.transpose();
  }

  /// alpha (density) + beta (harmonic energy of the map from the input
  /// surface, paper sign: descent) + gamma (pull landmarks to their targets).
  /// The harmonic term is integrated implicitly: y = (A + dt beta L)^{-1} A (x + dt d')
  /// with the input's L and A, the landmark rows taking their explicit update
  /// as Dirichlet values, so that each landmark drags its neighbourhood along
  /// instead of being smoothed back. An explicit Laplacian step is unstable at
  /// the paper's step size on fine meshes (folds, endless step halving); the
  /// implicit matrix is constant, so it is factored once for the whole run.
  void direction(const Flow_state& st, Matrix& d)
  {
    d *= alpha;
    // A landmark vertex follows the landmark term alone: with the density
    // term kept there, the landmark settles where gamma |x - q| balances
    // alpha |grad rho / rho|, an error of order 1e-2 on real data.
    for(std::size_t k = 0; k < vertices.size(); ++k)
      d.row(vertices[k]) = -gamma * (st.x.row(vertices[k]) - targets.row(k));
    if(beta == 0) return;
    Matrix explicit_step = st.x + time_step * d, y;
    Matrix rhs = m_dirichlet_load * explicit_step;
    for(Eigen::Index i = 0; i < rhs.rows(); ++i)
      rhs.row(i) = m_is_landmark[i] ? explicit_step.row(i) : Eigen::RowVector3d(rhs.row(i) + source_mass[i] * explicit_step.row(i));
    if(!smoother->solve(rhs, y)) return; // keep the explicit terms only
    d = (y - st.x) / time_step;
    for(Eigen::Index i = 0; i < d.rows(); ++i) {
      const Eigen::RowVector3d r = st.x.row(i);
      d.row(i) -= d.row(i).dot(r) * r;
    }
  }

  /// Factors A + dt beta L of the input surface with the landmark rows eliminated.
  bool prepare(const Matrix& X, const Index_matrix& F, double dt, const Spd_solver& prototype)
  {
    time_step = dt;
    const Eigen::Index n = X.rows();
    // the input's mass scaled to the sphere's total area 4 pi: the flow is
    // then independent of the input's units, like the other two terms
    source_mass = lumped_mass(X, F);
    source_mass *= 4 * M_PI / source_mass.sum();
    m_matrix = Face_block_assembler(F, n).assemble(dt * beta * cotangent_stiffness_blocks(X, F), &source_mass);
    m_is_landmark.assign(static_cast<std::size_t>(n), 0);
    for(Eigen::Index v : vertices) m_is_landmark[v] = 1;
    // the load of the landmark columns on the free rows: rhs_i -= K_il y_l
    std::vector<Triplet> t;
    for(int c = 0; c < m_matrix.outerSize(); ++c)
      for(Sparse_matrix::InnerIterator it(m_matrix, c); it; ++it)
        if(m_is_landmark[it.col()] && !m_is_landmark[it.row()]) t.emplace_back(int(it.row()), int(it.col()), -it.value());
    m_dirichlet_load.resize(n, n);
    m_dirichlet_load.setFromTriplets(t.begin(), t.end());
    Matrix dummy = Matrix::Zero(n, 3);
    apply_dirichlet(m_matrix, dummy, m_is_landmark, dummy);
    smoother = prototype.clone();
    return smoother->factor(m_matrix);
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
