// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPARSE_SOLVER_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPARSE_SOLVER_H

// Every linear system of the package (diffusion, harmonic maps, LBS) is
// symmetric positive definite after Dirichlet elimination. They go through a
// CGAL sparse solver traits class (concept SparseLinearAlgebraWithFactorTraits_d).
// The numerical code sees them through the small type-erased interface below,
// so it is compiled once whatever traits the user chooses.
//
// For `CGAL::Eigen_solver_traits` the Eigen solver is driven directly so that
// the symbolic analysis is done once per sparsity pattern: the traits' own
// `factor()` always redoes it (CGAL_CONVENTIONS.md section 4).

#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Eigen_vector.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#ifdef CGAL_DEM_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#ifdef CGAL_DEM_HAS_OPENMP_RUNTIME
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsRef
/// The default sparse solver traits: a supernodal Cholesky factorization
/// (SuiteSparse CHOLMOD through Eigen) when the package is built with
/// `CGAL_DEM_USE_CHOLMOD`, otherwise Eigen's `SimplicialLDLT`.
#ifdef CGAL_DEM_USE_CHOLMOD
typedef CGAL::Eigen_solver_traits<Eigen::CholmodSupernodalLLT<CGAL::Eigen_sparse_matrix<double>::EigenType> >
  Default_sparse_solver_traits;
#else
typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<CGAL::Eigen_sparse_matrix<double>::EigenType> >
  Default_sparse_solver_traits;
#endif

namespace internal {

/// How much a solver may spend on the fill-reducing ordering of a new
/// sparsity pattern.
enum class Ordering_effort
{
  /// the solver's own choice (CHOLMOD: minimum degree, and METIS as well when
  /// the fill is high): pays off for a pattern factored many times (the
  /// density-equalizing flows)
  thorough,
  /// a cheap ordering (CHOLMOD: minimum degree alone), for a pattern factored
  /// once or twice (the conformal maps): on a 1M-face mesh METIS costs more
  /// than the numeric work it saves in two factorizations
  fast
};

/// Factor once, solve many right-hand sides.
class Spd_solver
{
public:
  virtual ~Spd_solver() = default;
  /// The effort for the orderings of later patterns (solvers without a choice ignore it).
  virtual void set_ordering_effort(Ordering_effort) {}
  /// Factorizes `A` (kept by reference until the next call). Returns false on failure.
  virtual bool factor(const Sparse_matrix& A) = 0;
  /// Solves for every column of B.
  virtual bool solve(const Matrix& B, Matrix& X) = 0;
  /// Solves for every column of B; iterative solvers start from `guess`
  /// (same shape as B), direct ones ignore it.
  virtual bool solve(const Matrix& B, Matrix& X, const Matrix& /*guess*/) { return solve(B, X); }
  /// A fresh solver of the same kind (each system keeps its own factorization).
  virtual std::unique_ptr<Spd_solver> clone() const = 0;
};

template <class T> struct Is_eigen_solver_traits : std::false_type {};
template <class S> struct Is_eigen_solver_traits<CGAL::Eigen_solver_traits<S> > : std::true_type {};

/// While alive, lets the OpenMP runtime give a parallel region fewer threads
/// than it asks for (dynamic adjustment), on the calling thread only.
/// CHOLMOD's supernodal factorization always asks for 4 threads; on a machine
/// with fewer free cores the surplus threads cost more in wake-ups than the
/// factorization itself (measured: 100k-face FLASH 0.74 s -> 0.43 s on 2 cores).
/// A no-op without the OpenMP runtime (`CGAL_DEM_HAS_OPENMP_RUNTIME`).
class Dynamic_openmp_threads
{
public:
#ifdef CGAL_DEM_HAS_OPENMP_RUNTIME
  Dynamic_openmp_threads() : m_previous(omp_get_dynamic()) { omp_set_dynamic(1); }
  ~Dynamic_openmp_threads() { omp_set_dynamic(m_previous); }
private:
  int m_previous;
#endif
};

/// Reads the protected settings of an Eigen solver that have a setter but no
/// getter (the iteration limit as set, not as resolved against the last
/// matrix; the diagonal shifts). Forming a pointer to a protected member
/// through a derived class is allowed, and applying it to a base object is
/// not an access; the class is never instantiated as an object.
template <class Solver>
struct Eigen_solver_protected_settings : Solver
{
  static Eigen::Index max_iterations(const Solver& s)
  { return s.*(&Eigen_solver_protected_settings::m_maxIterations); }
  static void simplicial_shift(const Solver& s, double& offset, double& scale)
  {
    offset = double(s.*(&Eigen_solver_protected_settings::m_shiftOffset));
    scale = double(s.*(&Eigen_solver_protected_settings::m_shiftScale));
  }
#ifdef CGAL_DEM_USE_CHOLMOD
  static double cholmod_shift(const Solver& s) { return (s.*(&Eigen_solver_protected_settings::m_shiftOffset))[0]; }
#endif
};

template <class T> struct Is_cholmod_solver : std::false_type {};
#ifdef CGAL_DEM_USE_CHOLMOD
template <class M, int U> struct Is_cholmod_solver<Eigen::CholmodSupernodalLLT<M, U> > : std::true_type {};
template <class M, int U> struct Is_cholmod_solver<Eigen::CholmodSimplicialLLT<M, U> > : std::true_type {};
template <class M, int U> struct Is_cholmod_solver<Eigen::CholmodSimplicialLDLT<M, U> > : std::true_type {};
template <class M, int U> struct Is_cholmod_solver<Eigen::CholmodDecomposition<M, U> > : std::true_type {};
#endif

/// Gives the fresh solver `to` the user's settings of `from`. Eigen solvers
/// cannot be copied, and copies of a `CGAL::Eigen_solver_traits` share one
/// solver object, so a clone that must own its factorization builds a new
/// solver and copies the settings it knows: the tolerance and iteration limit
/// of the iterative solvers (conjugate gradients, BiCGSTAB, ...), the shift
/// (offset, scale) of Eigen's simplicial Cholesky factorizations and CHOLMOD's
/// shift. Preconditioner parameters and CHOLMOD's `cholmod_common` fields are
/// not copied: the clones use their defaults.
template <class Solver>
void copy_eigen_solver_settings(const Solver& from, Solver& to)
{
  typedef Eigen_solver_protected_settings<Solver> Access;
  if constexpr(std::is_base_of<Eigen::IterativeSolverBase<Solver>, Solver>::value) {
    to.setTolerance(from.tolerance());
    const Eigen::Index limit = Access::max_iterations(from);
    if(limit >= 0) to.setMaxIterations(limit); // negative: Eigen's default (twice the size), kept
  } else if constexpr(std::is_base_of<Eigen::SimplicialCholeskyBase<Solver>, Solver>::value) {
    double offset = 0, scale = 1;
    Access::simplicial_shift(from, offset, scale);
    to.setShift(offset, scale);
  }
#ifdef CGAL_DEM_USE_CHOLMOD
  else if constexpr(Is_cholmod_solver<Solver>::value) {
    to.setShift(Access::cholmod_shift(from));
  }
#endif
}

/// The sparsity pattern of the last matrix a factorization analysed: a
/// factorization whose next matrix has the same pattern keeps its ordering
/// and symbolic analysis.
class Sparsity_pattern
{
public:
  bool matches(const Sparse_matrix& A) const
  {
    return m_known && A.rows() == m_rows && A.nonZeros() == Eigen::Index(m_inner.size()) &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, m_outer.begin()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), m_inner.begin());
  }
  void remember(const Sparse_matrix& A)
  {
    m_rows = A.rows();
    m_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    m_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    m_known = true;
  }
  void forget() { m_known = false; }
  /// The unknowns of the remembered pattern.
  Eigen::Index rows() const { return m_known ? m_rows : 0; }

