// spherical_conformal_map (FLASH) and mobius_area_correction on generated
// genus-0 meshes and, with `--shared` (ctest test_spherical_conformal_shared,
// label shared_data), on the papers' meshes:
// bijective (exact fold-over count 0), on the unit sphere, nearly conformal,
// the Moebius correction lowers the area distortion, and a user-chosen solver
// gives the same map.

#include <CGAL/Density_equalizing_maps/measures.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>

#include <cmath>
#include <limits>

#include "dem_test_meshes.h"

namespace DEM = CGAL::Density_equalizing_maps;
namespace params = CGAL::Density_equalizing_maps::parameters;
using namespace dem_test;

namespace {

typedef CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<CGAL::Eigen_sparse_matrix<double>::EigenType> > Ldlt_traits;
typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;

double max_unit_deviation(const Mesh& m, Point_map s)
{
  double e = 0;
  for(auto v : m.vertices()) e = std::max(e, std::abs(std::sqrt(CGAL::to_double(s[v].x() * s[v].x() + s[v].y() * s[v].y() +
                                                                                s[v].z() * s[v].z())) - 1));
  return e;
}

double max_distance(const Mesh& m, Point_map a, Point_map b)
{
  double e = 0;
  for(auto v : m.vertices()) e = std::max(e, std::sqrt(CGAL::squared_distance(a[v], b[v])));
  return e;
}

// mu_bound: bound on the mean |mu| of the conformal map; shared: the mesh is
// one of the papers' (then the Moebius correction must strictly help);
// solver_tolerance: how close the map with SimplicialLDLT must be to the
// default solver's. FLASH pins the 10% of vertices nearest the south pole:
// on a mesh with exact mirror symmetries (icosphere, ellipsoid) vertices of
// equal height compete for the last pinned slot and rounding (hence the solver)
// decides which is pinned, which moves the map by ~1e-4. Perturbing the
// ellipsoid's vertices by 1e-9 brings both solvers to 5e-12 of each other.
double mean_abs_mu_of(Mesh m)
{
  Point_map s = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
  DEM::spherical_conformal_map(m, s);
  return DEM::map_distortion(m, s).mean_abs_mu;
}

void check_mesh(Mesh& m, const std::string& name, double mu_bound, bool shared, double solver_tolerance = 1e-8)
{
  Stopwatch clock;
  Point_map s = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
  const DEM::Map_report r = DEM::spherical_conformal_map(m, s);
  const double t_map = clock.seconds();
  const std::size_t folds = DEM::number_of_fold_overs(m, s);
  check(folds == 0, name + ": 0 fold-overs (" + std::to_string(folds) + ")");
  check(r.fold_overs == folds, name + ": report.fold_overs is the exact count");
  check(!r.used_tutte_fallback, name + ": no Tutte fallback needed");
  const double dev = max_unit_deviation(m, s);
  check(dev < 1e-12, name + ": on the unit sphere (" + std::to_string(dev) + ")");
  const DEM::Distortion_statistics d = DEM::map_distortion(m, s);
  check(d.mean_abs_mu <= mu_bound,
        name + ": mean |mu| " + std::to_string(d.mean_abs_mu) + " <= " + std::to_string(mu_bound));

  // Moebius area correction through the named parameter
  Point_map q = m.add_property_map<vertex_descriptor, Point>("v:mobius").first;
  Stopwatch clock2;
  const DEM::Map_report rq = DEM::spherical_conformal_map(m, q, params::mobius_area_correction(true));
  const double t_mobius = clock2.seconds();
  const DEM::Distortion_statistics dq = DEM::map_distortion(m, q);
  check(DEM::number_of_fold_overs(m, q) == 0 && rq.fold_overs == 0, name + ": Moebius-corrected map has 0 fold-overs");
  check(max_unit_deviation(m, q) < 1e-12, name + ": Moebius-corrected map on the unit sphere");
  // (on the generated meshes "not higher" is the library's own guard, not a
  // test: the correction's own case is the Moebius-dilated icosphere in main)
  if(shared)
    check(dq.mean_abs_darea < d.mean_abs_darea, name + ": Moebius correction lowers mean |d_area|");
  // a Moebius map is conformal: |mu| may only change by the discretization
  check(dq.mean_abs_mu <= mu_bound + 0.02, name + ": Moebius-corrected mean |mu| stays small");

  // a user-supplied solver gives the same map
  Point_map u = m.add_property_map<vertex_descriptor, Point>("v:ldlt").first;
  Stopwatch clock3;
  DEM::spherical_conformal_map(m, u, params::sparse_linear_solver(Ldlt_traits()));
  const double t_ldlt = clock3.seconds();
  const double diff = max_distance(m, s, u);
  check(diff <= solver_tolerance, name + ": SimplicialLDLT traits give the same map (" + std::to_string(diff) + ")");
  check(DEM::number_of_fold_overs(m, u) == 0, name + ": SimplicialLDLT map has 0 fold-overs");

  std::printf("%-16s %6zu v  mean|mu| %.4f (sd %.4f)  mean|darea| %.4f -> Moebius %.4f  max|1-|p|| %.1e  "
              "map %.2fs, with Moebius %.2fs, LDLT %.2fs\n",
              name.c_str(), static_cast<std::size_t>(m.number_of_vertices()), d.mean_abs_mu, d.sd_abs_mu,
              d.mean_abs_darea, dq.mean_abs_darea, dev, t_map, t_mobius, t_ldlt);
  m.remove_property_map(s);
  m.remove_property_map(q);
  m.remove_property_map(u);
}

// FLASH's south cap chosen before the north step (one factorization of the
// Laplacian serves both steps with the default solver; from
// one_factorization_min_vertices vertices on): the map is fold-free, and
// SimplicialLDLT, which factors the south system on its own, gives the same
// map, also on an icosphere whose mirror symmetries make many vertices tie
// (the cap is chosen by edge distance, ties by index, not by the solver).
// Below the threshold the rule by size is the reference's cap, to the bit.
void check_cap_chosen_first()
{
  namespace I = DEM::internal;
  const std::unique_ptr<I::Spd_solver> default_solver = I::make_default_spd_solver();
  const std::unique_ptr<I::Spd_solver> ldlt = I::make_spd_solver(Ldlt_traits());
  const std::pair<std::string, Arrays> meshes[] = {{"bumpy(5)", bumpy_arrays(5)}, {"icosphere(4)", icosphere_arrays(4)}};
  for(const auto& [name, a] : meshes) {
    const I::Flash_result f = I::flash_spherical_map(a.X, a.F, *default_solver, {}, I::South_cap_rule::chosen_first);
    const I::Flash_result g = I::flash_spherical_map(a.X, a.F, *ldlt, {}, I::South_cap_rule::chosen_first);
    check(I::count_inverted_faces_about_center(f.S, a.F) == 0 && f.fallback.empty() && !f.tutte,
          name + ", cap chosen first: 0 inverted faces, no fallback");
    const double diff = (f.S - g.S).cwiseAbs().maxCoeff();
    check(diff <= 1e-8, name + ", cap chosen first: SimplicialLDLT gives the same map (" + std::to_string(diff) + ")");
    const I::Flash_result by_size = I::flash_spherical_map(a.X, a.F, *default_solver);
    const I::Flash_result reference =
      I::flash_spherical_map(a.X, a.F, *default_solver, {}, I::South_cap_rule::reference);
    check(a.X.rows() >= I::one_factorization_min_vertices || by_size.S == reference.S,
          name + ": below the threshold the rule by size is the reference's cap");
  }
  // above the threshold, through the public function: 40,962 vertices
  Mesh m = bumpy(6);
  check(Eigen::Index(m.number_of_vertices()) >= I::one_factorization_min_vertices, "bumpy(6) is above the threshold");
  check_mesh(m, "bumpy(6)", 0.03, false);
}

// The Moebius correction searches on a sample of about 4,000 faces, then
// polishes on all faces (below 32,000 faces) or on a sample of about 16,000
// and all faces. Its objective (mean |log area ratio| on all faces) must end
// where a long Nelder-Mead search on all faces ends, from the identity to a
// simplex of 1e-9: within 1e-6, a millionth of a unit of log area ratio, far
// below what the maps' figures show. Without the polish on all faces
// bumpy(5)'s search ends 3e-6 above. (The stopping point itself is guarded by
// test_hard_inputs' maps of inputs scaled by 1e+-100: a search on smaller
// samples that passed this check moved those maps by 3e-4; benchmark/RESULTS.md,
// "The Moebius search on smaller samples".)
void check_mobius_search_precision()
{
  namespace I = DEM::internal;
  const auto solver = I::make_default_spd_solver();
  for(const auto& [name, a] : {std::pair<std::string, Arrays>{"bumpy(5)", bumpy_arrays(5)}, {"bumpy(4)", bumpy_arrays(4)}}) {
    const I::Flash_result flash = I::flash_spherical_map(a.X, a.F, *solver);
    const I::Vector area = I::face_areas(a.X, a.F);
    double before = 0, searched = 0;
    (void)I::mobius_correction(area, a.F, flash.S, &before, &searched);
    I::Moebius_area_objective on_all(I::face_sample(a.F, area, a.X.rows(), 1), I::north_chart(flash.S), a.X.rows());
    const Eigen::Vector3d xi = I::nelder_mead_3(std::ref(on_all), Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d(0.2, 0.2, 0.5), 2000, 1e-12, 1e-9);
    const double thorough = on_all(xi);
    std::printf("%s: Moebius objective %.12f -> search %.12f, long search on all faces %.12f\n", name.c_str(), before,
                searched, thorough);
    check(searched < before, name + ": the Moebius search lowers the objective");
    check(searched <= thorough + 1e-6, name + ": the Moebius search ends within 1e-6 of a long search on all faces");
  }
}

// The Moebius search's image of a point (two divisions) is the point of the
// general functions, mobius_rotation_scaling() then the inverse stereographic
// projection, on the unit sphere, from the origin to near the pole and for the
// pole itself, for rotations, dilations and their limits.
void check_mobius_point_on_sphere()
{
  namespace I = DEM::internal;
  const double inf = std::numeric_limits<double>::infinity();
  const I::Complex points[] = {{0, 0}, {0.3, -0.2}, {-1, 0}, {0.7071, 0.7071}, {2.5, 1e-3}, {-40, 7},
                               {1e-9, -1e-9}, {3e7, -2e7}, {1e140, 1e140}, {inf, 0}};
  const I::Complex centres[] = {{0, 0}, {0.4, -0.1}, {-2, 3}, {1e-3, 0}};
  double worst = 0;
  bool on_sphere = true;
  for(const I::Complex& w0 : centres)
    for(const double s : {-30., -2., 0., 0.7, 30.})
      for(const I::Complex& z : points) {
        const Eigen::Vector3d fast = I::mobius_point_on_sphere(z, w0, std::exp(s));
        const Eigen::Vector3d general = I::inverse_north_stereographic(I::mobius_rotation_scaling(z, w0, std::exp(s)));
        worst = std::max(worst, (fast - general).norm());
        on_sphere = on_sphere && std::abs(fast.norm() - 1) <= 1e-14;
      }
  check(worst <= 1e-13, "the Moebius search's image is the general functions' point (" + std::to_string(worst) + ")");
  check(on_sphere, "the Moebius search's image lies on the unit sphere");
}

} // namespace

