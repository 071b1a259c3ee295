// Diagnostic probe of issue 14 item 2 (extreme populations), see README.md here.
#include <CGAL/Density_equalizing_maps/spherical_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/ellipsoidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/measures.h>
#include "dem_test_meshes.h"
namespace DEM = CGAL::Density_equalizing_maps;
namespace PM = CGAL::Density_equalizing_maps::parameters;
using namespace dem_test;
typedef Mesh::Property_map<vertex_descriptor, Point> Point_map;
typedef Mesh::Property_map<face_descriptor, double> Face_map;
Face_map population(Mesh& m, double ratio, bool step, double unit = 1)
{
  Face_map p = m.add_property_map<face_descriptor, double>("f:population", 0.).first;
  for(auto f : m.faces()) {
    std::vector<Eigen::Vector3d> c;
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      c.emplace_back(m.point(v).x(), m.point(v).y(), m.point(v).z());
    const Eigen::Vector3d g = (c[0] + c[1] + c[2]) / (3 * unit);
    const double area = 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm();
    const double rho = step ? (g.x() > 0.3 ? ratio : 1.)
                            : std::exp(std::log(ratio) * std::exp(-((g - Eigen::Vector3d(1, 0, 0)).squaredNorm()) / 0.18));
    p[f] = rho * area;
  }
  return p;
}
int main(int argc, char** argv)
{
  std::string method = argv[1];
  int sub = std::atoi(argv[2]);
  double ratio = std::atof(argv[3]);
  bool step = std::string(argv[4]) == "step";
  double dt = argc > 5 ? std::atof(argv[5]) : 0.1;
  int maxit = argc > 6 ? std::atoi(argv[6]) : 200;
  Mesh m = method == "tdem" ? to_mesh(torus_arrays(3, 1, 40, 20)) : to_mesh(icosphere_arrays(sub));
  Face_map p = population(m, ratio, step, method == "tdem" ? 3 : 1);
  Point_map out = m.add_property_map<vertex_descriptor, Point>("v:out").first;
  Stopwatch clock;
  auto cb = [](std::size_t it, double e) { if(std::getenv("DEM_VERBOSE")) std::cout << "it " << it << " err " << e << "\n"; return true; };
  DEM::Map_report r;
  if(method == "sdem")
    r = DEM::spherical_density_equalizing_map(m, out, PM::combine(PM::face_population_map(p), PM::time_step(dt), PM::number_of_iterations(maxit), PM::progress_callback(cb)));
  else if(method == "edem")
    r = DEM::ellipsoidal_density_equalizing_map(m, out, PM::combine(PM::face_population_map(p), PM::time_step(dt), PM::number_of_iterations(maxit), PM::progress_callback(cb), PM::ellipsoid_radii(std::array<double,3>{1,1,1})));
  else
    r = DEM::toroidal_density_equalizing_map(m, out, PM::combine(PM::face_population_map(p), PM::time_step(dt), PM::number_of_iterations(maxit), PM::progress_callback(cb), PM::torus_radii(std::array<double,2>{3,1})));
  double secs = clock.seconds();
  std::cout << method << " sub " << sub << " " << (step ? "step" : "bump") << " " << ratio << " dt " << dt << ": " << secs << " s, "
            << r.iterations << " it, " << DEM::to_string(r.termination) << ", err " << r.initial_error << " -> " << r.final_error
            << ", halvings " << r.step_halvings << ", repairs " << r.repairs << ", folds " << r.fold_overs << " msg: " << r.message << "\n";
}
