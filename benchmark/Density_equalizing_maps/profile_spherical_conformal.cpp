// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Where the time of the spherical conformal map goes: times the stages of
// spherical_conformal_map() (validation, operators, the harmonic solve, the
// south cap, the exact fold-over count) separately, minimum of R runs; then
// the public function on a Surface_mesh, and the stages FECM adds after FLASH
// (charts, the conformal correction psi, point location, the dilation search).
// The evaluate_ellipsoidal_conformal line reuses a mapper whose psi pattern is
// already analysed: its factorization is the numeric one alone.
//
// usage: profile_spherical_conformal MESH [R=5]

#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace DI = CGAL::Density_equalizing_maps::internal;
typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point;

namespace {

// Best wall time of R runs; the CPU time (all threads of the process) of the
// same best run goes to last_cpu: on a loaded machine it is the better
// estimate of the unloaded wall time of a single-threaded stage.
double last_cpu = 0;
double cpu_now()
{
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double best_of(const char* name, int repeats, const std::function<void()>& f)
{
  double best = std::numeric_limits<double>::infinity();
  for(int r = 0; r < repeats; ++r) {
    const double c0 = cpu_now();
    const auto t0 = std::chrono::steady_clock::now();
    f();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if(t < best) { best = t; last_cpu = cpu_now() - c0; }
  }
  std::printf("  %-44s %8.4f s wall %8.4f s CPU\n", name, best, last_cpu);
  return best;
}

} // namespace

int main(int argc, char** argv)
{
  // the BLAS kernels of this CPU, as dem runs them (internal/openblas.h)
  CGAL::Density_equalizing_maps::internal::restart_with_openblas_kernels_of_this_cpu(argv);
  if(argc < 2) { std::fprintf(stderr, "usage: profile_spherical_conformal MESH [R=5]\n"); return 2; }
  const int R = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if(!CGAL::IO::read_polygon_soup(argv[1], points, polygons)) { std::fprintf(stderr, "cannot read %s\n", argv[1]); return 3; }
  DI::Matrix X(points.size(), 3);
  DI::Index_matrix F(polygons.size(), 3);
  for(std::size_t i = 0; i < points.size(); ++i) X.row(i) << points[i].x(), points[i].y(), points[i].z();
  for(std::size_t k = 0; k < polygons.size(); ++k)
    for(int c = 0; c < 3; ++c) F(k, c) = int(polygons[k][c]);

  const auto solver = DI::make_spd_solver(CGAL::Density_equalizing_maps::Default_sparse_solver_traits());
  std::printf("%s: %ld vertices, %ld faces, best of %d runs\n", argv[1], long(X.rows()), long(F.rows()), R);
#ifdef CGAL_DEM_USE_CHOLMOD
  std::printf("solver: CHOLMOD supernodal LLT\n");
#else
  std::printf("solver: Eigen SimplicialLDLT\n");
#endif
  const double t_validate = best_of("validate_closed_surface", R, [&] { DI::validate_closed_surface(X, F, 2, 4); });
  const double t_regular = best_of("most_regular_face", R, [&] { (void)DI::most_regular_face(X, F); });
  DI::Sparse_matrix L;
  const double t_laplacian = best_of("cotangent_laplacian", R, [&] { L = DI::cotangent_laplacian(X, F); });
  const Eigen::Index t = DI::most_regular_face(X, F);
  const DI::Complex corners[3] = {DI::Complex(0, 0), DI::Complex(1, 0), DI::Complex(0.5, 0.8)};
  DI::Complex_vector z;
  const double t_harmonic = best_of("harmonic map (Dirichlet, factor, solve)", R, [&] {
    auto s = solver->clone();
    DI::punctured_harmonic_map(L, F, t, corners, *s, z);
  });
  // the Cholesky factorization alone: first call = ordering + symbolic + numeric,
  // second call on the same pattern = numeric only
  DI::Sparse_matrix A = L;
  for(Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1e-8; // SPD without Dirichlet rows
  double t_factor_full = 0, t_factor_numeric = 0;
  {
    t_factor_full = best_of("  factor: ordering + symbolic + numeric", R, [&] { auto s = solver->clone(); s->factor(A); });
    auto s = solver->clone();
    s->factor(A);
    t_factor_numeric = best_of("  factor: numeric only (same pattern)", R, [&] { s->factor(A); });
  }
  const Eigen::Index cap_size = std::max<Eigen::Index>(X.rows() / 10, 3);
  const double t_cap = best_of("south cap (Dijkstra from the puncture)", R,
                               [&] { (void)DI::farthest_vertices_from_face(X, L, F, t, cap_size); });
  DI::Flash_result flash;
  const double t_flash = best_of("flash_spherical_map (total)", R, [&] { flash = DI::flash_spherical_map(X, F, *solver); });
  const double t_folds = best_of("exact fold-over count", R, [&] { (void)DI::count_inverted_faces_about_center(flash.S, F); });
  const double t_mobius = best_of("Moebius area correction (--mobius only)", std::min(R, 2), [&] { (void)DI::mobius_area_correction(X, F, flash.S); });

  // the default solver's flash factors once: the harmonic map's line above is
  // (nearly) all of its linear algebra
  std::printf("  => flash besides the Laplacian and the harmonic map (cap %.4f, south solve on the same factor, "
              "charts, lifting) ~ %.4f s wall\n",
              t_cap, t_flash - t_regular - t_laplacian - t_harmonic);
  std::printf("  => spherical_conformal_map without Moebius ~ %.4f s wall (validation + flash + fold count)\n",
              t_validate + t_flash + t_folds);
  (void)t_factor_full; (void)t_factor_numeric; (void)t_mobius;
  {
    // the public function on a Surface_mesh, as `dem spherical-conformal` calls it
    CGAL::Surface_mesh<Point> mesh;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    auto out = mesh.add_property_map<CGAL::Surface_mesh<Point>::Vertex_index, Point>("v:out").first;
    best_of("closed_surface_arrays (Surface_mesh)", R,
            [&] { (void)DI::closed_surface_arrays(mesh, CGAL::parameters::default_values(), 2); });
    best_of("spherical_conformal_map (public, Surface_mesh)", R,
            [&] { (void)CGAL::Density_equalizing_maps::spherical_conformal_map(mesh, out); });
  }

  // FECM's stages after FLASH (default radii and poles, chart dilation searched)
  std::printf("ellipsoidal conformal map (FECM) after FLASH:\n");
  const DI::Principal_frame frame = DI::principal_frame(X);
  const Eigen::Vector3d radii = frame.extent / frame.extent.mean();
  const std::array<Eigen::Index, 3> poles = DI::default_pole_vertices(X, frame);
  std::unique_ptr<DI::Ellipsoidal_mapper> mapper;
  best_of("charts and pinned set (Ellipsoidal_mapper)", R,
          [&] { mapper.reset(new DI::Ellipsoidal_mapper(X, F, poles, *solver, flash)); });
  // each run on a fresh mapper: a mapper's first factorization, with its
  // ordering and symbolic analysis, is the one FECM pays (the line includes
  // the charts of the line above)
  DI::Conformal_correction psi;
  best_of("charts + conformal correction psi (LBS)", R, [&] {
    mapper.reset(new DI::Ellipsoidal_mapper(X, F, poles, *solver, flash));
    psi = mapper->conformal_correction(radii, 1.);
  });
  std::unique_ptr<DI::Planar_point_locator> locator;
  best_of("locator of psi's image", R,
          [&] { locator.reset(new DI::Planar_point_locator(psi.image, mapper->chart().open_faces)); });
  best_of("psi^-1 at every vertex", R,
          [&] { (void)mapper->inverse_correction(*locator, psi, mapper->planar_chart()); });
  const DI::Vector source_area = DI::face_areas(X, F);
  DI::Matrix f;
  best_of("evaluate_ellipsoidal_conformal (total)", R,
          [&] { f = DI::evaluate_ellipsoidal_conformal(*mapper, radii, source_area, true).f; });
  best_of("exact fold-over count of the ellipsoidal map", R,
          [&] { (void)DI::count_inverted_faces_about_center(f, F); });
  return 0;
}
