// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPERATORS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPERATORS_H

// Discrete P1 operators on triangle meshes (ALGORITHMS.md section 1).
// Positions are n x 3 (surfaces) or n x 2 (planar charts); triangles m x 3.
// Angles and areas come from cross and dot products, not Heron's formula, so
// needles and slivers stay finite.

#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>

#include <Eigen/Geometry> // cross products
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

using Sparse_matrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

inline Eigen::Vector3d row3(const Matrix& X, Eigen::Index i)
{
  return X.cols() == 3 ? Eigen::Vector3d(X(i, 0), X(i, 1), X(i, 2)) : Eigen::Vector3d(X(i, 0), X(i, 1), 0.);
}

/// Unnormalized normal (x_j - x_i) x (x_k - x_i) of face k; planar charts get (0,0,2*signed area).
inline Eigen::Vector3d face_normal(const Matrix& X, const Index_matrix& F, Eigen::Index k)
{
  const Eigen::Vector3d a = row3(X, F(k, 0)), b = row3(X, F(k, 1)), c = row3(X, F(k, 2));
  return (b - a).cross(c - a);
}

/// Unsigned triangle areas.
inline Vector face_areas(const Matrix& X, const Index_matrix& F)
{
  Vector A(F.rows());
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) A[k] = 0.5 * face_normal(X, F, k).norm();
  });
  return A;
}

/// A subset of the faces with their source areas, and the vertices they use.
/// Searches whose objective is a mean over faces (the Moebius area
/// correction, the dilation of the ellipsoidal chart) run on such a sample and
/// are polished or confirmed on all faces.
struct Face_sample
{
  Index_matrix F;
  Vector source_area;
  double source_total = 0; // the sum of source_area (parallel_sum()), once: the objectives divide by it
  std::vector<char> uses_vertex; // per vertex of the mesh
  std::vector<Eigen::Index> vertices; // increasing
};

/// The faces `kept` (increasing) of F.
inline Face_sample face_sample(const Index_matrix& F, const Vector& source_area, Eigen::Index n,
                               const std::vector<Eigen::Index>& kept)
{
  Face_sample smp;
  smp.F.resize(Eigen::Index(kept.size()), 3);
  smp.source_area.resize(Eigen::Index(kept.size()));
  smp.uses_vertex.assign(static_cast<std::size_t>(n), 0);
  for(std::size_t j = 0; j < kept.size(); ++j) {
    smp.F.row(Eigen::Index(j)) = F.row(kept[j]);
    smp.source_area[Eigen::Index(j)] = source_area[kept[j]];
    for(int c = 0; c < 3; ++c) smp.uses_vertex[F(kept[j], c)] = 1;
  }
  for(Eigen::Index i = 0; i < n; ++i)
    if(smp.uses_vertex[i]) smp.vertices.push_back(i);
  smp.source_total = parallel_sum(smp.source_area.size(), [&](Eigen::Index k) { return smp.source_area[k]; });
  return smp;
}

/// The sample's faces with each vertex numbered by its position in
/// `vertices` (every vertex the sample uses, in the order the caller keeps
/// its per-vertex arrays): objectives evaluated hundreds of times then touch
/// only the sample's vertices.
inline Index_matrix faces_in_sample_numbering(const Face_sample& sample, const std::vector<Eigen::Index>& vertices,
                                              Eigen::Index n)
{
  std::vector<int> position(static_cast<std::size_t>(n), -1);
  for(std::size_t j = 0; j < vertices.size(); ++j) position[static_cast<std::size_t>(vertices[j])] = int(j);
  Index_matrix F(sample.F.rows(), 3);
  for(Eigen::Index k = 0; k < sample.F.rows(); ++k)
    for(int c = 0; c < 3; ++c) F(k, c) = position[static_cast<std::size_t>(sample.F(k, c))];
  return F;
}

/// Every `stride`-th face of F.
inline Face_sample face_sample(const Index_matrix& F, const Vector& source_area, Eigen::Index n, Eigen::Index stride)
{
  std::vector<Eigen::Index> kept;
  for(Eigen::Index k = 0; k < F.rows(); k += std::max<Eigen::Index>(stride, 1)) kept.push_back(k);
  return face_sample(F, source_area, n, kept);
}

