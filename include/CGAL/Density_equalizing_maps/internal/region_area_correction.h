// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_REGION_AREA_CORRECTION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_REGION_AREA_CORRECTION_H

// The last step of a globe cartogram: after the density-equalizing passes,
// give every region (and the sea) its target share of the globe's area with
// the smoothest displacement of the vertices that does it.
//
// Why a step of its own: a region that must shrink by 1e3..1e4 (Antarctica,
// Greenland in a population cartogram) ends as a tiny patch whose
// neighbouring faces have one edge of the patch's size. A face with such an
// edge cannot have the area the flow asks of it (its height is at most the
// globe's diameter), so a density flow on the faces stalls there, however
// many passes it makes (benchmark/RESULTS.md, "Globe cartograms"). The
// cartogram only asks for the area of each *region*, which those faces can
// give: a few hundred constraints on 3n unknowns.
//
// The step is Gauss-Newton (Levenberg-Marquardt) on the residuals
//   rho_j = sqrt(a_j(x) / t_j) - c   (j: regions and the sea),
// c the common scale (free: only shares are asked), weights w_j. The square
// root makes a residual linear in a similarity of its region (a region
// shrunk by s has sqrt(a) scaled by s), which the steps of a region that
// must shrink by 1e3 need; log(a) predicted those steps far too short.
// The damping is a stiffness R of the displacement d, so that a step is the
// smoothest displacement that lowers the linearized residuals:
//   min_d sum_j w_j (rho_j + G_j d)^2 + mu d^T R d,
// G_j the gradient of rho_j. There are few regions and many vertices, so it
// is solved in the dual: d = -R^{-1} G^T y with (mu I + Q G R^{-1} G^T) y = Q rho,
// Q = P^T W P (P removes the weighted mean, the scale c). Each iteration
// factors R on the current map and solves it for the gradients of the
// regions (three coordinates each). A step is halved until no face turns
// over (exact orientation about the centre) and the residual decreases.
// On a globe subdivided from a coarser one, the steps can be displacements of
// the coarse globe's vertices instead (Coarse_displacements): d = P d_c, the
// gradients restricted by P^T, and R the coarse map's stiffness, factored once.
//
// It does not reach every target: a region shrunk by orders of magnitude
// leaves the faces around it stretched over large parts of the globe, the
// steps become short and the correction stops as stalled (measured on the
// world at 50,000 vertices and on a generated polar region, RESULTS.md).

#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// per face: the parts (index, fraction of the face's area) it is made of
typedef std::vector<std::vector<std::pair<std::size_t, double> > > Face_parts;

struct Region_area_correction_result
{
  std::size_t iterations = 0;
  /// the size of the centred residuals (Region_area_residuals::size) before and after
  double initial_residual = 0, final_residual = 0;
  std::string message; ///< why it stopped before `stop` held, if it did
};

/// The parts' areas (regions 0..r-1, the uncovered rest as part r) for face areas A.
inline Vector part_areas(const Face_parts& parts, const Vector& A, std::size_t regions)
{
  Vector a = Vector::Zero(Eigen::Index(regions) + 1);
  for(std::size_t f = 0; f < parts.size(); ++f) {
    double covered = 0;
    for(const auto& p : parts[f]) {
      a[Eigen::Index(p.first)] += p.second * A[Eigen::Index(f)];
      covered += p.second;
    }
    a[Eigen::Index(regions)] += std::max(0., 1 - covered) * A[Eigen::Index(f)];
  }
  return a;
}


/// The Gauss-Newton problem on a map Y: residuals, weights and the centring.
class Region_area_residuals
{
public:
  Region_area_residuals(const Index_matrix& F, const Face_parts& parts, std::size_t regions, const Vector& target_share,
                        const Vector& weight)
    : m_F(F), m_parts(parts), m_regions(regions), m_target(target_share), m_weight(weight)
  {}

  /// sqrt(a_j / t_j) - (weighted mean), on the parts that have a target and an area.
  Vector centred_residual(const Matrix& Y, Vector* areas = nullptr) const
  {
    const Vector a = part_areas(m_parts, face_areas(Y, m_F), m_regions);
    if(areas) *areas = a;
    Vector rho = Vector::Zero(a.size());
    double wsum = 0, mean = 0;
    for(Eigen::Index j = 0; j < a.size(); ++j)
      if(active(j, a)) {
        rho[j] = std::sqrt(a[j] / m_target[j]);
        mean += m_weight[j] * rho[j];
        wsum += m_weight[j];
      }
    if(wsum > 0) mean /= wsum;
    for(Eigen::Index j = 0; j < a.size(); ++j)
      if(active(j, a)) rho[j] -= mean;
    return rho;
  }

