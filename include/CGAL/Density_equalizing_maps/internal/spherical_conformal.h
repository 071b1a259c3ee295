// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_CONFORMAL_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_CONFORMAL_H

// FLASH-style spherical conformal map (ALGORITHMS.md section 3) and the
// Moebius area correction (section 4), on index arrays.

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/ellipsoid_domain.h>
#include <CGAL/Density_equalizing_maps/internal/fold_overs.h>
#include <CGAL/Density_equalizing_maps/internal/projections.h>
#include <CGAL/Density_equalizing_maps/internal/stages.h>

#include <algorithm>
#include <array>
#include <functional>
#include <numeric>
#include <queue>
#include <sstream>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

struct Flash_result
{
  Matrix S;                 // n x 3, on the unit sphere
  Complex_vector south_w;   // the south-chart coordinates after the LBS step (S = (P^S)^{-1}(w))
  Eigen::Index north_face = 0;
  bool tutte = false;
  std::string fallback;     // empty, or which fallback was taken (Map_report::fallback)
  std::size_t repairs = 0;  // Beltrami repairs of the fallback start
};

/// The system of the harmonic map of the mesh punctured at face `t` onto the
/// plane: the three corners of `t` pinned at `corners` (big-triangle
/// boundary), the rest solves L z = 0. Modifies `L` in place.
inline void punctured_harmonic_system(Sparse_matrix& L, const Index_matrix& F, Eigen::Index t,
                                      const Complex corners[3], Matrix& rhs)
{
  const Eigen::Index n = L.rows();
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  Matrix values = Matrix::Zero(n, 2);
  rhs = Matrix::Zero(n, 2);
  for(int a = 0; a < 3; ++a) {
    fixed[F(t, a)] = 1;
    values(F(t, a), 0) = corners[a].real();
    values(F(t, a), 1) = corners[a].imag();
  }
  apply_dirichlet(L, rhs, fixed, values);
}

inline bool complex_solution(const Matrix& sol, Complex_vector& z)
{
  z.resize(sol.rows());
  for(Eigen::Index i = 0; i < sol.rows(); ++i) z[i] = Complex(sol(i, 0), sol(i, 1));
  return z.allFinite();
}

/// Harmonic map of the mesh punctured at face `t` onto the plane
/// (punctured_harmonic_system()). `L` is taken by value and modified in place
/// (one matrix alive, not two).
inline bool punctured_harmonic_map(Sparse_matrix L, const Index_matrix& F, Eigen::Index t,
                                   const Complex corners[3], Spd_solver& solver, Complex_vector& z)
{
  Matrix rhs, sol;
  punctured_harmonic_system(L, F, t, corners, rhs);
  if(!solver.factor(L) || !solver.solve(rhs, sol)) return false;
  return complex_solution(sol, z);
}

/// The south cap of FLASH chosen *before* the north step, so that one
/// factorization serves both steps: the `m` vertices farthest from the
/// corners of the north face `t` along the mesh's edges (Dijkstra over edge
/// lengths; the neighbours are the off-diagonal entries of `adjacency`, the
/// Laplacian's pattern). FLASH's own cap,
/// the m vertices of lowest height after the north step, is known only after
/// the first factorization. Both are far from the puncture, where the north
/// step's map is accurate, which is all the south step asks of its cap.
struct South_cap
{
  std::vector<char> member;     // one flag per vertex
  Eigen::Index deepest = -1;    // the farthest vertex: it goes to the south pole
};