private:
  bool m_known = false;
  Eigen::Index m_rows = 0;
  std::vector<int> m_outer, m_inner;
};

/// Adapter for `CGAL::Eigen_solver_traits`: reuses the symbolic analysis while
/// the sparsity pattern of the matrix does not change.
template <class Traits>
class Eigen_traits_spd_solver : public Spd_solver
{
public:
  explicit Eigen_traits_spd_solver(const Traits& t = Traits()) : m_traits(t) {}
  bool factor(const Sparse_matrix& A) override
  {
    const Dynamic_openmp_threads dynamic_threads;
    auto& s = m_traits.solver();
    if(!m_pattern.matches(A)) {
      if(m_effort == Ordering_effort::fast) ask_for_minimum_degree_ordering(s);
      s.analyzePattern(A);
      m_pattern.remember(A);
    }
    s.factorize(A);
    return s.info() == Eigen::Success;
  }
  bool solve(const Matrix& B, Matrix& X) override
  {
    X = m_traits.solver().solve(B);
    return m_traits.solver().info() == Eigen::Success && X.allFinite();
  }
  /// A solver of its own (a copy of the traits would share the Eigen solver,
  /// hence the factorization) with the user's settings.
  std::unique_ptr<Spd_solver> clone() const override
  {
    Traits fresh;
    copy_eigen_solver_settings(const_cast<Traits&>(m_traits).solver(), fresh.solver());
    std::unique_ptr<Spd_solver> copy(new Eigen_traits_spd_solver<Traits>(fresh));
    copy->set_ordering_effort(m_effort);
    return copy;
  }
  void set_ordering_effort(Ordering_effort effort) override { m_effort = effort; }
  /// The traits (for tests: the settings a clone keeps).
  const Traits& traits() const { return m_traits; }

private:
  /// CHOLMOD's default choice of ordering (`nmethods` 0) computes the
  /// minimum-degree ordering (AMD) and, when its fill is high (mesh
  /// Laplacians somewhere between 100,000 and 1M faces and up), a METIS
  /// ordering as well, and keeps the better one. For one or two
  /// factorizations METIS costs more than the numeric work it saves: on a
  /// 1M-face Laplacian (one core, busy machine) AMD analysis 0.4 s + numeric
  /// 2.0-3.4 s, METIS 3.3-4.0 s + numeric 1.9-2.2 s (benchmark/RESULTS.md,
  /// "Speed at the floor"). So with `Ordering_effort::fast`, unless the user
  /// chose the methods (`nmethods` not 0), the package asks for AMD alone;
  /// where CHOLMOD would not try METIS this is exactly its own choice.
  template <class Solver>
  static void ask_for_minimum_degree_ordering(Solver& s)
  {
#ifdef CGAL_DEM_USE_CHOLMOD
    if constexpr(Is_cholmod_solver<Solver>::value) {
      cholmod_common& c = s.cholmod();
      if(c.nmethods == 0) {
        c.nmethods = 1;
        c.method[0].ordering = CHOLMOD_AMD;
      }
    }
#endif
    (void)s;
  }

  Traits m_traits;
  Ordering_effort m_effort = Ordering_effort::thorough;
  Sparsity_pattern m_pattern;
};

