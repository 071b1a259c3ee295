// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FOLD_OVERS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FOLD_OVERS_H

// Exact fold-over certification (ALGORITHMS.md section 11). Coordinates are
// converted to Epick points once per vertex, so every face incident to a
// vertex tests the very same numbers and the predicates are exact for them.

#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Epick;

/// The rows of Y (n x 3) as Epick points, each converted once.
inline std::vector<Epick::Point_3> epick_points_3(const Matrix& Y)
{
  std::vector<Epick::Point_3> P(static_cast<std::size_t>(Y.rows()));
  parallel_for(Y.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index i = begin; i < end; ++i) P[i] = Epick::Point_3(Y(i, 0), Y(i, 1), Y(i, 2));
  });
  return P;
}

/// Faces (i,j,k) of a map onto a star-shaped closed surface (sphere,
/// ellipsoid) whose image is not positively oriented about `center`:
/// orientation(center, f_i, f_j, f_k) != POSITIVE. The input mesh must be
/// oriented with outward normals (counter-clockwise seen from outside).
inline std::vector<Eigen::Index> inverted_faces_about_center(const Matrix& Y, const Index_matrix& F,
                                                              const Eigen::Vector3d& center = Eigen::Vector3d::Zero())
{
  const std::vector<Epick::Point_3> P = epick_points_3(Y);
  const Epick::Point_3 c(center.x(), center.y(), center.z());
  std::vector<char> inverted(static_cast<std::size_t>(F.rows()));
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k)
      inverted[k] = CGAL::orientation(c, P[F(k, 0)], P[F(k, 1)], P[F(k, 2)]) != CGAL::POSITIVE;
  });
  std::vector<Eigen::Index> out;
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    if(inverted[k]) out.push_back(k);
  return out;
}

inline std::size_t count_inverted_faces_about_center(const Matrix& Y, const Index_matrix& F,
                                                      const Eigen::Vector3d& center = Eigen::Vector3d::Zero())
{
  return inverted_faces_about_center(Y, F, center).size();
}

/// Exact orientation of every face of a planar chart (n x 2):
/// +1 counter-clockwise, -1 clockwise, 0 degenerate.
inline std::vector<int> planar_orientations(const Matrix& W, const Index_matrix& F)
{
  std::vector<Epick::Point_2> P(static_cast<std::size_t>(W.rows()));
  parallel_for(W.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index i = begin; i < end; ++i) P[i] = Epick::Point_2(W(i, 0), W(i, 1));
  });
  std::vector<int> o(static_cast<std::size_t>(F.rows()));
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k)
      o[k] = static_cast<int>(CGAL::orientation(P[F(k, 0)], P[F(k, 1)], P[F(k, 2)]));
  });
  return o;
}

/// The orientation most faces have (+1 on a tie), from planar_orientations():
/// the map's own sense, against which the other faces are the folded ones.
inline int majority_orientation(const std::vector<int>& orientations)
{
  long balance = 0;
  for(int o : orientations) balance += o;
  return balance >= 0 ? 1 : -1;
}

/// Faces of a planar map whose exact orientation is not `expected` (+1 or -1).
inline std::size_t count_planar_fold_overs(const Matrix& W, const Index_matrix& F, int expected = 1)
{
  std::size_t n = 0;
  for(int o : planar_orientations(W, F)) n += (o != expected);
  return n;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_FOLD_OVERS_H