inline South_cap farthest_vertices_from_face(const Matrix& X, const Sparse_matrix& adjacency, const Index_matrix& F,
                                             Eigen::Index t, Eigen::Index m)
{
  const Eigen::Index n = X.rows();
  std::vector<double> distance(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  typedef std::pair<double, int> Entry;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry> > front;
  for(int a = 0; a < 3; ++a) { distance[F(t, a)] = 0; front.emplace(0., F(t, a)); }
  while(!front.empty()) {
    const Entry e = front.top();
    front.pop();
    if(e.first > distance[e.second]) continue;
    for(Sparse_matrix::InnerIterator it(adjacency, e.second); it; ++it) {
      const int j = int(it.row());
      const double d = e.first + (row3(X, j) - row3(X, e.second)).norm();
      if(d < distance[j]) { distance[j] = d; front.emplace(d, j); }
    }
  }
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  const auto farther = [&](int i, int j) { return distance[i] > distance[j] || (distance[i] == distance[j] && i < j); };
  std::nth_element(order.begin(), order.begin() + (m - 1), order.end(), farther);
  South_cap cap;
  cap.member.assign(static_cast<std::size_t>(n), 0);
  cap.deepest = *std::min_element(order.begin(), order.begin() + m, farther);
  for(Eigen::Index k = 0; k < m; ++k) cap.member[order[k]] = 1;
  return cap;
}

inline double mean_side(const Complex a, const Complex b, const Complex c)
{
  return (std::abs(a - b) + std::abs(b - c) + std::abs(c - a)) / 3.;
}

/// The south chart of the south step: the north step's sphere S turned so
/// that the cap's deepest vertex is next to the south pole, in the south
/// stereographic chart, where the cap is the outer region and the puncture
/// sits near the centre. The vertices to pin: the cap, and the corners of
/// the faces straddling the south pole (inverted in the chart).
struct South_chart
{
  Eigen::Matrix3d turn;     // S -> turned sphere
  Matrix P;                 // n x 2 chart coordinates
  std::vector<char> pinned; // the cap and the straddling faces' corners
  bool pinned_is_cap = true;
};

/// The turn that takes the centre of a face at the cap's deepest vertex to
/// the south pole (a vertex there would be at infinity in the chart).
inline Eigen::Matrix3d turn_to_south_pole(const Matrix& S, const Index_matrix& F, const South_cap& cap)
{
  Eigen::Index pole_face = 0;
  while(F(pole_face, 0) != cap.deepest && F(pole_face, 1) != cap.deepest && F(pole_face, 2) != cap.deepest) ++pole_face;
  return rotation_to_north_pole(-(row_vector3(S, F(pole_face, 0)) + row_vector3(S, F(pole_face, 1)) +
                                  row_vector3(S, F(pole_face, 2))));
}

/// FLASH's own cap: the m vertices of lowest height of the north step's sphere.
inline South_cap lowest_vertices(const Matrix& S, Eigen::Index m)
{
  std::vector<Eigen::Index> order(static_cast<std::size_t>(S.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index i, Eigen::Index j) { return S(i, 2) < S(j, 2); });
  South_cap cap;
  cap.member.assign(order.size(), 0);
  for(Eigen::Index k = 0; k < m; ++k) cap.member[order[k]] = 1;
  cap.deepest = order[0];
  return cap;
}

inline South_chart south_chart_of(const Matrix& S, const Index_matrix& F, const South_cap& cap,
                                  const Eigen::Matrix3d& turn)
{
  const Eigen::Index n = S.rows();
  South_chart c;
  c.turn = turn;
  Complex_vector p(n);
  for(Eigen::Index i = 0; i < n; ++i) p[i] = south_stereographic(c.turn * row_vector3(S, i));
  c.P = to_planar(p);
  c.pinned = cap.member;
  const std::vector<int> orient = planar_orientations(c.P, F);
  const int sign = majority_orientation(orient);
  for(Eigen::Index k = 0; k < F.rows(); ++k)
    if(orient[k] != sign)
      for(int a = 0; a < 3; ++a)
        if(!c.pinned[F(k, a)]) { c.pinned[F(k, a)] = 1; c.pinned_is_cap = false; }
  return c;
}

/// The south step's harmonic system solved on the factorization of the north
/// step, whose ordering put the cap and the north face's corners T last
/// (Factorization_with_trailing_set): with R the free vertices other than T,
/// L_RR is the factorization's leading block, and T's three unknowns are
/// eliminated through their 3 x 3 Schur complement. `w` is n x 2, the pinned
/// vertices at their chart positions. False when a solve fails.
inline bool south_solve_on_leading_block(const Sparse_matrix& L, const Index_matrix& F, Eigen::Index t,
                                         const South_chart& chart, Factorization_with_trailing_set& factorization,
                                         Matrix& w)
{
  const Eigen::Index n = L.rows();
  const int T[3] = {F(t, 0), F(t, 1), F(t, 2)};
  // columns: -L_{free,cap} P_cap (2), and L's columns at T (3)
  Matrix B = Matrix::Zero(n, 5);
  for(Eigen::Index c = 0; c < n; ++c)
    for(Sparse_matrix::InnerIterator it(L, c); it; ++it) {
      const Eigen::Index r = it.row();
      if(chart.pinned[r]) continue;
      if(chart.pinned[c]) B.row(r).head<2>() -= it.value() * chart.P.row(c);
      for(int a = 0; a < 3; ++a)
        if(c == T[a]) B(r, 2 + a) = it.value();
    }
  Matrix B_T(3, 5); // T's rows: b_T and L_TT (the leading solve ignores them)
  for(int a = 0; a < 3; ++a) B_T.row(a) = B.row(T[a]);
  // With L_RR = G G^T and Z = G^-1 B_R (forward halves only): the Schur
  // complement onto T is L_TT - Z_T^T Z_T (Z_T: the columns of L_RT), T's
  // right-hand side b_T - Z_T^T Z_b; then w_R = L_RR^-1 (b_R - L_RT w_T) =
  // G^-T (Z_b - Z_T w_T) takes one backward half, on two columns, not five.
  Matrix Z;
  if(!factorization.forward_leading(B, Z)) return false;
  const Eigen::Matrix3d schur = B_T.rightCols<3>() - Z.rightCols<3>().transpose() * Z.rightCols<3>();
  const Eigen::Matrix<double, 3, 2> rhs = B_T.leftCols<2>() - Z.rightCols<3>().transpose() * Z.leftCols<2>();
  const Eigen::Matrix<double, 3, 2> w_T = schur.fullPivLu().solve(rhs);
  if(!w_T.allFinite() || !factorization.backward_leading(Z.leftCols<2>() - Z.rightCols<3>() * w_T, w)) return false;
  for(int a = 0; a < 3; ++a) w.row(T[a]) = w_T.row(a);
  for(Eigen::Index i = 0; i < n; ++i)
    if(chart.pinned[i]) w.row(i) = chart.P.row(i);
  return w.allFinite();
}

/// The south step's harmonic system factored on its own (any solver).
inline bool south_solve_factored(Sparse_matrix K, const South_chart& chart, Spd_solver& solver, Matrix& w)
{
  Matrix rhs = Matrix::Zero(K.rows(), 2);
  apply_dirichlet(K, rhs, chart.pinned, chart.P);
  return solver.factor(K) && solver.solve(rhs, w);
}

/// The sphere of the south step's chart coordinates w, turned back.
inline void lift_south_chart(const Matrix& w, const South_chart& chart, Flash_result& res)
{
  const Eigen::Index n = w.rows();
  res.S.resize(n, 3);
  res.south_w.resize(n);
  for(Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d s = chart.turn.transpose() * inverse_south_stereographic(Complex(w(i, 0), w(i, 1)));
    res.S.row(i) = s.transpose();
    res.south_w[i] = chart.turn.isIdentity(0) ? Complex(w(i, 0), w(i, 1)) : south_stereographic(s);
  }
}

/// Which south cap FLASH pins (flash_spherical_map()).
enum class South_cap_rule
{
  /// chosen_first from one_factorization_min_vertices on, the reference's below
  by_size,
  /// chosen before the north step, so that one factorization serves both steps
  chosen_first,
  /// the reference's: the lowest 10 % after the north step, a second factorization
  reference
};

/// Below this many vertices FLASH keeps the reference's cap: a whole map then
/// takes a few hundredths of a second, so the second factorization costs a
/// few milliseconds, and the map is the paper's own. The density-equalizing
/// runs that start from it, many of them shaped by fold repairs, depend on the
/// start in detail: LSDEM's landmark error on a 642-vertex sphere falls by 41
/// % and 21 % from landmark weight 0.5 to 5 to 20 from the reference's cap,
/// by 55 % and 1 % from the other (benchmark/RESULTS.md, "One factorization for FLASH").
constexpr Eigen::Index one_factorization_min_vertices = 20000;

/// FLASH (ALGORITHMS.md section 3): the harmonic map of the mesh punctured at
/// its most regular face onto the plane, balanced and lifted to the sphere
/// (north step); then, in the south chart where the puncture sits at the
/// centre, the harmonic map again with a cap far from the puncture pinned to
/// the north step's map (south step). The south step's system is FLASH's LBS
/// system with the metric Beltrami coefficient, which *is* the cotangent
/// Laplacian L (beltrami.h), so both steps have L's pattern.
///
/// One departure from the reference, for speed, from
/// one_factorization_min_vertices on: the cap is, where it serves, the 10 % of
/// vertices farthest from the puncture along the mesh's edges, chosen before
/// the north step (farthest_vertices_from_face()), with the south chart
/// centred on its deepest vertex; the reference takes the 10 % of
/// lowest height after the north step and the chart of the north step's south
/// pole. Both caps lie where the north step's map is accurate; knowing the
/// cap first lets one factorization of L, ordered with the cap last, serve
/// both steps (south_solve_on_leading_block()) with the package's default
/// solver. The chosen cap is kept when its map has no inverted face;
/// otherwise the reference's cap is used, with a second factorization. The
/// mean |mu| moves by -1 % to +3.4 % against the reference's cap on the
/// shared and benchmark meshes (benchmark/RESULTS.md, "One factorization for
/// FLASH"). With another solver
/// the south system is factored on its own, with the same choice of cap, so
/// every solver gives the same map.
///
/// Falls back to a Tutte embedding when the cotangent harmonic map fails.
inline Flash_result flash_spherical_map(const Matrix& X, const Index_matrix& F, const Spd_solver& prototype,
                                        const Stage_notifier& stage = Stage_notifier(),
                                        South_cap_rule rule = South_cap_rule::by_size)
{
  const Eigen::Index n = X.rows();
  Flash_result res;
  const Eigen::Index t = most_regular_face(X, F);
  res.north_face = t;
  const Eigen::Vector3d a = row3(X, F(t, 1)) - row3(X, F(t, 0)), b = row3(X, F(t, 2)) - row3(X, F(t, 0));
  // the 3D triangle scaled to a unit base, with the signed real part
  const Complex cot_corners[3] = {Complex(0, 0), Complex(1, 0),
                                  Complex(a.dot(b), a.cross(b).norm()) / a.squaredNorm()};
  const Face_block_assembler assembler(F, n);
  std::unique_ptr<Spd_solver> solver = clone_with_fast_ordering(prototype);
  const bool cap_first = rule == South_cap_rule::chosen_first ||
                         (rule == South_cap_rule::by_size && n >= one_factorization_min_vertices);
  std::unique_ptr<Factorization_with_trailing_set> one_factorization =
    cap_first ? factorization_with_trailing_set_like(prototype) : nullptr;
  begin_stage(stage, "harmonic map (cotangent Laplacian, sparse Cholesky)");
  // The Laplacian's values (into storage allocated here) and the cap (a
  // serial Dijkstra over its pattern) are computed side by side. The m x 9
  // blocks die before the factorization, the memory peak.
  Sparse_matrix L = assembler.pattern();
  const Eigen::Index cap_size = std::max<Eigen::Index>(static_cast<Eigen::Index>(std::llround(n / 10.)), 3);
  South_cap cap;
  {
    Matrix blocks(F.rows(), 9);
    run_beside([&] { cotangent_stiffness_blocks(X, F, 1., blocks); assembler.assemble(blocks, nullptr, L); },
               [&] { if(cap_first) cap = farthest_vertices_from_face(X, assembler.pattern(), F, t, cap_size); });
  }
  std::vector<char> cap_and_puncture = cap_first ? cap.member : std::vector<char>(static_cast<std::size_t>(n), 0);
  for(int c = 0; c < 3; ++c) {
    if(cap_and_puncture[F(t, c)]) one_factorization.reset(); // a tiny mesh: the cap reaches the puncture
    cap_and_puncture[F(t, c)] = 1;
  }

  // North step. The Dirichlet rows of the puncture are written into L itself
  // and its values restored afterwards: one matrix alive, not two.
  Complex_vector z;
  {
    std::vector<std::pair<int, double> > saved;
    for(int c = 0; c < L.outerSize(); ++c)
      for(int p = L.outerIndexPtr()[c]; p < L.outerIndexPtr()[c + 1]; ++p)
        if((c == F(t, 0) || c == F(t, 1) || c == F(t, 2)) ||
           (L.innerIndexPtr()[p] == F(t, 0) || L.innerIndexPtr()[p] == F(t, 1) || L.innerIndexPtr()[p] == F(t, 2)))
          saved.emplace_back(p, L.valuePtr()[p]);
    Matrix rhs, sol;
    punctured_harmonic_system(L, F, t, cot_corners, rhs);
    bool ok = one_factorization && one_factorization->factor(L, cap_and_puncture) &&
              one_factorization->solve(rhs, sol);
    if(!ok) {
      one_factorization.reset();
      ok = solver->factor(L) && solver->solve(rhs, sol);
    }
    ok = ok && complex_solution(sol, z);
    for(const auto& e : saved) L.valuePtr()[e.first] = e.second;
    if(!ok) z = Complex_vector();
  }

  Matrix S;
  auto balance_and_lift = [&](Complex_vector& zz) {
    zz.array() -= zz.mean();
    // south triangle: smallest sum of |z| over the corners, t excluded
    Eigen::Index ts = -1;
    double best = std::numeric_limits<double>::infinity();
    for(Eigen::Index k = 0; k < F.rows(); ++k) {
      if(k == t) continue;
      const double s = std::abs(zz[F(k, 0)]) + std::abs(zz[F(k, 1)]) + std::abs(zz[F(k, 2)]);
      if(s < best) { best = s; ts = k; }
    }
    auto inv = [](Complex w) { return 1. / std::conj(w); };
    const double lN = mean_side(zz[F(t, 0)], zz[F(t, 1)], zz[F(t, 2)]);
    const double lS = mean_side(inv(zz[F(ts, 0)]), inv(zz[F(ts, 1)]), inv(zz[F(ts, 2)]));
    if(std::isfinite(lS) && lS > 0 && lN > 0) zz *= std::sqrt(lS / lN);
    S = inverse_north_chart(zz);
    return S.allFinite();
  };
  if(z.size() == 0 || !balance_and_lift(z)) {
    begin_stage(stage, "Tutte embedding (the harmonic map failed)");
    res.tutte = true;
    res.fallback = "tutte embedding (the cotangent harmonic map could not be computed)";
    one_factorization.reset();
    const Complex tutte_corners[3] = {Complex(1, 0), std::polar(1., 2 * M_PI / 3), std::polar(1., 4 * M_PI / 3)};
    std::unique_ptr<Spd_solver> s2 = clone_with_fast_ordering(prototype);
    if(!punctured_harmonic_map(graph_laplacian(F, n), F, t, tutte_corners, *s2, z) || !balance_and_lift(z))
      throw Algorithm_failure("the spherical conformal map failed: neither the cotangent harmonic map nor the "
                              "Tutte embedding of the (valid) mesh could be computed (linear solver failure or "
                              "non-finite result)");
  }

  // South step: the harmonic map in the south chart with a cap pinned, where
  // the north step's distortion (near the puncture) sits at the centre. The
  // cap chosen beforehand is kept when its map has no inverted face;
  // otherwise FLASH's own cap is taken (a second factorization). A
  // protrusion far from the puncture, e.g. the far end of a cigar, can be
  // crowded by the conformal map into a tiny cap, and a tiny pinned cap acts
  // like a second puncture (the tests' 4:1 bumpy cigar of 5,120 faces folds with it).
  begin_stage(stage, "south-chart LBS correction");
  bool solved = false;
  std::size_t inverted = 0; // exact count on the map of the south step
  if(cap_first) {
    const South_chart chart = south_chart_of(S, F, cap, turn_to_south_pole(S, F, cap));
    Matrix w;
    solved = chart.P.allFinite() &&
             ((one_factorization && chart.pinned_is_cap &&
               south_solve_on_leading_block(L, F, t, chart, *one_factorization, w)) ||
              south_solve_factored(L, chart, *solver, w));
    if(solved) {
      lift_south_chart(w, chart, res);
      inverted = count_inverted_faces_about_center(res.S, F);
      solved = inverted == 0;
    }
  }
  one_factorization.reset(); // the factor dies before any other system
  if(!solved) {
    const South_chart chart = south_chart_of(S, F, lowest_vertices(S, cap_size), Eigen::Matrix3d::Identity());
    Matrix w;
    if(!chart.P.allFinite() || !south_solve_factored(std::move(L), chart, *solver, w)) {
      w = chart.P; // reported: the map is the north step's, distorted near the puncture
      res.fallback = "the north step's map alone (the south-chart correction could not be solved)";
    }
    lift_south_chart(w, chart, res);
    inverted = count_inverted_faces_about_center(res.S, F);
  }
  { Sparse_matrix none; L.swap(none); }

  // On coarse meshes with many obtuse angles (negative cotangent weights) the
  // harmonic step can fold. Then start from the Tutte embedding (convex
  // weights: an embedding) and move towards the conformal map with the
  // fold-over repair of the density engine: the folded faces of the step are
  // untangled locally, and the step is shortened if that cannot succeed.
  if(inverted > 0) {
    begin_stage(stage, "fold repair from the Tutte embedding (the harmonic map folded)");
    const Complex tutte_corners[3] = {Complex(1, 0), std::polar(1., 2 * M_PI / 3), std::polar(1., 4 * M_PI / 3)};
    std::unique_ptr<Spd_solver> s4 = clone_with_fast_ordering(prototype);
    Complex_vector zt;
    if(punctured_harmonic_map(graph_laplacian(F, n), F, t, tutte_corners, *s4, zt) && balance_and_lift(zt) &&
       count_inverted_faces_about_center(S, F) == 0) {
      const Matrix tutte = S;
      Ellipsoid_domain sphere(F, tutte, Eigen::Vector3d::Ones(), 0.1, prototype);
      Step_statistics stats;
      Matrix repaired;
      const bool moved = sphere.advance(tutte, res.S - tutte, 1., repaired, stats);
      res.S = moved ? repaired : tutte;
      res.tutte = true;
      res.repairs += stats.repairs;
      res.fallback = moved ? "tutte embedding repaired towards the harmonic map (the harmonic map folded)"
                           : "tutte embedding (the harmonic map folded and could not be repaired)";
      for(Eigen::Index i = 0; i < n; ++i) res.south_w[i] = south_stereographic(row_vector3(res.S, i));
    }
  }
  return res;
}

/// Why a conformal map onto the sphere or an ellipsoid folded, for the
/// report: the spread of the (normalized) image-to-input area ratios. A
/// conformal map of a long tube crowds exponentially with its length (a 100:1
/// capsule needs ratios near e^-200): past about 1e-14 the faces of the
/// crowded end are below the rounding of the coordinates and fold.
inline std::string crowding_note(const Matrix& X, const Index_matrix& F, const Matrix& Y)
{
  const Vector a = face_areas(X, F), b = face_areas(Y, F);
  const double sa = a.sum(), sb = b.sum();
  double smallest = std::numeric_limits<double>::infinity();
  for(Eigen::Index k = 0; k < F.rows(); ++k) smallest = std::min(smallest, (b[k] / sb) / (a[k] / sa));
  std::ostringstream o;
  o << "smallest image-to-input area ratio " << smallest;
  if(!(smallest > 1e-12))
    o << ": the conformal map crowds faces below the precision of double (an elongated or strongly "
         "protruding surface: its conformal image shrinks exponentially along the protrusion)";
  return o.str();
}

/// Moebius map f(z) = e^s (z - w0) / (1 + conj(w0) z): a rotation of the
/// sphere taking w0 to the south pole followed by a dilation. Up to a final
/// rotation (which does not change areas) every Moebius map is of this form.
/// The dilation factor e^s is given (a map applied to many points computes
/// it once). Infinity (the north pole) goes to e^s / conj(w0).
inline Complex mobius_rotation_scaling(Complex z, Complex w0, double dilation)
{
  if(!std::isfinite(z.real()) || !std::isfinite(z.imag()))
    return std::norm(w0) == 0 ? z : dilation / std::conj(w0);
  const Complex num = z - w0, den = 1. + std::conj(w0) * z;
  return (dilation / std::norm(den)) * (num * std::conj(den)); // real arithmetic: no complex division
}

/// The point of the sphere of the Moebius map (mobius_rotation_scaling()) of
/// the north-chart point z: (P^N)^{-1}(u) = (2 Re u, 2 Im u, |u|^2 - 1) /
/// (1 + |u|^2) for u = f(z). The Moebius search evaluates it hundreds of
/// times per vertex, so it takes two divisions where the general functions
/// take five or six: the one of f, and 1 / (1 + |u|^2) for the three
/// coordinates. Points whose image is at or beyond |u|^2 = 1e300 (where the
/// formula would overflow), or not finite, take the general, overflow-safe
/// path.
inline Eigen::Vector3d mobius_point_on_sphere(Complex z, Complex w0, double dilation)
{
  const double x = z.real() - w0.real(), y = z.imag() - w0.imag();       // z - w0
  const double a = 1 + w0.real() * z.real() + w0.imag() * z.imag();      // 1 + conj(w0) z
  const double b = w0.real() * z.imag() - w0.imag() * z.real();
  const double scale = dilation / (a * a + b * b);
  const double ux = scale * (x * a + y * b), uy = scale * (y * a - x * b); // scale (z - w0) conj(den)
  const double m = ux * ux + uy * uy;
  if(!(m < 1e300)) return inverse_north_stereographic(mobius_rotation_scaling(z, w0, dilation));
  const double r = 1 / (1 + m);
  return Eigen::Vector3d(2 * ux * r, 2 * uy * r, (m - 1) * r);
}

/// The Moebius map with parameters xi (w0 = xi[0] + i xi[1], dilation
/// e^xi[2]; mobius_rotation_scaling()) of the north-chart points z, back on
/// the sphere: row i of `image` receives the image of z[i].
template <class RowMatrix>
void mobius_image(const Complex_vector& z, const Eigen::Vector3d& xi, RowMatrix& image)
{
  const Complex w0(xi[0], xi[1]);
  const double dilation = std::exp(xi[2]);
  parallel_for(z.size(), [&](Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index i = begin; i < end; ++i) image.row(i) = mobius_point_on_sphere(z[i], w0, dilation).transpose();
  });
}