/// Adapter for any other model of `SparseLinearAlgebraWithFactorTraits_d`.
template <class Traits>
class Generic_traits_spd_solver : public Spd_solver
{
  typedef typename Traits::Matrix TMatrix;
  typedef typename Traits::Vector TVector;
  typedef typename Traits::NT NT;
public:
  explicit Generic_traits_spd_solver(const Traits& t = Traits()) : m_traits(t) {}
  bool factor(const Sparse_matrix& A) override
  {
    m_matrix.reset(new TMatrix(static_cast<std::size_t>(A.rows())));
    for(int c = 0; c < A.outerSize(); ++c)
      for(Sparse_matrix::InnerIterator it(A, c); it; ++it) m_matrix->set_coef(it.row(), it.col(), it.value(), true);
    NT D;
    return m_traits.factor(*m_matrix, D);
  }
  bool solve(const Matrix& B, Matrix& X) override
  {
    X.resize(B.rows(), B.cols());
    for(Eigen::Index c = 0; c < B.cols(); ++c) {
      TVector b(B.rows()), x(B.rows());
      for(Eigen::Index i = 0; i < B.rows(); ++i) b.set(i, B(i, c));
      if(!m_traits.linear_solver(b, x)) return false;
      for(Eigen::Index i = 0; i < B.rows(); ++i) X(i, c) = x(i);
    }
    return X.allFinite();
  }
  /// A copy of the user's traits object, with its settings (a model of the
  /// concept holds its state by value).
  std::unique_ptr<Spd_solver> clone() const override
  { return std::unique_ptr<Spd_solver>(new Generic_traits_spd_solver<Traits>(m_traits)); }
  /// The traits (for tests: the settings a clone keeps).
  const Traits& traits() const { return m_traits; }

private:
  Traits m_traits;
  std::unique_ptr<TMatrix> m_matrix;
};

template <class Traits>
std::unique_ptr<Spd_solver> make_spd_solver(const Traits& t)
{
  if constexpr(Is_eigen_solver_traits<Traits>::value)
    return std::unique_ptr<Spd_solver>(new Eigen_traits_spd_solver<Traits>(t));
  else
    return std::unique_ptr<Spd_solver>(new Generic_traits_spd_solver<Traits>(t));
}

inline std::unique_ptr<Spd_solver> make_default_spd_solver()
{ return make_spd_solver(Default_sparse_solver_traits()); }

/// A clone of `prototype` for a system whose pattern is factored once or twice.
inline std::unique_ptr<Spd_solver> clone_with_fast_ordering(const Spd_solver& prototype)
{
  std::unique_ptr<Spd_solver> s = prototype.clone();
  s->set_ordering_effort(Ordering_effort::fast);
  return s;
}

/// A sparse Cholesky factorization of an SPD matrix A whose ordering puts a
/// given set of unknowns, the *trailing* set T, last. Its leading block is
/// then the Cholesky factor of the principal submatrix A_RR on the other
/// unknowns R, so the one factorization solves both A x = b and A_RR x_R =
/// b_R (forward solve, the T part zeroed, backward solve): a Dirichlet
/// problem with T pinned costs two triangular solves instead of a second
/// factorization. The spherical conformal map uses it for its two systems,
/// which share the cotangent Laplacian (spherical_conformal.h).
///
/// CHOLMOD's supernodal LL^T with the constrained minimum-degree ordering
/// (CAMD, T in the last constraint set) and no postordering of the
/// elimination tree (which could move unknowns of R behind T). Only for the
/// package's default solver: the factory returns null for any other one,
/// and the caller factors twice through the user's solver.
class Factorization_with_trailing_set
{
public:
  virtual ~Factorization_with_trailing_set() = default;
  /// Factors A (full symmetric storage, compressed) with `trailing` (one flag
  /// per unknown) ordered last. False on failure or when the ordering did not
  /// keep T last (then nothing may be solved).
  virtual bool factor(const Sparse_matrix& A, const std::vector<char>& trailing) = 0;
  /// A X = B.
  virtual bool solve(const Matrix& B, Matrix& X) = 0;
  /// The two halves of solve_leading(), with A_RR = G G^T: Y = G^-1 B_R in
  /// the factorization's order of the unknowns (T's rows 0), and X =
  /// A_RR^-1 B_R from such a Y (its rows of T are ignored).
  virtual bool forward_leading(const Matrix& B, Matrix& Y) = 0;
  virtual bool backward_leading(const Matrix& Y, Matrix& X) = 0;
  /// A_RR X_R = B_R; the rows of T in B are ignored and are 0 in X.
  bool solve_leading(const Matrix& B, Matrix& X)
  {
    Matrix Y;
    return forward_leading(B, Y) && backward_leading(Y, X);
  }
};

#ifdef CGAL_DEM_USE_CHOLMOD
class Cholmod_factorization_with_trailing_set : public Factorization_with_trailing_set
{
public:
  explicit Cholmod_factorization_with_trailing_set(double shift = 0) : m_shift(shift)
  {
    cholmod_start(&m_common);
    m_common.nmethods = 1;
    m_common.method[0].ordering = CHOLMOD_GIVEN;
    m_common.postorder = 0;
    m_common.supernodal = CHOLMOD_SUPERNODAL;
    m_common.final_ll = 1;
  }
  ~Cholmod_factorization_with_trailing_set() override
  {
    if(m_factor) cholmod_free_factor(&m_factor, &m_common);
    cholmod_finish(&m_common);
  }
  Cholmod_factorization_with_trailing_set(const Cholmod_factorization_with_trailing_set&) = delete;
  Cholmod_factorization_with_trailing_set& operator=(const Cholmod_factorization_with_trailing_set&) = delete;

  bool factor(const Sparse_matrix& A, const std::vector<char>& trailing) override
  {
    const Dynamic_openmp_threads dynamic_threads;
    if(m_factor) cholmod_free_factor(&m_factor, &m_common);
    m_leading = 0;
    const int n = int(A.rows());
    if(!A.isCompressed() || A.cols() != n || trailing.size() != std::size_t(n)) return false;
    cholmod_sparse view = lower_view(A);
    std::vector<int> member(std::size_t(n), 0), perm(std::size_t(n), 0);
    for(int i = 0; i < n; ++i)
      if(trailing[std::size_t(i)]) member[std::size_t(i)] = 1; else ++m_leading;
    if(!cholmod_camd(&view, nullptr, 0, member.data(), perm.data(), &m_common) ||
       !postorder_each_block(view, perm))
      return false;
    m_factor = cholmod_analyze_p(&view, perm.data(), nullptr, 0, &m_common);
    if(!m_factor || m_common.status != CHOLMOD_OK) return false;
    // the ordering the factor uses must still have R first
    const int* used = static_cast<const int*>(m_factor->Perm);
    for(int k = 0; k < m_leading; ++k)
      if(trailing[std::size_t(used[k])]) return fail();
    if(!numeric_factorization(A)) return fail();
    m_trailing = trailing;
    return true;
  }