/// Signed areas of a planar chart (counter-clockwise positive).
inline Vector signed_areas_2(const Matrix& X, const Index_matrix& F)
{
  Vector A(F.rows());
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) A[k] = 0.5 * face_normal(X, F, k).z();
  });
  return A;
}

/// Assembles per-face 3x3 blocks into a sparse n x n matrix whose sparsity
/// pattern (all mesh edges plus the diagonal) is computed once. Re-assembly
/// writes straight into the value array, so solvers can keep their symbolic
/// factorization across iterations.
class Face_block_assembler
{
public:
  Face_block_assembler() = default;
  Face_block_assembler(const Index_matrix& F, Eigen::Index n) { build(F, n); }

  void build(const Index_matrix& F, Eigen::Index n)
  {
    // The pattern is the vertex adjacency plus the diagonal. Built column by
    // column from the vertex-face incidence (small sorted lists), which is
    // several times cheaper than setFromTriplets on 9 m + n triplets.
    std::vector<int> first(static_cast<std::size_t>(n) + 1, 0);
    for(Eigen::Index k = 0; k < F.rows(); ++k)
      for(int a = 0; a < 3; ++a) ++first[F(k, a) + 1];
    for(Eigen::Index i = 0; i < n; ++i) first[i + 1] += first[i];
    // corners (3 k + a) at each vertex, faces in increasing order
    m_corners.resize(static_cast<std::size_t>(first[n]));
    {
      std::vector<int> next(first.begin(), first.end() - 1);
      for(Eigen::Index k = 0; k < F.rows(); ++k)
        for(int a = 0; a < 3; ++a) m_corners[next[F(k, a)]++] = int(3 * k + a);
    }
    m_first_corner = std::move(first);
    // Each column (the vertex and the corners of its faces, sorted, without
    // repeats) is written by one thread into room for all its candidates,
    // then the columns are packed: the same pattern on any number of threads.
    std::vector<int> room(static_cast<std::size_t>(n) + 1, 0), length(static_cast<std::size_t>(n), 0);
    for(Eigen::Index c = 0; c < n; ++c) room[c + 1] = room[c] + 1 + 3 * (m_first_corner[c + 1] - m_first_corner[c]);
    std::vector<int> candidates(static_cast<std::size_t>(room[n]));
    parallel_for(n, [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index c = begin; c < end; ++c) {
        int* column = candidates.data() + room[c];
        int* last = column;
        *last++ = int(c);
        for(int s = m_first_corner[c]; s < m_first_corner[c + 1]; ++s)
          for(int a = 0; a < 3; ++a) *last++ = F(m_corners[s] / 3, a);
        std::sort(column, last);
        length[c] = int(std::unique(column, last) - column);
      }
    });
    std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0);
    for(Eigen::Index c = 0; c < n; ++c) outer[c + 1] = outer[c] + length[c];
    std::vector<int> inner(static_cast<std::size_t>(outer[n]));
    parallel_for(n, [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index c = begin; c < end; ++c)
        std::copy(candidates.data() + room[c], candidates.data() + room[c] + length[c], inner.data() + outer[c]);
    });
    { std::vector<int> none; candidates.swap(none); }
    std::vector<double> zeros(inner.size(), 0.);
    m_pattern = Eigen::Map<const Sparse_matrix>(n, n, Eigen::Index(inner.size()), outer.data(), inner.data(),
                                                zeros.data());
    m_slot.resize(F.rows(), 9);
    parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index k = begin; k < end; ++k)
        for(int a = 0; a < 3; ++a)
          for(int b = 0; b < 3; ++b) m_slot(k, 3 * a + b) = int(slot(F(k, a), F(k, b)));
    });
    m_diag.resize(n);
    for(Eigen::Index i = 0; i < n; ++i) m_diag[i] = slot(i, i);
  }

  /// blocks: m x 9, row-major local matrices; diagonal: optional extra n-vector.
  Sparse_matrix assemble(const Matrix& blocks, const Vector* diagonal = nullptr) const
  {
    Sparse_matrix S;
    assemble(blocks, diagonal, S);
    return S;
  }

  /// The same into S, whose storage is reused when it already has the
  /// pattern (a loop that reassembles every iteration then allocates nothing).
  void assemble(const Matrix& blocks, const Vector* diagonal, Sparse_matrix& S) const
  {
    if(!has_pattern(S)) S = m_pattern;
    double* v = S.valuePtr();
    const int* outer = S.outerIndexPtr();
    // Column by column, each column by one thread: the entries of column c
    // come from the faces at vertex c, added in increasing face order (as a
    // scatter over the faces would add them), so the sums are the same on
    // any number of threads.
    parallel_for(size(), [&](Eigen::Index begin, Eigen::Index end) {
      for(Eigen::Index c = begin; c < end; ++c) {
        std::fill(v + outer[c], v + outer[c + 1], 0.);
        for(int s = m_first_corner[c]; s < m_first_corner[c + 1]; ++s) {
          const int k = m_corners[s] / 3, b = m_corners[s] % 3;
          for(int a = 0; a < 3; ++a) v[m_slot(k, 3 * a + b)] += blocks(k, 3 * a + b);
        }
        if(diagonal) v[m_diag[c]] += (*diagonal)[c];
      }
    });
  }

  Eigen::Index size() const { return m_pattern.rows(); }
  /// The pattern (all values 0): the vertex adjacency plus the diagonal.
  const Sparse_matrix& pattern() const { return m_pattern; }