int shared_part();

int main(int argc, char** argv)
{
  if(shared_part_requested(argc, argv)) return run_shared_part("maxplanck.off", shared_part);
  Stopwatch clock;
  check_mobius_point_on_sphere();
  check_mobius_search_precision();
  {
    Mesh m = icosphere(4);
    check_mesh(m, "icosphere(4)", 0.01, false, 1e-3);
  }
  {
    Mesh m = ellipsoid(1, 1.5, 3, 4);
    check_mesh(m, "ellipsoid 1:1.5:3", 0.03, false, 1e-3);
  }
  {
    Mesh m = bumpy(4);
    check_mesh(m, "bumpy", 0.03, false);
  }
  check_cap_chosen_first();
  {
    // a bumpy cigar 4 times longer than wide: its long thin triangles give a
    // larger discretization error, which halves with each subdivision
    // (0.169, 0.078, 0.038 for 3, 4, 5 subdivisions)
    Mesh m = elongated(4);
    check_mesh(m, "elongated", 0.1, false);
    const double coarse = mean_abs_mu_of(elongated(3)), fine = mean_abs_mu_of(elongated(4));
    check(fine < 0.6 * coarse, "elongated: mean |mu| converges with refinement (" + std::to_string(coarse) + " -> " +
                                 std::to_string(fine) + ")");
  }

  // Coarse, strongly stretched meshes have many obtuse angles (about a quarter
  // of the edges get a negative cotangent weight) and the cotangent harmonic
  // north step folds (93 of 1280 faces for the 4:1 cigar below, 141 for
  // 10:1); the map then starts from the Tutte embedding and is repaired
  // towards the conformal one: the output must be bijective.
  for(double elongation : {4., 10.}) {
    Mesh m = to_mesh(bumpy_arrays(2, 0.15, elongation));
    Point_map s = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
    const DEM::Map_report r = DEM::spherical_conformal_map(m, s);
    const std::size_t n = DEM::number_of_fold_overs(m, s);
    const double mu = DEM::map_distortion(m, s).mean_abs_mu;
    std::cout << "coarse cigar " << elongation << ":1: " << n << " fold-overs, Tutte fallback "
              << r.used_tutte_fallback << ", repairs " << r.repairs << ", mean|mu| " << mu << std::endl;
    check(r.used_tutte_fallback, "coarse cigar: the harmonic north step folds (Tutte fallback used)");
    // The step from the Tutte map to the (folded) harmonic one is untangled
    // and, where that fails, halved. Measured: mean |mu| 0.509 (4:1) and 0.776
    // (10:1); until 2026-12 a two-chart LBS repair ran first and gave 0.519 and
    // 0.763 (benchmark/RESULTS.md, "Repairs and fallbacks"): the bounds sit
    // above both.
    check(mu <= (elongation == 4. ? 0.55 : 0.81), "coarse cigar: mean |mu| of the repaired map");
    check(r.fold_overs == n, "coarse cigar: report.fold_overs is the exact count");
    check(n == 0, "coarse cigar: the Tutte-started repair makes the map bijective");
    check(max_unit_deviation(m, s) < 1e-12, "coarse cigar: on the unit sphere");
  }

  // The Moebius correction's own case: a unit sphere whose vertices were moved
  // by a Moebius dilation (x3 in the stereographic chart). Every conformal map
  // of it onto the sphere is a Moebius map; FLASH's leaves a large area
  // distortion (measured 1.25) that only the right Moebius map removes
  // (measured 0.004 after the correction).
  {
    Mesh m = to_mesh(mobius_dilated_icosphere_arrays(4, 3.));
    Point_map s = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
    Point_map q = m.add_property_map<vertex_descriptor, Point>("v:mobius").first;
    DEM::spherical_conformal_map(m, s);
    const DEM::Map_report r = DEM::mobius_area_correction(m, s, q);
    const double before = DEM::map_distortion(m, s).mean_abs_darea, after = DEM::map_distortion(m, q).mean_abs_darea;
    std::cout << "Moebius-dilated icosphere: mean|d_area| conformal " << before << ", Moebius-corrected " << after
              << std::endl;
    check(before > 0.5, "Moebius-dilated icosphere: the conformal map leaves a large area distortion");
    check(after < 0.05 * before && after < 0.02, "Moebius correction removes the area distortion of a Moebius image");
    check(r.fold_overs == 0 && DEM::number_of_fold_overs(m, q) == 0, "Moebius correction: 0 fold-overs");
    check(max_unit_deviation(m, q) < 1e-12, "Moebius correction: on the unit sphere");
    check(DEM::map_distortion(m, q).mean_abs_mu <= DEM::map_distortion(m, s).mean_abs_mu + 0.005,
          "Moebius correction keeps the map conformal");
    // non-finite input is the caller's fault
    put(s, vertex_descriptor(5), Point(std::numeric_limits<double>::quiet_NaN(), 0, 0));
    Point_map q2 = m.add_property_map<vertex_descriptor, Point>("v:mobius2", output_sentinel()).first;
    const std::string msg =
      expect_throw<DEM::Invalid_input>([&] { DEM::mobius_area_correction(m, s, q2); }, "NaN spherical map");
    std::cout << "mobius_area_correction of a NaN map: " << msg << std::endl;
    check(contains(msg, "non-finite"), "mobius_area_correction of a NaN map: message says non-finite");
    check(untouched(m, q2), "mobius_area_correction of a NaN map: nothing written");
  }

  // the public Moebius correction agrees with the named-parameter route
  {
    Mesh m = ellipsoid(1, 1.5, 3, 3);
    Point_map s = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
    Point_map q = m.add_property_map<vertex_descriptor, Point>("v:mobius").first;
    Point_map q2 = m.add_property_map<vertex_descriptor, Point>("v:mobius2").first;
    DEM::spherical_conformal_map(m, s);
    DEM::spherical_conformal_map(m, q, params::mobius_area_correction(true));
    const DEM::Map_report r = DEM::mobius_area_correction(m, s, q2);
    check(r.fold_overs == 0 && DEM::number_of_fold_overs(m, q2) == 0, "mobius_area_correction: 0 fold-overs");
    const double a1 = DEM::map_distortion(m, q).mean_abs_darea, a2 = DEM::map_distortion(m, q2).mean_abs_darea;
    check(std::abs(a1 - a2) <= 1e-6 * a1, "mobius_area_correction() matches mobius_area_correction(true)");
    // in place: the input and output map may be the same
    DEM::mobius_area_correction(m, s, s);
    check(std::abs(DEM::map_distortion(m, s).mean_abs_darea - a2) <= 1e-6 * a2, "mobius_area_correction in place");
  }

  std::cout << "time " << clock.seconds() << " s" << std::endl;
  return finish("test_spherical_conformal");
}

// --shared (ctest test_spherical_conformal_shared, label shared_data): the
// papers' meshes (FLASH paper: mean |mu| about 0.02-0.04).
int shared_part()
{
  for(const char* name : {"maxplanck", "twistedball", "brain_landmarks"}) {
    Mesh m;
    if(!check(load_shared_mesh(name, m), std::string("read ") + name)) continue;
    check_mesh(m, name, 0.05, true);
  }
  return finish("test_spherical_conformal --shared");
}