  bool solve(const Matrix& B, Matrix& X) override { return run({CHOLMOD_A}, B, X, false); }

  bool forward_leading(const Matrix& B, Matrix& Y) override { return run({CHOLMOD_P, CHOLMOD_L}, B, Y, true); }

  bool backward_leading(const Matrix& Y, Matrix& X) override
  {
    if(!m_factor || Y.rows() != Eigen::Index(m_factor->n)) return false;
    Matrix leading = Y;
    leading.bottomRows(leading.rows() - m_leading).setZero();
    return run({CHOLMOD_Lt, CHOLMOD_Pt}, leading, X, false);
  }

  /// The numeric factorization of A, whose sparsity pattern must be that of
  /// the last successful `factor()`, on its ordering and symbolic analysis.
  bool refactor(const Sparse_matrix& A)
  {
    if(!m_factor || A.rows() != Eigen::Index(m_factor->n)) return false;
    const Dynamic_openmp_threads dynamic_threads;
    if(numeric_factorization(A)) return true;
    fail();
    return false;
  }

  /// Y = L^{-1} P B: the forward half of a solve, in the factor's order of
  /// the unknowns (T last). This and `backward()` run on the factor's
  /// supernodes with Eigen's dense kernels, without CHOLMOD or the BLAS
  /// (whose single-threaded builds must not be entered from two threads at
  /// once), as fast as CHOLMOD's own solve (1M faces: 0.094 against
  /// 0.087-0.100 s, benchmark/RESULTS.md): several threads may solve with
  /// one factorization, or with several, at the same time.
  bool forward(const Matrix& B, Matrix& Y) const
  {
    if(!m_factor || B.rows() != Eigen::Index(m_factor->n)) return false;
    const int* perm = static_cast<const int*>(m_factor->Perm);
    Y.resize(B.rows(), B.cols());
    for(Eigen::Index k = 0; k < B.rows(); ++k) Y.row(k) = B.row(perm[k]);
    const Supernodes L(*m_factor);
    Vector update;
    for(Eigen::Index c = 0; c < Y.cols(); ++c) { // column by column: matrix-vector kernels
      double* y = Y.col(c).data();
      for(std::size_t s = 0; s < L.count; ++s) {
        const auto block = L.block(s);
        const int width = L.width(s), below = int(block.rows()) - width;
        Eigen::Map<Vector> y_s(y + L.first_column(s), width);
        y_s = block.topRows(width).triangularView<Eigen::Lower>().solve(y_s);
        if(below == 0) continue;
        update.noalias() = block.bottomRows(below) * y_s;
        const int* rows = L.rows_below(s);
        for(int r = 0; r < below; ++r) y[rows[r]] -= update[r];
      }
    }
    return Y.allFinite();
  }

  /// X = P^T L^{-T} Y: the backward half, from the factor's order.
  bool backward(const Matrix& Y, Matrix& X) const
  {
    if(!m_factor || Y.rows() != Eigen::Index(m_factor->n)) return false;
    Matrix Z = Y;
    const Supernodes L(*m_factor);
    Vector gathered;
    for(Eigen::Index c = 0; c < Z.cols(); ++c) {
      double* z = Z.col(c).data();
      for(std::size_t s = L.count; s-- > 0;) {
        const auto block = L.block(s);
        const int width = L.width(s), below = int(block.rows()) - width;
        Eigen::Map<Vector> z_s(z + L.first_column(s), width);
        if(below > 0) {
          gathered.resize(below);
          const int* rows = L.rows_below(s);
          for(int r = 0; r < below; ++r) gathered[r] = z[rows[r]];
          z_s.noalias() -= block.bottomRows(below).transpose() * gathered;
        }
        z_s = block.topRows(width).transpose().triangularView<Eigen::Upper>().solve(z_s);
      }
    }
    const int* perm = static_cast<const int*>(m_factor->Perm);
    X.resize(Z.rows(), Z.cols());
    for(Eigen::Index k = 0; k < Z.rows(); ++k) X.row(perm[k]) = Z.row(k);
    return X.allFinite();
  }

  /// The supernodes of a supernodal LL^T factor: supernode s holds the
  /// columns first_column(s) .. first_column(s) + width(s) - 1 as one dense
  /// column-major block whose rows are those columns (the diagonal block,
  /// lower triangular) followed by the rows `rows_below(s)`.
  struct Supernodes
  {
    explicit Supernodes(const cholmod_factor& L)
      : count(L.nsuper), super(static_cast<const int*>(L.super)), row_start(static_cast<const int*>(L.pi)),
        value_start(static_cast<const int*>(L.px)), rows(static_cast<const int*>(L.s)),
        values(static_cast<const double*>(L.x)) {}
    int first_column(std::size_t s) const { return super[s]; }
    int width(std::size_t s) const { return super[s + 1] - super[s]; }
    Eigen::Map<const Matrix> block(std::size_t s) const
    { return Eigen::Map<const Matrix>(values + value_start[s], row_start[s + 1] - row_start[s], width(s)); }
    const int* rows_below(std::size_t s) const { return rows + row_start[s] + width(s); }

    std::size_t count;
    const int *super, *row_start, *value_start, *rows;
    const double* values;
  };