  /// sqrt(sum_j w_j rho_j^2 / sum_j w_j) of a centred residual (0 when every share is reached)
  double size(const Vector& rho) const
  {
    double s = 0, w = 0;
    for(Eigen::Index j = 0; j < rho.size(); ++j) {
      s += m_weight[j] * rho[j] * rho[j];
      w += m_weight[j];
    }
    return w > 0 ? std::sqrt(s / w) : 0.;
  }

  /// The weights of the parts that take part on the map with areas a (0 elsewhere).
  Vector active_weights(const Vector& a) const
  {
    Vector w = Vector::Zero(a.size());
    for(Eigen::Index j = 0; j < a.size(); ++j)
      if(active(j, a)) w[j] = m_weight[j];
    return w;
  }

  /// The gradient of sqrt(a_j / t_j) with respect to the vertex positions,
  /// as the columns of a (3n x parts) sparse matrix: d|T|/dp = n x (q - r) / 2
  /// for the face T = (p, q, r) of unit normal n.
  Sparse_matrix residual_gradients(const Matrix& Y, const Vector& a) const
  {
    std::vector<Eigen::Triplet<double> > t;
    t.reserve(std::size_t(m_F.rows()) * 12);
    for(Eigen::Index k = 0; k < m_F.rows(); ++k) {
      const Eigen::Vector3d p[3] = {row3(Y, m_F(k, 0)), row3(Y, m_F(k, 1)), row3(Y, m_F(k, 2))};
      const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
      Eigen::Vector3d dA[3];
      for(int c = 0; c < 3; ++c) dA[c] = 0.5 * normal.cross(p[(c + 2) % 3] - p[(c + 1) % 3]);
      double covered = 0;
      auto add = [&](Eigen::Index j, double fraction) {
        if(!active(j, a)) return;
        for(int c = 0; c < 3; ++c)
          for(int d = 0; d < 3; ++d) t.emplace_back(3 * m_F(k, c) + d, j, fraction * dA[c][d] / (2 * std::sqrt(a[j] * m_target[j])));
      };
      for(const auto& part : m_parts[std::size_t(k)]) {
        add(Eigen::Index(part.first), part.second);
        covered += part.second;
      }
      if(covered < 1) add(Eigen::Index(m_regions), 1 - covered);
    }
    Sparse_matrix G(3 * Y.rows(), Eigen::Index(m_regions) + 1);
    G.setFromTriplets(t.begin(), t.end());
    return G;
  }

private:
  bool active(Eigen::Index j, const Vector& a) const { return m_target[j] > 0 && a[j] > 0 && m_weight[j] > 0; }

  const Index_matrix& m_F;
  const Face_parts& m_parts;
  std::size_t m_regions;
  Vector m_target, m_weight;
};

/// The distance from the centre to the plane of face k: about 1 for a small
/// face of the unit sphere, 0 for a face whose corners lie on a great circle.
inline double plane_offset(const Matrix& Y, const Index_matrix& F, Eigen::Index k)
{
  const Eigen::Vector3d a = row3(Y, F(k, 0)), b = row3(Y, F(k, 1)), c = row3(Y, F(k, 2));
  return a.dot(b.cross(c)) / (b - a).cross(c - a).norm();
}

/// R: the cotangent stiffness with every face's block divided by its area,
/// i.e. sum over faces of |grad d|^2 (not of |T| |grad d|^2): a face counts
/// as much however small the flow has made it, so the step cannot turn the
/// tiny faces of a shrunk region over by moving them unevenly. A small
/// multiple of the identity makes it definite.
inline Sparse_matrix face_scaled_stiffness(const Matrix& Y, const Index_matrix& F, const std::vector<char>& pinned)
{
  Matrix blocks = cotangent_stiffness_blocks(Y, F);
  const Vector A = face_areas(Y, F);
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    double edges = 0; // sum of squared edge lengths
    for(int c = 0; c < 3; ++c) edges += (row3(Y, F(k, c)) - row3(Y, F(k, (c + 1) % 3))).squaredNorm();
    const double quality = 4 * std::sqrt(3.) * A[k] / edges; // 1: equilateral, 0: degenerate
    blocks.row(k) /= A[k] * std::max(quality * quality, 1e-8);
  }
  Sparse_matrix R = Face_block_assembler(F, Y.rows()).assemble(blocks);
  const double mean = R.diagonal().mean();
  for(Eigen::Index i = 0; i < R.rows(); ++i) R.coeffRef(i, i) += (pinned[std::size_t(i)] ? 1e12 : 1e-9) * mean;
  return R;
}

