// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BISECTION_CHOLESKY_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BISECTION_CHOLESKY_H

// A sparse Cholesky factorization split in two by a vertex separator, so that
// two cores can share one factorization and every solve with it.
//
// Order the unknowns as [H0, H1, S], S a separator: no entry of A couples H0
// and H1. Each half h is factored on its own with S ordered last,
//
//   B_h = [A_hh A_hS; A_Sh A_SS] = L_h L_h^T,   L_h = [L_hh 0; W_h^T D_h],
//
// and D_h D_h^T = A_SS - A_Sh A_hh^{-1} A_hS is the half's Schur complement
// onto S. The Schur complement of A onto S is then dense and small (a few
// thousand unknowns on a million-face mesh):
//
//   C = A_SS - sum_h A_Sh A_hh^{-1} A_hS = D_0 D_0^T + D_1 D_1^T - A_SS.
//
// A solve of A x = b runs one forward and one backward triangular solve per
// half: the forward solve of L_h on [b_h; 0] leaves -W_h^T y_h = D_h z_h in
// its trailing part, C x_S = b_S + sum_h D_h z_h gives the separator, and the
// backward solve of L_h^T on [y_h; D_h^T x_S] gives x_h. The two halves run
// in parallel when the caller asked for parallel loops: the solves always
// (they do not call the BLAS), the factorizations when the BLAS may be called
// from two threads at once. The arithmetic is the same either way, so the
// solution does not depend on the number of threads.

#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/internal/parallel.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// A vertex separator of the graph of a symmetric sparsity pattern (full
/// storage) from the level structure of a breadth-first search: the search
/// starts from a pseudo-peripheral unknown (the last one reached by a search
/// from the last one reached from unknown 0, twice), the level where half of
/// the unknowns have been reached splits them, and of that level only the
/// unknowns with a neighbour in the next level are kept in the separator (the
/// others join the near half). On a mesh the levels are rings, and the
/// separator is a ring of about sqrt(n) unknowns. `side[i]` is 0 or 1 (the
/// halves) or 2 (the separator). False when the graph is not connected or
/// has too few levels to be split.
inline bool level_structure_bisection(const Sparse_matrix& A, std::vector<signed char>& side)
{
  const int n = int(A.rows());
  const int* start = A.outerIndexPtr();
  const int* neighbour = A.innerIndexPtr();
  std::vector<int> level(static_cast<std::size_t>(n)), reached;
  reached.reserve(static_cast<std::size_t>(n));
  auto search_from = [&](int source) {
    std::fill(level.begin(), level.end(), -1);
    reached.clear();
    reached.push_back(source);
    level[std::size_t(source)] = 0;
    for(std::size_t head = 0; head < reached.size(); ++head) {
      const int u = reached[head];
      for(int k = start[u]; k < start[u + 1]; ++k) {
        const int w = neighbour[k];
        if(level[std::size_t(w)] < 0) {
          level[std::size_t(w)] = level[std::size_t(u)] + 1;
          reached.push_back(w);
        }
      }
    }
  };
  if(n < 3) return false;
  search_from(0);
  if(int(reached.size()) != n) return false;
  for(int sweep = 0; sweep < 2; ++sweep) search_from(reached.back());
  const int depth = level[std::size_t(reached.back())];
  std::vector<int> count(static_cast<std::size_t>(depth) + 1, 0);
  for(int v = 0; v < n; ++v) ++count[std::size_t(level[std::size_t(v)])];
  int middle = 0;
  for(int total = 0; middle <= depth; ++middle)
    if((total += count[std::size_t(middle)]) >= n / 2) break;
  if(middle <= 0 || middle >= depth) return false;
  side.assign(static_cast<std::size_t>(n), 0);
  for(int v = 0; v < n; ++v) {
    const int l = level[std::size_t(v)];
    if(l > middle) side[std::size_t(v)] = 1;
    else if(l == middle)
      for(int k = start[v]; k < start[v + 1]; ++k)
        if(level[std::size_t(neighbour[k])] == middle + 1) { side[std::size_t(v)] = 2; break; }
  }
  return true;
}

#ifdef CGAL_DEM_USE_CHOLMOD

/// The factorization described at the top of this file, for the package's
/// default solver on large systems (sparse_solver.h). The separator and the
/// halves' orderings and symbolic analyses are kept while the sparsity
/// pattern does not change: a refactorization gathers the new values and
/// redoes the numeric work only.
class Bisection_cholesky : public Spd_solver
{
public:
  explicit Bisection_cholesky(double shift = 0) : m_shift(shift) {}