  /// The trailing diagonal block D of the factor L (the columns and rows of
  /// T, lower triangular, dense) and, for each of its positions, the index of
  /// the unknown among T's (T's unknowns numbered in increasing order).
  /// D D^T is the Schur complement of A onto T.
  void trailing_block(Matrix& D, std::vector<int>& trailing_index) const
  {
    const int n = int(m_factor->n), t = n - m_leading;
    D.setZero(t, t);
    trailing_index.assign(static_cast<std::size_t>(t), 0);
    std::vector<int> rank(static_cast<std::size_t>(n), -1); // unknown -> its index among T's
    for(int i = 0, r = 0; i < n; ++i)
      if(m_trailing[std::size_t(i)]) rank[std::size_t(i)] = r++;
    const int* perm = static_cast<const int*>(m_factor->Perm);
    for(int p = 0; p < t; ++p) trailing_index[std::size_t(p)] = rank[std::size_t(perm[m_leading + p])];
    const Supernodes L(*m_factor);
    for(std::size_t s = 0; s < L.count; ++s) {
      const int first = L.first_column(s), end = first + L.width(s);
      if(end <= m_leading) continue;
      const auto block = L.block(s);
      const int* rows = L.rows_below(s) - L.width(s); // the supernode's rows, its own columns first
      for(int col = std::max(first, m_leading); col < end; ++col)
        for(Eigen::Index r = col - first; r < block.rows(); ++r) // from the diagonal down
          D(rows[r] - m_leading, col - m_leading) = block(r, col - first);
    }
  }

private:
  bool numeric_factorization(const Sparse_matrix& A)
  {
    cholmod_sparse view = lower_view(A);
    double beta[2] = {m_shift, 0};
    return cholmod_factorize_p(&view, beta, nullptr, 0, m_factor, &m_common) && m_common.status == CHOLMOD_OK &&
           m_factor->minor == m_factor->n;
  }

  bool fail()
  {
    if(m_factor) cholmod_free_factor(&m_factor, &m_common);
    return false;
  }

  /// Postorders the elimination tree of the permuted matrix within R and
  /// within T, R first: an ordering that keeps every node after its
  /// descendants has the same fill, and a postorder makes the chains of the
  /// tree contiguous, hence large supernodes (the numeric factorization of a
  /// 100K-face Laplacian takes 0.20 s without it, 0.175 s with it). CHOLMOD's
  /// own postorder would interleave R and T. A node of T is never a
  /// descendant of one of R (a parent comes later), so cutting R's links to
  /// parents in T leaves two forests.
  bool postorder_each_block(cholmod_sparse& view, std::vector<int>& perm)
  {
    const int n = int(view.nrow);
    cholmod_sparse* permuted = cholmod_ptranspose(&view, 0, perm.data(), nullptr, 0, &m_common); // upper
    if(!permuted) return false;
    // CHOLMOD's own analysis: the tree, a postorder, the column counts of the
    // factor, and a postorder weighted by them (each node's heaviest child
    // last); here with the links from R to T cut before the weighted one
    const std::size_t size = static_cast<std::size_t>(n);
    std::vector<int> parent(size), post(size), column_count(size), first(size), level(size);
    cholmod_sparse* lower = cholmod_transpose(permuted, 0, &m_common); // rowcolcounts reads this form
    const bool ok = lower && cholmod_etree(permuted, parent.data(), &m_common) &&
                    cholmod_postorder(parent.data(), size, nullptr, post.data(), &m_common) == n &&
                    cholmod_rowcolcounts(lower, nullptr, 0, parent.data(), post.data(), nullptr,
                                         column_count.data(), first.data(), level.data(), &m_common);
    cholmod_free_sparse(&permuted, &m_common);
    if(lower) cholmod_free_sparse(&lower, &m_common);
    if(!ok) return false;
    for(int j = 0; j < m_leading; ++j)
      if(parent[std::size_t(j)] >= m_leading) parent[std::size_t(j)] = -1;
    if(cholmod_postorder(parent.data(), size, column_count.data(), post.data(), &m_common) != n) return false;
    std::vector<int> postordered(static_cast<std::size_t>(n));
    for(int k = 0; k < n; ++k) postordered[std::size_t(k)] = perm[std::size_t(post[std::size_t(k)])];
    perm.swap(postordered);
    return true;
  }

  static cholmod_sparse lower_view(const Sparse_matrix& A)
  {
    cholmod_sparse v;
    v.nrow = v.ncol = std::size_t(A.rows());
    v.nzmax = std::size_t(A.nonZeros());
    v.p = const_cast<int*>(A.outerIndexPtr());
    v.i = const_cast<int*>(A.innerIndexPtr());
    v.x = const_cast<double*>(A.valuePtr());
    v.z = nullptr; v.nz = nullptr;
    v.stype = -1; // the lower triangle is read
    v.itype = CHOLMOD_INT; v.xtype = CHOLMOD_REAL; v.dtype = CHOLMOD_DOUBLE;
    v.sorted = 1; v.packed = 1;
    return v;
  }

  /// Applies the CHOLMOD solves `steps` in turn to B; with `leading`, the
  /// permuted vector's trailing rows are zeroed between the triangular solves
  /// (L y = P b restricted to R is y_R = L_RR^{-1} (P b)_R).
  bool run(std::initializer_list<int> steps, const Matrix& B, Matrix& X, bool leading)
  {
    if(!m_factor) return false;
    Matrix current = B;
    for(int sys : steps) {
      cholmod_dense in;
      in.nrow = std::size_t(current.rows()); in.ncol = std::size_t(current.cols());
      in.nzmax = in.nrow * in.ncol; in.d = in.nrow;
      in.x = current.data(); in.z = nullptr;
      in.xtype = CHOLMOD_REAL; in.dtype = CHOLMOD_DOUBLE;
      cholmod_dense* out = cholmod_solve(sys, m_factor, &in, &m_common);
      if(!out) return false;
      current = Eigen::Map<const Matrix>(static_cast<const double*>(out->x), current.rows(), current.cols());
      cholmod_free_dense(&out, &m_common);
      if(leading && (sys == CHOLMOD_P || sys == CHOLMOD_L)) current.bottomRows(current.rows() - m_leading).setZero();
    }
    X.swap(current);
    return X.allFinite();
  }