private:
  /// Same sizes and same (shared or equal) index arrays as the pattern.
  bool has_pattern(const Sparse_matrix& S) const
  {
    const Eigen::Index nnz = m_pattern.nonZeros(), n = m_pattern.outerSize();
    return S.rows() == m_pattern.rows() && S.cols() == m_pattern.cols() && S.isCompressed() &&
           S.nonZeros() == nnz &&
           std::equal(S.outerIndexPtr(), S.outerIndexPtr() + n + 1, m_pattern.outerIndexPtr()) &&
           std::equal(S.innerIndexPtr(), S.innerIndexPtr() + nnz, m_pattern.innerIndexPtr());
  }

  Eigen::Index slot(Eigen::Index r, Eigen::Index c) const
  {
    const int* inner = m_pattern.innerIndexPtr();
    const int* begin = inner + m_pattern.outerIndexPtr()[c];
    const int* end = inner + m_pattern.outerIndexPtr()[c + 1];
    return std::lower_bound(begin, end, int(r)) - inner;
  }
  Sparse_matrix m_pattern;
  Eigen::Matrix<int, Eigen::Dynamic, 9> m_slot; // value slots; int like the matrix indices (half the memory)
  std::vector<Eigen::Index> m_diag;
  std::vector<int> m_first_corner, m_corners; // the corners 3 k + a at each vertex (column)
};

/// Local cotangent stiffness blocks (m x 9) times `scale`, written into B
/// (whose storage a loop that reassembles every iteration reuses):
/// L_bc = -scale cot(a)/2, L_bb = scale (cot(a) + cot(c))/2, ...
inline void cotangent_stiffness_blocks(const Matrix& X, const Index_matrix& F, double scale, Matrix& B)
{
  B.resize(F.rows(), 9);
  const bool planar = X.cols() == 2; // planar charts and layouts: no third coordinate
  parallel_for(F.rows(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index k = begin; k < end; ++k) {
      double w[3]; // scale cot(a) / 2
      if(planar) {
        double e[3][2]; // e[a] = x_{a+1} - x_a
        for(int a = 0; a < 3; ++a)
          for(int d = 0; d < 2; ++d) e[a][d] = X(F(k, (a + 1) % 3), d) - X(F(k, a), d);
        const double twice_area = std::abs(e[0][0] * (X(F(k, 2), 1) - X(F(k, 0), 1)) -
                                           e[0][1] * (X(F(k, 2), 0) - X(F(k, 0), 0)));
        const double factor = -0.5 * scale / twice_area; // one division per face: the planar loops are hot
        for(int a = 0; a < 3; ++a) {
          const double* q = e[a];           // x_{a+1} - x_a
          const double* r = e[(a + 2) % 3]; // x_a - x_{a+2} = -(x_{a+2} - x_a)
          w[a] = factor * (q[0] * r[0] + q[1] * r[1]);
        }
      } else {
        const double twice_area = face_normal(X, F, k).norm();
        for(int a = 0; a < 3; ++a) {
          const Eigen::Vector3d p = row3(X, F(k, a)), q = row3(X, F(k, (a + 1) % 3)), r = row3(X, F(k, (a + 2) % 3));
          w[a] = scale * (0.5 * ((q - p).dot(r - p) / twice_area));
        }
      }
      for(int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        B(k, 3 * b + c) = B(k, 3 * c + b) = -w[a];
        B(k, 4 * a) = w[b] + w[c];
      }
    }
  });
}