/// R^{-1} applied to the columns of a (3n x c) matrix, R = L (x) I_3 with L
/// factored in `solver`: the three coordinates are three right-hand sides.
inline bool solve_coordinates(Spd_solver& solver, const Matrix& B3, Matrix& X3)
{
  const Eigen::Index n = B3.rows() / 3, c = B3.cols();
  Matrix B(n, 3 * c), X;
  for(Eigen::Index j = 0; j < c; ++j)
    for(int d = 0; d < 3; ++d)
      for(Eigen::Index i = 0; i < n; ++i) B(i, 3 * j + d) = B3(3 * i + d, j);
  if(!solver.solve(B, X)) return false;
  X3.resize(3 * n, c);
  for(Eigen::Index j = 0; j < c; ++j)
    for(int d = 0; d < 3; ++d)
      for(Eigen::Index i = 0; i < n; ++i) X3(3 * i + d, j) = X(i, 3 * j + d);
  return true;
}

/// The displacements of a coarser globe's vertices, carried to the vertices of
/// the map by the prolongation P (row i: the barycentric coordinates of vertex i
/// of the input globe in the coarse input globe). A correction step in this
/// space solves with the stiffness of the coarse map, whose size does not grow
/// with the fine mesh: why the correction of a fine globe started from a coarse
/// cartogram is cheap (benchmark/RESULTS.md).
struct Coarse_displacements
{
  Sparse_matrix prolongation; ///< n x n_c
  Matrix map;                 ///< the coarse globe's map (n_c x 3), for the stiffness
  Index_matrix faces;         ///< the coarse globe's faces
};

/// (P (x) I_3)^T G: the gradients (columns of G, 3n x c) with respect to the
/// coarse displacements (3 n_c x c).
inline Matrix restrict_gradients(const Sparse_matrix& P, const Sparse_matrix& G)
{
  const Sparse_matrix Pt = P.transpose(); // column i: the coarse weights of vertex i
  Matrix J = Matrix::Zero(3 * P.cols(), G.cols());
  for(Eigen::Index j = 0; j < G.outerSize(); ++j)
    for(Sparse_matrix::InnerIterator g(G, j); g; ++g) {
      const Eigen::Index i = g.row() / 3, d = g.row() % 3;
      for(Sparse_matrix::InnerIterator p(Pt, i); p; ++p) J(3 * p.row() + d, j) += p.value() * g.value();
    }
  return J;
}

/// (P (x) I_3) d: a displacement of the coarse vertices (3 n_c x 1) carried to the vertices (3n x 1).
inline Matrix prolong_displacement(const Sparse_matrix& P, const Matrix& dc)
{
  const Sparse_matrix Pt = P.transpose();
  Matrix d = Matrix::Zero(3 * P.rows(), 1);
  for(Eigen::Index i = 0; i < Pt.outerSize(); ++i)
    for(Sparse_matrix::InnerIterator p(Pt, i); p; ++p)
      for(int c = 0; c < 3; ++c) d(3 * i + c, 0) += p.value() * dc(3 * p.row() + c, 0);
  return d;
}