/// mean |log(image_area / image_total / target_share)| over the faces where
/// it is finite, each face's term being the log of its share of the image
/// area against its share of the target, computed as log(image_area) -
/// log(target_share) - log(image_total) with the target's logarithms given
/// (one logarithm per face and evaluation, no division). The logarithms run
/// over fixed blocks of faces in Eigen's vectorized form, and the sums add
/// up the same way on any number of threads.
inline double mean_abs_log_area_ratio(const Vector& log_target_share, const Vector& image_area, double image_total)
{
  const Eigen::Index m = log_target_share.size();
  const double log_total = std::log(image_total);
  std::vector<std::array<double, 2> > block_sums(static_cast<std::size_t>((m + parallel_block - 1) / parallel_block));
  for_each_fixed_block(m, [&](Eigen::Index b, Eigen::Index begin, Eigen::Index end) {
    const Eigen::Index len = end - begin;
    const Eigen::ArrayXd d =
      image_area.segment(begin, len).array().log() - log_target_share.segment(begin, len).array() - log_total;
    const auto finite = d.isFinite();
    // the sum of |log ratio| and the number of faces where it is finite
    block_sums[static_cast<std::size_t>(b)] = {finite.select(d.abs(), 0.).sum(), double(finite.count())};
  });
  double sum = 0, count = 0;
  for(const std::array<double, 2>& s : block_sums) { sum += s[0]; count += s[1]; }
  return count > 0 ? sum / count : std::numeric_limits<double>::infinity();
}