  bool factor(const Sparse_matrix& A) override
  {
    m_factored = false;
    m_whole.reset();
    if(!A.isCompressed() || A.rows() != A.cols()) return false;
    if(!m_pattern.matches(A) && !analyze(A)) {
      // no separator (a disconnected pattern, or too few levels): the same
      // system factored whole, by the default solver
      m_whole = make_default_spd_solver();
      return m_whole->factor(A);
    }
    bool ok[2] = {false, false};
    run_halves(Calls_blas::yes, [&](int h) { ok[h] = factor_half(A, *m_half[std::size_t(h)]); });
    if(!ok[0] || !ok[1]) return false;
    // C = D_0 D_0^T + D_1 D_1^T - (A_SS + shift)
    Matrix C = m_half[0]->schur_part + m_half[1]->schur_part;
    for(std::size_t k = 0; k < m_separator_entries.size(); ++k) {
      const Separator_entry& e = m_separator_entries[k];
      C(e.row, e.col) -= A.valuePtr()[e.source];
    }
    C.diagonal().array() -= m_shift;
    m_schur.compute(C);
    m_factored = m_schur.info() == Eigen::Success;
    return m_factored;
  }

  bool solve(const Matrix& B, Matrix& X) override
  {
    if(m_whole) return m_whole->solve(B, X);
    if(!m_factored || B.rows() != m_pattern.rows()) return false;
    const Eigen::Index k = B.cols(), s = Eigen::Index(m_separator.size());
    // forward solves; the separator's right-hand side b_S + sum_h D_h z_h
    std::array<Matrix, 2> forward;
    std::array<Matrix, 2> coupling;
    bool ok[2] = {false, false};
    run_halves(Calls_blas::no, [&](int h) {
      Half& half = *m_half[std::size_t(h)];
      Matrix local = Matrix::Zero(Eigen::Index(half.unknowns.size()), k);
      for(std::size_t i = 0; i < half.own; ++i) local.row(Eigen::Index(i)) = B.row(half.unknowns[i]);
      ok[h] = half.factorization.forward(local, forward[std::size_t(h)]);
      if(ok[h]) coupling[std::size_t(h)] = half.separator_block.triangularView<Eigen::Lower>() *
                                         forward[std::size_t(h)].bottomRows(s);
    });
    if(!ok[0] || !ok[1]) return false;
    Matrix separator_rhs(s, k);
    for(Eigen::Index i = 0; i < s; ++i) separator_rhs.row(i) = B.row(m_separator[std::size_t(i)]);
    for(int h = 0; h < 2; ++h)
      for(Eigen::Index p = 0; p < s; ++p)
        separator_rhs.row(m_half[std::size_t(h)]->separator_at[std::size_t(p)]) += coupling[std::size_t(h)].row(p);
    const Matrix x_separator = m_schur.solve(separator_rhs);
    // backward solves with the separator's values injected
    X.resize(B.rows(), k);
    run_halves(Calls_blas::no, [&](int h) {
      Half& half = *m_half[std::size_t(h)];
      Matrix& y = forward[std::size_t(h)];
      Matrix x_at_positions(s, k);
      for(Eigen::Index p = 0; p < s; ++p) x_at_positions.row(p) = x_separator.row(half.separator_at[std::size_t(p)]);
      y.bottomRows(s) = half.separator_block.transpose().triangularView<Eigen::Upper>() * x_at_positions;
      Matrix local;
      ok[h] = half.factorization.backward(y, local);
      if(ok[h])
        for(std::size_t i = 0; i < half.own; ++i) X.row(half.unknowns[i]) = local.row(Eigen::Index(i));
    });
    if(!ok[0] || !ok[1]) return false;
    for(Eigen::Index i = 0; i < s; ++i) X.row(m_separator[std::size_t(i)]) = x_separator.row(i);
    return X.allFinite();
  }

  std::unique_ptr<Spd_solver> clone() const override
  { return std::unique_ptr<Spd_solver>(new Bisection_cholesky(m_shift)); }

  /// The separator's size (0 before the first factorization, or when the
  /// last pattern had none), for tests and benchmarks.
  std::size_t separator_size() const { return m_whole ? 0 : m_separator.size(); }

private:
  struct Half
  {
    std::vector<int> unknowns;    // of A: the half's own unknowns, then the separator's
    std::size_t own = 0;
    Sparse_matrix B;              // B_h, full symmetric storage
    std::vector<int> source;      // B_h's values: indices into A's values
    Cholmod_factorization_with_trailing_set factorization{0};
    bool analyzed = false;
    Matrix separator_block;       // D_h, in the factor's order of the separator
    std::vector<int> separator_at; // factor position p of the separator -> index in m_separator
    Matrix schur_part;            // D_h D_h^T in m_separator's order
  };
  struct Separator_entry { Eigen::Index row, col; int source; };

  /// The solves run on the factor's supernodes without the BLAS
  /// (Cholmod_factorization_with_trailing_set::forward()); the
  /// factorizations call it.
  enum class Calls_blas { no, yes };

  template <class Body>
  void run_halves(Calls_blas blas, const Body& body)
  {
    if(parallel_loops_requested() && (blas == Calls_blas::no || blas_allows_two_concurrent_calls()))
      parallel_invoke([&] { body(0); }, [&] { body(1); });
    else {
      body(0);
      body(1);
    }
  }