/// Moves the vertices of the unit-sphere map Y (n x 3) so that the parts'
/// areas approach `target_share` (regions 0..r-1 and the rest as part r;
/// shares of the globe's area, <= 0 for a part without a target), weighted by
/// `weight`. Stops when `stop(Y, iterations done)` holds (it may report
/// progress), after `max_iterations`, or when no step lowers the residual.
/// With `coarse`, the steps are displacements of the coarse globe's vertices
/// carried to the vertices (see Coarse_displacements), else of the vertices
/// themselves. Y stays fold-free if it is on entry.
inline Region_area_correction_result correct_region_areas(Matrix& Y, const Index_matrix& F, const Face_parts& parts,
                                                          std::size_t regions, const Vector& target_share,
                                                          const Vector& weight, Spd_solver& solver,
                                                          const std::function<bool(const Matrix&, std::size_t)>& stop,
                                                          std::size_t max_iterations = 200,
                                                          const Coarse_displacements* coarse = nullptr)
{
  Region_area_correction_result res;
  const Region_area_residuals problem(F, parts, regions, target_share, weight);
  Vector a;
  Vector rho = problem.centred_residual(Y, &a);
  res.initial_residual = res.final_residual = problem.size(rho);
  if(stop(Y, 0)) return res;

  // Vertices that do not move: the corners of the faces whose plane passes
  // near the centre. Such a face (corners almost on a great circle: det ~ 0
  // with a chordal area that is not small) turns over under almost any
  // motion that is not a rotation; holding its corners keeps it as it is.
  auto pin_flat_corners = [](const Matrix& Z, const Index_matrix& G, std::vector<char>& pinned) {
    for(Eigen::Index k = 0; k < G.rows(); ++k)
      if(plane_offset(Z, G, k) < 0.05)
        for(int c = 0; c < 3; ++c) pinned[std::size_t(G(k, c))] = 1;
  };
  std::vector<char> pinned(std::size_t(Y.rows()), 0);
  // the coarse stiffness is that of the coarse map, fixed: factored once
  if(coarse) {
    std::vector<char> coarse_pinned(std::size_t(coarse->map.rows()), 0);
    pin_flat_corners(coarse->map, coarse->faces, coarse_pinned);
    if(!solver.factor(face_scaled_stiffness(coarse->map, coarse->faces, coarse_pinned))) {
      res.message = "the regularizing stiffness could not be factored";
      return res;
    }
  }
  double mu = -1;
  bool reached = false;
  std::vector<double> history; // the residual after each iteration
  const Eigen::Index m = rho.size();
  while(res.iterations < max_iterations) {
    pin_flat_corners(Y, F, pinned);
    if(!coarse && !solver.factor(face_scaled_stiffness(Y, F, pinned))) {
      res.message = "the regularizing stiffness could not be factored";
      break;
    }
    const Vector w = problem.active_weights(a);
    const Sparse_matrix G = problem.residual_gradients(Y, a); // 3n x m
    const Matrix J = coarse ? restrict_gradients(coarse->prolongation, G) : Matrix(G);
    Matrix Z;
    if(!solve_coordinates(solver, J, Z)) { res.message = "a solve with the stiffness failed"; break; }
    const Matrix S = J.transpose() * Z; // J^T R^{-1} J (m x m)
    // Q = P^T W P, P = I - 1 w^T / sum w
    const double wsum = w.sum();
    Matrix P = Matrix::Identity(m, m);
    for(Eigen::Index i = 0; i < m; ++i) P.row(i) -= w.transpose() / wsum;
    const Matrix Q = P.transpose() * w.asDiagonal() * P;
    const Matrix QS = Q * S;
    if(mu < 0) mu = 1e-3 * std::max(QS.trace() / double(m), 1e-300);
    const Vector Qrho = Q * rho;

    bool accepted = false;
    for(int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      const Vector y = (QS + mu * Matrix::Identity(m, m)).partialPivLu().solve(Qrho);
      Matrix d = -(Z * y); // the step of every coordinate
      if(coarse) d = prolong_displacement(coarse->prolongation, d);
      for(Eigen::Index i = 0; i < Y.rows(); ++i)
        if(pinned[std::size_t(i)]) d.block<3, 1>(3 * i, 0).setZero();
      for(double alpha = 1; alpha > 1. / 1024; alpha /= 2) {
        Matrix trial = Y;
        for(Eigen::Index i = 0; i < Y.rows(); ++i)
          trial.row(i) = (row3(Y, i) + alpha * d.block<3, 1>(3 * i, 0)).normalized().transpose();
        if(count_inverted_faces_about_center(trial, F) > 0) continue; // exact
        Vector trial_a;
        const Vector trial_rho = problem.centred_residual(trial, &trial_a);
        if(!(problem.size(trial_rho) < problem.size(rho))) continue;
        Y.swap(trial);
        rho = trial_rho;
        a = trial_a;
        mu = alpha == 1 ? mu / 3 : mu * 2;
        accepted = true;
        break;
      }
      if(!accepted) mu *= 10;
    }
    if(!accepted) { res.message = "no step lowered the area residuals"; break; }
    ++res.iterations;
    res.final_residual = problem.size(rho);
    history.push_back(res.final_residual);
    if(stop(Y, res.iterations)) { reached = true; break; }
    // stalled: faces around a region shrunk by orders of magnitude are
    // stretched over large parts of the globe, and the steps become short
    if(history.size() > 10 && !(history.back() < 0.99 * history[history.size() - 11])) {
      res.message = "the region-area correction stalled (its residual fell by less than 1 % in 10 iterations)";
      break;
    }
  }
  if(!reached && res.message.empty())
    res.message = "the region-area correction reached its " + std::to_string(max_iterations) + " iterations";
  return res;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_REGION_AREA_CORRECTION_H