/// The objective of the Moebius correction on a sample of faces: the mean
/// |log area ratio| of the Moebius map with parameters xi (w0 = xi[0] + i xi[1],
/// dilation e^xi[2]) of the north-chart points z. The sample keeps its own
/// numbering of the vertices it uses and its own image buffer: the search
/// evaluates hundreds of maps on it, and a scattered sample of a few thousand
/// faces of a large mesh would otherwise touch the whole mesh's arrays each
/// time. (With the vectorized logarithm: the search 10-15 % faster, the
/// same map to the bit; benchmark/RESULTS.md.)
class Moebius_area_objective
{
public:
  Moebius_area_objective(const Face_sample& sample, const Complex_vector& z, Eigen::Index n)
  {
    m_z.resize(Eigen::Index(sample.vertices.size()));
    for(std::size_t j = 0; j < sample.vertices.size(); ++j) m_z[Eigen::Index(j)] = z[sample.vertices[j]];
    m_F = faces_in_sample_numbering(sample, sample.vertices, n);
    m_log_target_share = (sample.source_area / sample.source_total).array().log().matrix();
    m_image.resize(m_z.size(), 3);
    m_image_area.resize(m_F.rows());
  }

  double operator()(const Eigen::Vector3d& xi)
  {
    if(xi.head<2>().norm() > 1e3 || std::abs(xi[2]) > 50) return std::numeric_limits<double>::infinity();
    mobius_image(m_z, xi, m_image);
    const double total = parallel_sums<1>(m_F.rows(), [&](Eigen::Index k, std::array<double, 1>& s) {
      const Eigen::Vector3d a = m_image.row(m_F(k, 0)), b = m_image.row(m_F(k, 1)), c = m_image.row(m_F(k, 2));
      m_image_area[k] = 0.5 * (b - a).cross(c - a).norm();
      s[0] += m_image_area[k];
    })[0];
    return mean_abs_log_area_ratio(m_log_target_share, m_image_area, total);
  }

private:
  Complex_vector m_z;
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> m_F;
  Vector m_log_target_share;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> m_image;
  Vector m_image_area;
};