  cholmod_common m_common;
  cholmod_factor* m_factor = nullptr;
  double m_shift;
  int m_leading = 0;
  std::vector<char> m_trailing;
};
#endif

/// Two solvers and a size: systems of fewer than `large_from` unknowns go
/// to `small`, the others to `large`. For the lagged factorization of the
/// diffusion systems: a simplicial LDL^T is the cheapest below a few ten
/// thousand unknowns (its triangular solves, applied several times per
/// iteration, have no supernode overhead), but its factorization has no
/// dense kernels and grows far faster than a supernodal one (1M faces:
/// about 30 s against 2-3 s, benchmark/RESULTS.md).
class Size_dispatched_spd_solver : public Spd_solver
{
public:
  Size_dispatched_spd_solver(std::unique_ptr<Spd_solver> small, std::unique_ptr<Spd_solver> large,
                             Eigen::Index large_from)
    : m_small(std::move(small)), m_large(std::move(large)), m_large_from(large_from) {}

  void set_ordering_effort(Ordering_effort effort) override
  {
    m_small->set_ordering_effort(effort);
    m_large->set_ordering_effort(effort);
  }
  bool factor(const Sparse_matrix& A) override
  {
    m_active = A.rows() < m_large_from ? m_small.get() : m_large.get();
    return m_active->factor(A);
  }
  bool solve(const Matrix& B, Matrix& X) override { return m_active && m_active->solve(B, X); }
  std::unique_ptr<Spd_solver> clone() const override
  {
    return std::unique_ptr<Spd_solver>(
      new Size_dispatched_spd_solver(m_small->clone(), m_large->clone(), m_large_from));
  }
  /// The solver that factored the last matrix (none before the first).
  const Spd_solver* active() const { return m_active; }

private:
  std::unique_ptr<Spd_solver> m_small, m_large;
  Eigen::Index m_large_from;
  Spd_solver* m_active = nullptr;
};

/// The factorization with a trailing set when `prototype` is the package's default solver
/// (with its shift); null otherwise (a user's solver, or no CHOLMOD).
inline std::unique_ptr<Factorization_with_trailing_set> factorization_with_trailing_set_like(const Spd_solver& prototype)
{
#ifdef CGAL_DEM_USE_CHOLMOD
  typedef Eigen_traits_spd_solver<Default_sparse_solver_traits> Default_solver;
  if(const Default_solver* d = dynamic_cast<const Default_solver*>(&prototype)) {
    auto& eigen_solver = const_cast<Default_sparse_solver_traits&>(d->traits()).solver();
    return std::unique_ptr<Factorization_with_trailing_set>(new Cholmod_factorization_with_trailing_set(
      Eigen_solver_protected_settings<Default_sparse_solver_traits::Solver>::cholmod_shift(eigen_solver)));
  }
#endif
  (void)prototype;
  return nullptr;
}

/// Solver of the diffusion systems (A + dt L) rho+ = A rho of the
/// density-equalizing engine, one per iteration on a slowly moving mesh:
/// preconditioned conjugate gradients started from the linear extrapolation
/// of the two previous solutions (the diffused density changes smoothly, so
/// the error of that guess lies in the smooth modes). The preconditioner
/// depends on the size:
///  - small systems: Jacobi. Matrix-vector products are so cheap that a few
///    dozen of them beat any triangular solve.
///  - larger systems: a Cholesky factorization of an *earlier* matrix of the
///    sequence, an excellent preconditioner for the nearby current one (a
///    handful of steps). It is redone for the next matrix when a solve
///    needed more than `refactor_iterations` steps, and at once, for the
///    matrix being solved, when a solve reaches twice as many on it: a
///    factorization that far off would otherwise run up to its step budget
///    (twistedball SDEM spent 100 and 92 steps in its second and third
///    solves). Refactoring at once on every slow solve instead was measured
///    worse: the first steps of a flow move the mesh most, and the matrix
///    of a slow solve is soon stale too (SDEM at 1M faces: 6-10 steps per
///    solve after it instead of 4-7, +10 % time).
/// Relative residual 1e-8: far below what the velocity and the stopping tests
/// (1e-3 and above) resolve.
class Diffusion_pcg_solver : public Spd_solver
{
public:
  /// Refinements of the behaviour above for one method's systems, all off by
  /// default (they change the iterates by round-off or the preconditioner).
  struct Tuning
  {
    /// The matrices are exactly symmetric (a Face_block_assembler's: entries
    /// (i,j) and (j,i) receive the same terms in the same order), so a
    /// product gathers row i from the stored column i instead of scattering
    /// column i (tdem_torus_4: the lagged-factorization CG 8 % faster), and
    /// the Jacobi steps run in three fused passes over the unknowns (product
    /// with its dot product; x, r, z with both reductions; p) instead of
    /// Eigen's separate expressions and temporaries.
    bool fused_jacobi = false;
    /// Start from the quadratic extrapolation of the last three solutions
    /// (exact for densities that change quadratically in time, as they do
    /// away from repairs).
    bool quadratic_extrapolation = false;
    /// Give up Jacobi for the lagged factorization for good once a Jacobi
    /// solve needs more than this many steps (0: never): on strongly graded
    /// meshes (cells whose mass is far below their stiffness) Jacobi needs
    /// dozens of steps where the lagged factorization needs a few.
    int jacobi_step_limit = 0;
    /// Refactor the lagged factorization once a solve needs more than this
    /// many steps (0: the constructor's `refactor_iterations`).
    int refactor_steps = 0;
  };

