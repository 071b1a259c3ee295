// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The floor of the direct methods: one sparse Cholesky factorization of the
// mesh's cotangent Laplacian with the package's default solver.
//
//   factorization_floor MESH [repeats=5]
//
// The Laplacian is singular (constants), so one vertex is pinned (its row and
// column removed), as every harmonic map of the package pins vertices: the
// matrix then has the pattern and the fill of the systems the maps solve.
// Prints one JSON object: the median seconds of a full factorization (the
// fill-reducing ordering and symbolic analysis included) and of a numeric-only
// refactorization on the analysed pattern, plus the assembly time; and the
// full factorization again with the cheap ordering the conformal maps ask for
// (Ordering_effort::fast: on large meshes CHOLMOD's default also tries METIS).
// benchmark/floor_table.py divides each method's time by these.

#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>
#include <CGAL/Density_equalizing_maps/internal/sparse_solver.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace DI = CGAL::Density_equalizing_maps::internal;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// L with the last vertex's row and column removed: symmetric positive definite
/// for a connected mesh.
DI::Sparse_matrix pinned_laplacian(const DI::Sparse_matrix& L)
{
  const Eigen::Index n = L.rows() - 1;
  return L.topLeftCorner(n, n);
}

} // namespace

int main(int argc, char** argv)
{
  // the BLAS kernels of this CPU, as dem runs them (internal/openblas.h)
  CGAL::Density_equalizing_maps::internal::restart_with_openblas_kernels_of_this_cpu(argv);
  if(argc < 2) {
    std::fprintf(stderr, "usage: factorization_floor MESH [repeats=5]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point_3;
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if(!CGAL::IO::read_polygon_soup(argv[1], points, polygons) || polygons.empty()) {
    std::fprintf(stderr, "factorization_floor: cannot read %s\n", argv[1]);
    return 3;
  }
  DI::Matrix X(Eigen::Index(points.size()), 3);
  for(std::size_t i = 0; i < points.size(); ++i)
    X.row(Eigen::Index(i)) << points[i].x(), points[i].y(), points[i].z();
  DI::Index_matrix F(Eigen::Index(polygons.size()), 3);
  for(std::size_t k = 0; k < polygons.size(); ++k) {
    if(polygons[k].size() != 3) { std::fprintf(stderr, "factorization_floor: not a triangle mesh\n"); return 3; }
    for(int c = 0; c < 3; ++c) F(Eigen::Index(k), c) = int(polygons[k][std::size_t(c)]);
  }

  std::vector<double> assembly, full, numeric, full_fast;
  for(int r = 0; r < repeats; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    const DI::Sparse_matrix A = pinned_laplacian(DI::cotangent_laplacian(X, F));
    assembly.push_back(seconds_since(t0));

    // A fresh solver: ordering + symbolic analysis + numeric factorization.
    std::unique_ptr<DI::Spd_solver> solver = DI::make_default_spd_solver();
    t0 = std::chrono::steady_clock::now();
    if(!solver->factor(A)) { std::fprintf(stderr, "factorization_floor: factorization failed\n"); return 4; }
    full.push_back(seconds_since(t0));

    // Same pattern again: the adapter keeps the analysis, numeric part only.
    t0 = std::chrono::steady_clock::now();
    if(!solver->factor(A)) { std::fprintf(stderr, "factorization_floor: refactorization failed\n"); return 4; }
    numeric.push_back(seconds_since(t0));
    solver.reset(); // one factor alive at a time

    std::unique_ptr<DI::Spd_solver> fast = DI::make_default_spd_solver();
    fast->set_ordering_effort(DI::Ordering_effort::fast);
    t0 = std::chrono::steady_clock::now();
    if(!fast->factor(A)) { std::fprintf(stderr, "factorization_floor: factorization failed\n"); return 4; }
    full_fast.push_back(seconds_since(t0));
  }
  std::printf("{\"vertices\": %zu, \"faces\": %zu, \"repeats\": %d, \"assembly_seconds\": %.6g, "
              "\"full_factorization_seconds\": %.6g, \"numeric_factorization_seconds\": %.6g, "
              "\"full_factorization_fast_ordering_seconds\": %.6g}\n",
              points.size(), polygons.size(), repeats, median(assembly), median(full), median(numeric),
              median(full_fast));
  return 0;
}