/// Nelder-Mead minimization in R^3 (the objective is non-smooth). Stops
/// after `max_evaluations`, or when the simplex's values agree to the
/// relative `tolerance` and its size is below `size_tolerance`.
template <class Objective>
Eigen::Vector3d nelder_mead_3(Objective f, Eigen::Vector3d x0, const Eigen::Vector3d& step, int max_evaluations,
                              double tolerance, double size_tolerance = 1e-8)
{
  std::array<Eigen::Vector3d, 4> x;
  std::array<double, 4> v;
  x[0] = x0;
  for(int i = 0; i < 3; ++i) { x[i + 1] = x0; x[i + 1][i] += step[i]; }
  int evals = 0;
  for(int i = 0; i < 4; ++i) { v[i] = f(x[i]); ++evals; }
  while(evals < max_evaluations) {
    std::array<int, 4> idx = {0, 1, 2, 3};
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return v[a] < v[b]; });
    std::array<Eigen::Vector3d, 4> xs; std::array<double, 4> vs;
    for(int i = 0; i < 4; ++i) { xs[i] = x[idx[i]]; vs[i] = v[idx[i]]; }
    x = xs; v = vs;
    if(std::abs(v[3] - v[0]) <= tolerance * (std::abs(v[0]) + 1e-30) &&
       (x[3] - x[0]).norm() <= size_tolerance)
      break;
    const Eigen::Vector3d c = (x[0] + x[1] + x[2]) / 3.;
    const Eigen::Vector3d xr = c + (c - x[3]);
    const double vr = f(xr); ++evals;
    if(vr < v[0]) {
      const Eigen::Vector3d xe = c + 2. * (c - x[3]);
      const double ve = f(xe); ++evals;
      if(ve < vr) { x[3] = xe; v[3] = ve; } else { x[3] = xr; v[3] = vr; }
    } else if(vr < v[2]) {
      x[3] = xr; v[3] = vr;
    } else {
      const bool outside = vr < v[3];
      const Eigen::Vector3d xc = outside ? Eigen::Vector3d(c + 0.5 * (xr - c)) : Eigen::Vector3d(c + 0.5 * (x[3] - c));
      const double vc = f(xc); ++evals;
      if(vc < (outside ? vr : v[3])) { x[3] = xc; v[3] = vc; }
      else {
        for(int i = 1; i < 4; ++i) { x[i] = x[0] + 0.5 * (x[i] - x[0]); v[i] = f(x[i]); ++evals; }
      }
    }
  }
  int best = 0;
  for(int i = 1; i < 4; ++i) if(v[i] < v[best]) best = i;
  return x[best];
}