  /// CG steps allowed to one solve preconditioned by a factorization. It
  /// needs a handful (the exact factorization of the matrix itself one or
  /// two); one that needs more is stale, and is redone (run()), or broken,
  /// and the solve fails rather than running for minutes (a million
  /// unknowns: 0.1 s a step, and Jacobi's budget would allow 500,000 steps).
  static constexpr int factorization_step_budget = 100;

  explicit Diffusion_pcg_solver(std::unique_ptr<Spd_solver> direct, Eigen::Index jacobi_below = 4000,
                                double tolerance = 1e-8, int refactor_iterations = 12)
    : m_direct(std::move(direct)), m_jacobi_below(jacobi_below), m_tolerance(tolerance),
      m_refactor_iterations(refactor_iterations) {}

  void tune(const Tuning& tuning)
  {
    m_tuning = tuning;
    if(tuning.refactor_steps > 0) m_refactor_iterations = tuning.refactor_steps;
  }

  bool factor(const Sparse_matrix& A) override
  {
    m_A = &A;
    if(A.rows() < m_jacobi_below && !m_jacobi_given_up) {
      const Vector diagonal = A.diagonal(); // a search per column: extract it once
      m_inverse_diagonal = diagonal.cwiseInverse();
      return m_inverse_diagonal.allFinite() && (diagonal.array() > 0).all();
    }
    m_inverse_diagonal.resize(0);
    if(m_factored && m_rows == A.rows() && m_last_iterations <= m_refactor_iterations) return true;
    return refactor();
  }

  /// The next system of the sequence: starts from the extrapolation of the
  /// previous two solutions, and its cost decides the next refactorization.
  bool solve(const Matrix& B, Matrix& X) override
  {
    auto known = [&B](const Matrix& Y) { return Y.rows() == B.rows() && Y.cols() == B.cols(); };
    Matrix guess = Matrix::Zero(B.rows(), B.cols());
    if(m_tuning.quadratic_extrapolation && known(m_last) && known(m_before_last) && known(m_third_last))
      guess = 3 * (m_last - m_before_last) + m_third_last;
    else if(known(m_last))
      guess = known(m_before_last) ? Matrix(2 * m_last - m_before_last) : m_last;
    int iterations = 0;
    if(!run(B, X, guess, iterations, Refactoring::when_far_off)) return false;
    m_last_iterations = iterations;
    // judged on warm-started solves only: the first ones start far off
    if(m_tuning.jacobi_step_limit > 0 && m_inverse_diagonal.size() == B.rows() && known(m_before_last) &&
       iterations > m_tuning.jacobi_step_limit)
      m_jacobi_given_up = true;
    if(m_tuning.quadratic_extrapolation) m_third_last.swap(m_before_last);
    m_before_last.swap(m_last);
    m_last = X;
    return true;
  }

  /// A side system near the sequence (EDEQ's radius candidates): starts from
  /// `guess` and leaves the sequence's history and factorization policy alone.
  bool solve(const Matrix& B, Matrix& X, const Matrix& guess) override
  {
    int iterations = 0;
    return run(B, X, guess, iterations, Refactoring::on_failure_only);
  }

  std::unique_ptr<Spd_solver> clone() const override
  {
    std::unique_ptr<Diffusion_pcg_solver> copy(
      new Diffusion_pcg_solver(m_direct->clone(), m_jacobi_below, m_tolerance, m_refactor_iterations));
    copy->tune(m_tuning);
    return copy;
  }

private:
  /// Whether a solve redoes a lagged factorization far from its matrix as
  /// soon as it has taken twice `m_refactor_iterations` steps on it (the
  /// sequence's solves), or only after failing (a side system, which leaves
  /// the sequence's factorization alone when it can).
  enum class Refactoring { when_far_off, on_failure_only };

  /// CG with the current preconditioner; if it misses the tolerance within
  /// its step budget (Jacobi on meshes with sliver faces, whose cotangent
  /// weights reach 1e4 times the mass: the system is too ill-conditioned for
  /// it; or a lagged factorization too far from this matrix), the exact
  /// factorization of this very matrix, for good (Jacobi is given up).
  bool run(const Matrix& B, Matrix& X, const Matrix& guess, int& iterations, Refactoring refactoring)
  {
    if(preconditioned_run(B, X, guess, iterations, refactoring)) return true;
    if(m_A == nullptr) return false;
    m_inverse_diagonal.resize(0);
    m_jacobi_given_up = true;
    return refactor() && preconditioned_run(B, X, guess, iterations, refactoring);
  }

  /// A new factorization of the current matrix.
  bool refactor()
  {
    m_factored = m_direct->factor(*m_A);
    m_rows = m_A->rows();
    return m_factored;
  }

  bool preconditioned_run(const Matrix& B, Matrix& X, const Matrix& guess, int& iterations, Refactoring refactoring)
  {
    X.resize(B.rows(), B.cols());
    iterations = 0;
    const bool fused = m_tuning.fused_jacobi && preconditioned_by_jacobi(B.rows());
    for(Eigen::Index c = 0; c < B.cols(); ++c) {
      Vector x = guess.col(c);
      const int k = fused ? fused_jacobi_cg(B.col(c), x) : preconditioned_cg(B.col(c), x, refactoring);
      if(k < 0) return false;
      iterations = std::max(iterations, k);
      X.col(c) = x;
    }
    return X.allFinite();
  }