/// Local cotangent stiffness blocks (m x 9): L_bc -= cot(a)/2, L_bb += cot(a)/2, ...
inline Matrix cotangent_stiffness_blocks(const Matrix& X, const Index_matrix& F)
{
  Matrix B;
  cotangent_stiffness_blocks(X, F, 1., B);
  return B;
}

/// Cotangent Laplacian L (symmetric positive semidefinite stiffness matrix;
/// the Laplace-Beltrami operator is -A^{-1} L).
inline Sparse_matrix cotangent_laplacian(const Matrix& X, const Index_matrix& F)
{
  return Face_block_assembler(F, X.rows()).assemble(cotangent_stiffness_blocks(X, F));
}

/// Uniform graph Laplacian (weight 1 per edge), for the Tutte fallback.
inline Sparse_matrix graph_laplacian(const Index_matrix& F, Eigen::Index n)
{
  std::vector<Triplet> t;
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int a = 0; a < 3; ++a) {
      const int i = F(k, a), j = F(k, (a + 1) % 3);
      if(i < j) { // each undirected edge once (closed, consistently oriented mesh)
        t.emplace_back(i, j, -1.); t.emplace_back(j, i, -1.);
        t.emplace_back(i, i, 1.); t.emplace_back(j, j, 1.);
      }
    }
  Sparse_matrix L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

/// Diagonal of the barycentric lumped mass matrix: A_ii = sum of |T|/3 over T containing i.
inline Vector lumped_mass(const Vector& face_area, const Index_matrix& F, Eigen::Index n)
{
  Vector A = Vector::Zero(n);
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) A[F(k, c)] += face_area[k] / 3.;
  return A;
}

inline Vector lumped_mass(const Matrix& X, const Index_matrix& F) { return lumped_mass(face_areas(X, F), F, X.rows()); }

/// Area-weighted face-to-vertex averaging M (n x m, rows sum to 1),
/// M_ik = |T_k| / sum_{T_l > i} |T_l| for the corners i of T_k. Its pattern
/// (column k: the three corners of face k, sorted) depends on the
/// connectivity only, so it is built once and re-assembly writes the weights
/// (the density-equalizing loops need M on every accepted map).
class Face_to_vertex_assembler
{
public:
  Face_to_vertex_assembler() = default;
  Face_to_vertex_assembler(const Index_matrix& F, Eigen::Index n) { build(F, n); }

  void build(const Index_matrix& F, Eigen::Index n)
  {
    m_rows = n;
    m_corners.resize(static_cast<std::size_t>(3 * F.rows()));
    for(Eigen::Index k = 0; k < F.rows(); ++k) {
      int* corner = &m_corners[static_cast<std::size_t>(3 * k)];
      for(int c = 0; c < 3; ++c) corner[c] = F(k, c);
      std::sort(corner, corner + 3);
    }
  }

  Sparse_matrix assemble(const Vector& face_area) const
  {
    Sparse_matrix M;
    assemble(face_area, M);
    return M;
  }

  /// The same into M, whose pattern is written only if it is not M's already
  /// (a loop that reassembles every iteration then allocates nothing).
  void assemble(const Vector& face_area, Sparse_matrix& M) const
  {
    const Eigen::Index m = face_area.size();
    m_total.setZero(m_rows);
    for(Eigen::Index k = 0; k < m; ++k)
      for(int c = 0; c < 3; ++c) m_total[m_corners[3 * k + c]] += face_area[k];
    if(M.rows() != m_rows || M.cols() != m || !M.isCompressed() || M.nonZeros() != 3 * m ||
       !std::equal(m_corners.begin(), m_corners.end(), M.innerIndexPtr())) {
      M.resize(m_rows, m);
      M.resizeNonZeros(3 * m);
      int* outer = M.outerIndexPtr();
      for(Eigen::Index k = 0; k <= m; ++k) outer[k] = int(3 * k);
      std::copy(m_corners.begin(), m_corners.end(), M.innerIndexPtr());
    }
    double* v = M.valuePtr();
    for(Eigen::Index k = 0; k < m; ++k)
      for(int c = 0; c < 3; ++c) v[3 * k + c] = face_area[k] / m_total[m_corners[3 * k + c]];
  }

private:
  mutable Vector m_total; // per vertex, the area of its faces (work storage)
  Eigen::Index m_rows = 0;
  std::vector<int> m_corners; // 3 k + c, c = 0, 1, 2: the corners of face k, sorted (column k of M)
};

