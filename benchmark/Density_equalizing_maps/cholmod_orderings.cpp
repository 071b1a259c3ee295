// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The fill-reducing orderings CHOLMOD offers, on a mesh's pinned cotangent
// Laplacian (the pattern and fill of every system of the package): for each,
// the analysis time (ordering + symbolic), two numeric factorizations (the
// first one also touches the factor's memory for the first time), a solve
// with two right-hand sides, nnz(L) and the flop count of the factorization.
//
//   cholmod_orderings MESH [ORDERING ...]   ORDERING: default amd metis nesdis (all four if none)
//
// "default" is CHOLMOD's own choice (nmethods 0: AMD, and METIS as well when
// AMD's fill is high); the package asks for AMD alone (sparse_solver.h).
// Single runs: interleave several invocations on a busy machine.

#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#ifdef CGAL_DEM_USE_CHOLMOD
#include <cholmod.h>
#endif

namespace DI = CGAL::Density_equalizing_maps::internal;

int main(int argc, char** argv)
{
  // the BLAS kernels of this CPU, as dem runs them (internal/openblas.h)
  CGAL::Density_equalizing_maps::internal::restart_with_openblas_kernels_of_this_cpu(argv);
  if(argc < 2) {
    std::fprintf(stderr, "usage: cholmod_orderings MESH [default|amd|metis|nesdis ...]\n");
    return 2;
  }
#ifndef CGAL_DEM_USE_CHOLMOD
  std::fprintf(stderr, "cholmod_orderings: built without CHOLMOD\n");
  return 77;
#else
  typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point_3;
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if(!CGAL::IO::read_polygon_soup(argv[1], points, polygons) || polygons.empty()) {
    std::fprintf(stderr, "cholmod_orderings: cannot read %s\n", argv[1]);
    return 3;
  }
  DI::Matrix X(Eigen::Index(points.size()), 3);
  for(std::size_t i = 0; i < points.size(); ++i) X.row(Eigen::Index(i)) << points[i].x(), points[i].y(), points[i].z();
  DI::Index_matrix F(Eigen::Index(polygons.size()), 3);
  for(std::size_t k = 0; k < polygons.size(); ++k)
    for(int c = 0; c < 3; ++c) F(Eigen::Index(k), c) = int(polygons[k][std::size_t(c)]);
  // the last vertex pinned (row and column removed): SPD, as in factorization_floor
  const Eigen::Index n = X.rows() - 1;
  DI::Sparse_matrix A = DI::cotangent_laplacian(X, F).topLeftCorner(n, n);
  A.makeCompressed();

  std::vector<std::string> orderings;
  for(int i = 2; i < argc; ++i) orderings.push_back(argv[i]);
  if(orderings.empty()) orderings = {"default", "amd", "metis", "nesdis"};
  const auto seconds_since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::printf("%s: %ld unknowns, nnz(A) %ld\n", argv[1], long(n), long(A.nonZeros()));
  for(const std::string& ordering : orderings) {
    cholmod_common c;
    cholmod_start(&c);
    if(ordering != "default") {
      c.nmethods = 1;
      c.method[0].ordering = ordering == "amd" ? CHOLMOD_AMD : ordering == "metis" ? CHOLMOD_METIS : CHOLMOD_NESDIS;
    }
    cholmod_sparse a;
    std::memset(&a, 0, sizeof a);
    a.nrow = a.ncol = std::size_t(n);
    a.nzmax = std::size_t(A.nonZeros());
    a.p = A.outerIndexPtr();
    a.i = A.innerIndexPtr();
    a.x = A.valuePtr();
    a.stype = -1; // the lower triangle of the symmetric matrix
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = a.packed = 1;
    auto t0 = std::chrono::steady_clock::now();
    cholmod_factor* L = cholmod_analyze(&a, &c);
    const double analysis = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    cholmod_factorize(&a, L, &c);
    const double first = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    cholmod_factorize(&a, L, &c);
    const double second = seconds_since(t0);
    cholmod_dense* b = cholmod_ones(std::size_t(n), 2, CHOLMOD_REAL, &c);
    t0 = std::chrono::steady_clock::now();
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, L, b, &c);
    const double solve = seconds_since(t0);
    std::printf("  %-8s analysis %7.3f s  numeric %7.3f s (first) %7.3f s (again)  solve(2) %6.3f s  "
                "nnz(L) %6.1f M  %6.1f Gflop  status %d\n",
                ordering.c_str(), analysis, first, second, solve, c.lnz / 1e6, c.fl / 1e9, c.status);
    cholmod_free_dense(&x, &c);
    cholmod_free_dense(&b, &c);
    cholmod_free_factor(&L, &c);
    cholmod_finish(&c);
  }
  return 0;
#endif
}