  /// The separator, the halves' matrices B_h (pattern and where each value
  /// comes from in A) and the separator's entries of A.
  bool analyze(const Sparse_matrix& A)
  {
    m_pattern.forget();
    m_separator.clear();
    m_separator_entries.clear();
    std::vector<signed char> side;
    if(!level_structure_bisection(A, side)) return false;
    const int n = int(A.rows());
    std::vector<int> separator_index(static_cast<std::size_t>(n), -1);
    for(int v = 0; v < n; ++v)
      if(side[std::size_t(v)] == 2) {
        separator_index[std::size_t(v)] = int(m_separator.size());
        m_separator.push_back(v);
      }
    for(int h = 0; h < 2; ++h) {
      m_half[std::size_t(h)].reset(new Half());
      Half& half = *m_half[std::size_t(h)];
      for(int v = 0; v < n; ++v)
        if(side[std::size_t(v)] == h) half.unknowns.push_back(v);
      half.own = half.unknowns.size();
      half.unknowns.insert(half.unknowns.end(), m_separator.begin(), m_separator.end());
      if(half.own == 0) return false;
      // B_h's columns, each with its rows sorted (the separator's local
      // numbers follow the half's own)
      std::vector<int> local(static_cast<std::size_t>(n), -1);
      for(std::size_t i = 0; i < half.unknowns.size(); ++i) local[std::size_t(half.unknowns[i])] = int(i);
      const int m = int(half.unknowns.size());
      half.B.resize(m, m);
      std::vector<int> column_start(static_cast<std::size_t>(m) + 1, 0), rows;
      std::vector<std::pair<int, int> > column; // (local row, index into A's values)
      for(int j = 0; j < m; ++j) {
        const int v = half.unknowns[std::size_t(j)];
        column.clear();
        for(int k = A.outerIndexPtr()[v]; k < A.outerIndexPtr()[v + 1]; ++k) {
          const int i = local[std::size_t(A.innerIndexPtr()[k])];
          if(i >= 0) column.emplace_back(i, k);
        }
        std::sort(column.begin(), column.end());
        for(const auto& e : column) {
          rows.push_back(e.first);
          half.source.push_back(e.second);
        }
        column_start[std::size_t(j) + 1] = int(rows.size());
      }
      half.B.resizeNonZeros(Eigen::Index(rows.size()));
      std::copy(column_start.begin(), column_start.end(), half.B.outerIndexPtr());
      std::copy(rows.begin(), rows.end(), half.B.innerIndexPtr());
    }
    for(std::size_t j = 0; j < m_separator.size(); ++j) {
      const int v = m_separator[j];
      for(int k = A.outerIndexPtr()[v]; k < A.outerIndexPtr()[v + 1]; ++k) {
        const int i = separator_index[std::size_t(A.innerIndexPtr()[k])];
        if(i >= 0) m_separator_entries.push_back({Eigen::Index(i), Eigen::Index(j), k});
      }
    }
    m_pattern.remember(A);
    return true;
  }

  /// Factors B_h (the ordering and analysis once per pattern), keeps the
  /// trailing block D_h of its factor and D_h D_h^T in the separator's order.
  bool factor_half(const Sparse_matrix& A, Half& half)
  {
    for(std::size_t k = 0; k < half.source.size(); ++k) half.B.valuePtr()[k] = A.valuePtr()[half.source[k]];
    if(half.analyzed) {
      if(!half.factorization.refactor(half.B)) return half.analyzed = false; // analyzed afresh next time
    } else {
      std::vector<char> trailing(half.unknowns.size(), 0);
      std::fill(trailing.begin() + std::ptrdiff_t(half.own), trailing.end(), char(1));
      if(!half.factorization.factor(half.B, trailing)) return false;
      half.analyzed = true;
    }
    std::vector<int> trailing_order;
    half.factorization.trailing_block(half.separator_block, trailing_order);
    const Eigen::Index s = half.separator_block.rows();
    half.separator_at.resize(std::size_t(s));
    for(Eigen::Index p = 0; p < s; ++p) half.separator_at[std::size_t(p)] = trailing_order[std::size_t(p)];
    Matrix at_positions = Matrix::Zero(s, s);
    at_positions.selfadjointView<Eigen::Lower>().rankUpdate(half.separator_block);
    half.schur_part.resize(s, s);
    for(Eigen::Index q = 0; q < s; ++q)
      for(Eigen::Index p = q; p < s; ++p) {
        const int i = half.separator_at[std::size_t(p)], j = half.separator_at[std::size_t(q)];
        half.schur_part(i, j) = half.schur_part(j, i) = at_positions(p, q);
      }
    return true;
  }

  double m_shift;
  Sparsity_pattern m_pattern;
  std::vector<int> m_separator;
  std::vector<Separator_entry> m_separator_entries;
  std::array<std::unique_ptr<Half>, 2> m_half;
  Eigen::LLT<Matrix> m_schur;
  bool m_factored = false;
  std::unique_ptr<Spd_solver> m_whole; // when the pattern has no separator
};

#endif // CGAL_DEM_USE_CHOLMOD

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_BISECTION_CHOLESKY_H