/// The fraction t in [0, 1] of the dilation `xi[2]` (the rotation part kept)
/// that keeps every face of `apply(xi)` positively oriented about the centre,
/// by bisection; 1 when the full dilation does. A strong dilation (a
/// population far from uniform) can stretch one face over more than a
/// hemisphere, where its chordal triangle turns over: such a Moebius map is no
/// longer a fold-free map of the mesh.
template <class Apply>
double fold_free_dilation_fraction(const Eigen::Vector3d& xi, const Index_matrix& F, const Matrix& q, Apply apply)
{
  auto oriented = [&](double t) {
    apply(Eigen::Vector3d(xi[0], xi[1], t * xi[2]));
    return first_index_where(F.rows(), [&](Eigen::Index k) {
             return !(row3(q, F(k, 0)).dot(row3(q, F(k, 1)).cross(row3(q, F(k, 2)))) > 0);
           }) == F.rows();
  };
  if(oriented(1.)) return 1.;
  double lo = 0, hi = 1;
  for(int i = 0; i < 30; ++i) (oriented(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return 0.9 * lo; // a margin: the caller's exact test must pass too
}

/// Moebius correction towards target face areas: the Moebius transformation of
/// the spherical map S minimizing the mean |log(normalized image area /
/// normalized target area)|, with the dilation limited so that no face turns
/// over (fold_free_dilation_fraction()). The targets are the input's face
/// areas for the area correction of paper 001, the population for the start
/// of a density-equalizing map (which a Moebius map brings closest to uniform
/// density at no risk of folding: every face keeps its angles). Never worse
/// than S itself on the objective. Returns the corrected map.
///
/// With `Mobius_search::sample_only` the search stops after its first stage,
/// on the sample of about 4000 faces: for a start that only needs the Moebius
/// freedom fixed, which later steps move anyway (a registration's starting maps).
enum class Mobius_search { polished, sample_only };

inline Matrix mobius_correction(const Vector& target_area, const Index_matrix& F, const Matrix& S,
                                double* objective_before = nullptr, double* objective_after = nullptr,
                                Mobius_search search = Mobius_search::polished)
{
  const Complex_vector z = north_chart(S);
  const Eigen::Index n = S.rows();
  Matrix q(n, 3);
  auto apply = [&](const Eigen::Vector3d& xi) { mobius_image(z, xi, q); }; // all vertices, into q
  // The objective is a mean over faces: the search runs on a sample of about
  // 4000 faces and is polished on a sample of about 16,000 (120 evaluations
  // there, which cost a sixth of 120 on all faces at 100,000 faces and a 60th
  // at 1M); a last, short polish on all faces (40 evaluations, steps ten
  // times smaller) removes the sample's bias. On the benchmark and shared
  // meshes the objective then matches that of 120 evaluations on all faces
  // to 1e-8 (benchmark/RESULTS.md, "Speed at the floor"). The search on the
  // first sample stops once its simplex is below 1e-6: the sample's optimum
  // differs from the mesh's by more than that, and the polish starts with
  // steps of 0.02 (maxplanck: 400 -> 201 evaluations, the final objective
  // equal to 1e-10). Below 32,000 faces the polishing sample would be every
  // face: the polish runs on all faces once.
  Moebius_area_objective on_all(face_sample(F, target_area, n, 1), z, n);
  const double before = on_all(Eigen::Vector3d::Zero());
  Eigen::Vector3d best = nelder_mead_3(Moebius_area_objective(face_sample(F, target_area, n, F.rows() / 4000), z, n),
                                       Eigen::Vector3d::Zero(), Eigen::Vector3d(0.2, 0.2, 0.5), 400, 1e-8, 1e-6);
  const Eigen::Index polish_stride = F.rows() / 16000;
  if(search == Mobius_search::polished && polish_stride > 1) {
    best = nelder_mead_3(Moebius_area_objective(face_sample(F, target_area, n, polish_stride), z, n), best,
                         Eigen::Vector3d(0.02, 0.02, 0.05), 120, 1e-8);
    best = nelder_mead_3(std::ref(on_all), best, Eigen::Vector3d(0.002, 0.002, 0.005), 40, 1e-8);
  } else if(search == Mobius_search::polished)
    best = nelder_mead_3(std::ref(on_all), best, Eigen::Vector3d(0.02, 0.02, 0.05), 120, 1e-8);
  best[2] *= fold_free_dilation_fraction(best, F, q, apply);
  const double after = on_all(best);
  if(objective_before) *objective_before = before;
  if(!(after <= before)) { // never make it worse
    if(objective_after) *objective_after = before;
    return S;
  }
  if(objective_after) *objective_after = after;
  apply(best);
  return q;
}

/// Moebius area correction (paper 001): mobius_correction() towards the face
/// areas of the input X.
inline Matrix mobius_area_correction(const Matrix& X, const Index_matrix& F, const Matrix& S,
                                     double* objective_before = nullptr, double* objective_after = nullptr)
{
  return mobius_correction(face_areas(X, F), F, S, objective_before, objective_after);
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_SPHERICAL_CONFORMAL_H