  /// Returns the number of steps, or -1 if the residual did not fall below
  /// the tolerance within the step budget.
  int preconditioned_cg(const Vector& b, Vector& x, Refactoring refactoring)
  {
    const Sparse_matrix& A = *m_A;
    auto product = [&](const Vector& v, Vector& Av) {
      if(m_tuning.fused_jacobi) Av.noalias() = A.transpose() * v; // = A v, by rows
      else Av.noalias() = A * v;
    };
    const double stop = m_tolerance * b.norm();
    Vector& Ap = m_Ap;
    product(x, Ap);
    Vector& r = m_r;
    Vector& z = m_z;
    r = b - Ap;
    if(r.norm() <= stop) return 0;
    precondition(r, z);
    Vector& p = m_p;
    p = z;
    double rz = r.dot(z);
    const int budget = step_budget(A.rows());
    const bool refactor_when_far_off = refactoring == Refactoring::when_far_off && !preconditioned_by_jacobi(A.rows());
    for(int k = 1, on_this_factorization = 0; k <= budget; ++k, ++on_this_factorization) {
      if(refactor_when_far_off && on_this_factorization == 2 * m_refactor_iterations) {
        if(!refactor()) return -1;
        on_this_factorization = 0; // CG restarts from x, preconditioned by the new factorization
        product(x, Ap);
        r = b - Ap;
        precondition(r, z);
        p = z;
        rz = r.dot(z);
      }
      product(p, Ap);
      const double alpha = rz / p.dot(Ap);
      x += alpha * p;
      r -= alpha * Ap;
      if(r.norm() <= stop) return k;
      precondition(r, z);
      const double rz_new = r.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
    }
    return -1;
  }

  /// preconditioned_cg() with the Jacobi preconditioner in fused passes (Tuning::fused_jacobi).
  int fused_jacobi_cg(const Vector& b, Vector& x)
  {
    const Sparse_matrix& A = *m_A;
    const Eigen::Index n = A.rows();
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* value = A.valuePtr();
    const double* d = m_inverse_diagonal.data();
    // row i of the symmetric A times v, from the stored column i
    auto row_times = [&](Eigen::Index i, const double* v) {
      double s = 0;
      for(int q = outer[i]; q < outer[i + 1]; ++q) s += value[q] * v[inner[q]];
      return s;
    };
    m_r.resize(n); m_z.resize(n); m_p.resize(n); m_Ap.resize(n);
    double* r = m_r.data(); double* z = m_z.data(); double* p = m_p.data(); double* Ap = m_Ap.data();
    double* xv = x.data();
    const double stop_squared = m_tolerance * m_tolerance * b.squaredNorm();
    double rr = 0, rz = 0;
    for(Eigen::Index i = 0; i < n; ++i) {
      r[i] = b[i] - row_times(i, xv);
      z[i] = p[i] = d[i] * r[i];
      rr += r[i] * r[i];
      rz += r[i] * z[i];
    }
    if(rr <= stop_squared) return 0;
    const int budget = step_budget(n);
    for(int k = 1; k <= budget; ++k) {
      double pAp = 0;
      for(Eigen::Index i = 0; i < n; ++i) {
        Ap[i] = row_times(i, p);
        pAp += p[i] * Ap[i];
      }
      const double alpha = rz / pAp;
      double rz_new = 0;
      rr = 0;
      for(Eigen::Index i = 0; i < n; ++i) {
        xv[i] += alpha * p[i];
        r[i] -= alpha * Ap[i];
        z[i] = d[i] * r[i];
        rr += r[i] * r[i];
        rz_new += r[i] * z[i];
      }
      if(rr <= stop_squared) return k;
      const double beta = rz_new / rz;
      for(Eigen::Index i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
      rz = rz_new;
    }
    return -1;
  }

  /// z = P^{-1} r. The lagged factorization's solve takes and fills n x 1
  /// matrices: they are kept, so a CG step copies no vector.
  bool preconditioned_by_jacobi(Eigen::Index n) const { return m_inverse_diagonal.size() == n; }

  /// CG steps allowed to one solve: Jacobi may need many (as many as
  /// unknowns, at least 1,000), a factorization a handful.
  int step_budget(Eigen::Index n) const
  { return preconditioned_by_jacobi(n) ? std::max<int>(1000, static_cast<int>(n)) : factorization_step_budget; }

  void precondition(const Vector& r, Vector& z)
  {
    if(preconditioned_by_jacobi(r.size())) { z = m_inverse_diagonal.cwiseProduct(r); return; }
    m_residual_column = r;
    m_direct->solve(m_residual_column, m_preconditioned_column);
    z = m_preconditioned_column.col(0);
  }

  std::unique_ptr<Spd_solver> m_direct;
  Eigen::Index m_jacobi_below;
  double m_tolerance;
  int m_refactor_iterations;
  int m_last_iterations = 0; // steps of the sequence's last solve
  Tuning m_tuning;
  bool m_jacobi_given_up = false;
  Vector m_r, m_z, m_p, m_Ap; // work vectors of the CG loops
  Matrix m_residual_column, m_preconditioned_column; // n x 1, for the lagged factorization's solve
  const Sparse_matrix* m_A = nullptr;
  Vector m_inverse_diagonal;
  bool m_factored = false;
  Eigen::Index m_rows = 0;
  Matrix m_last, m_before_last, m_third_last;
};

/// Dirichlet conditions by symmetric elimination that keeps the sparsity
/// pattern: for a fixed j, rhs_i -= K_ij w_j for every free i, then row and
/// column j become the identity and rhs_j = w_j. The reduced matrix is SPD
/// whenever K restricted to the free vertices is.
inline void apply_dirichlet(Sparse_matrix& K, Matrix& rhs, const std::vector<char>& is_fixed, const Matrix& fixed_values)
{
  double* v = K.valuePtr();
  const int* inner = K.innerIndexPtr();
  const int* outer = K.outerIndexPtr();
  for(int c = 0; c < K.outerSize(); ++c)
    for(int p = outer[c]; p < outer[c + 1]; ++p) {
      const int r = inner[p];
      if(!is_fixed[c] && !is_fixed[r]) continue;
      if(is_fixed[c] && !is_fixed[r]) rhs.row(r) -= v[p] * fixed_values.row(c);
      v[p] = (r == c) ? 1. : 0.;
    }
  for(Eigen::Index i = 0; i < rhs.rows(); ++i)
    if(is_fixed[i]) rhs.row(i) = fixed_values.row(i);
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPARSE_SOLVER_H