inline Sparse_matrix face_to_vertex(const Vector& face_area, const Index_matrix& F, Eigen::Index n)
{
  return Face_to_vertex_assembler(F, n).assemble(face_area);
}

/// Per-face gradient of a P1 function g on a surface (m x 3):
/// grad g|_T = n_T x (g_i e_i + g_j e_j + g_k e_k) / (2|T|), e_a the edge opposite a.
inline Matrix face_gradient(const Matrix& X, const Index_matrix& F, const Vector& g)
{
  Matrix G(F.rows(), 3);
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    const Eigen::Vector3d N = face_normal(X, F, k);
    const double twice_area_sq = N.squaredNorm(); // |N| = 2|T|, and n_T = N/|N|
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for(int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e = row3(X, F(k, (a + 2) % 3)) - row3(X, F(k, (a + 1) % 3));
      s += g[F(k, a)] * e;
    }
    G.row(k) = N.cross(s) / twice_area_sq;
  }
  return G;
}

/// Per-face gradient on a planar chart (m x 2), valid for either orientation.
/// Corner a of face k sits at X(F(k, a)) and carries the value
/// g[G(k, a)]: G = F for a chart of the mesh itself; a layout with its own
/// corner points (the flat torus's unrolled faces) passes the mesh's faces as G.
inline Matrix planar_face_gradient(const Matrix& X, const Index_matrix& F, const Index_matrix& value_faces,
                                   const Vector& g)
{
  Matrix G(F.rows(), 2);
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    // grad g = J (sum_a g_a e_a) / (2 signed area), e_a the edge opposite a, J e = (-e_y, e_x)
    double sx = 0, sy = 0;
    for(int a = 0; a < 3; ++a) {
      const int j = F(k, (a + 1) % 3), l = F(k, (a + 2) % 3);
      const double ga = g[value_faces(k, a)];
      sx += ga * (X(l, 0) - X(j, 0));
      sy += ga * (X(l, 1) - X(j, 1));
    }
    const int i0 = F(k, 0), i1 = F(k, 1), i2 = F(k, 2);
    const double twice_signed = (X(i1, 0) - X(i0, 0)) * (X(i2, 1) - X(i0, 1)) - (X(i1, 1) - X(i0, 1)) * (X(i2, 0) - X(i0, 0));
    G(k, 0) = -sy / twice_signed;
    G(k, 1) = sx / twice_signed;
  }
  return G;
}

inline Matrix planar_face_gradient(const Matrix& X, const Index_matrix& F, const Vector& g)
{
  return planar_face_gradient(X, F, F, g);
}

/// Index of the most regular face: argmin of sum |l_a / perimeter - 1/3| (lowest index on ties).
inline Vector face_irregularity(const Matrix& X, const Index_matrix& F)
{
  Vector R(F.rows());
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    double l[3], p = 0;
    for(int a = 0; a < 3; ++a) { l[a] = (row3(X, F(k, (a + 1) % 3)) - row3(X, F(k, (a + 2) % 3))).norm(); p += l[a]; }
    R[k] = std::abs(l[0] / p - 1. / 3) + std::abs(l[1] / p - 1. / 3) + std::abs(l[2] / p - 1. / 3);
  }
  return R;
}

inline Eigen::Index most_regular_face(const Matrix& X, const Index_matrix& F)
{
  Eigen::Index best;
  face_irregularity(X, F).minCoeff(&best);
  return best;
}

/// SDEM's most regular 1-ring face (paper 001 eqs. 25-28): R_v = sum_{T>v} R_T / 3,
/// then argmin over faces of the mean of R_v on its corners.
inline Eigen::Index most_regular_one_ring_face(const Matrix& X, const Index_matrix& F)
{
  const Vector R = face_irregularity(X, F);
  Vector Rv = Vector::Zero(X.rows());
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    for(int c = 0; c < 3; ++c) Rv[F(k, c)] += R[k] / 3.;
  Eigen::Index best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    const double v = (Rv[F(k, 0)] + Rv[F(k, 1)] + Rv[F(k, 2)]) / 3.;
    if(v < best_value) { best_value = v; best = k; }
  }
  return best;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPERATORS_H
