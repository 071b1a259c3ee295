// Timing of TDEM on the shared tdem_torus_* meshes and of the toroidal
// parameterization of bob_genus1 (automatic tree-cotree cut and the authors'
// cut), at the default settings. Usage: bench_toroidal [data_dir] [repeats]
#include <CGAL/Density_equalizing_maps/internal/openblas.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace DEM = CGAL::Density_equalizing_maps;
namespace PM = DEM::parameters;
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;

static std::map<std::string, double> read_params(const std::string& path)
{
  std::map<std::string, double> p;
  std::ifstream in(path);
  std::string line;
  while(std::getline(in, line)) {
    const auto eq = line.find('=');
    if(eq != std::string::npos) p[line.substr(0, eq)] = std::stod(line.substr(eq + 1));
  }
  return p;
}

static std::vector<double> read_values(const std::string& path)
{
  std::ifstream in(path);
  std::vector<double> v;
  double x;
  while(in >> x) v.push_back(x);
  return v;
}

// normalized vertex density variance and mean |d_area| of the output
static void measures(const Mesh& m, const Mesh::Property_map<vertex_descriptor, K::Point_3>& out,
                     const std::vector<double>& population, double& var, double& darea)
{
  using namespace DEM::internal;
  Matrix X(m.number_of_vertices(), 3), Y(m.number_of_vertices(), 3);
  Index_matrix F(m.number_of_faces(), 3);
  for(auto v : m.vertices()) {
    X.row(v.idx()) << m.point(v).x(), m.point(v).y(), m.point(v).z();
    Y.row(v.idx()) << out[v].x(), out[v].y(), out[v].z();
  }
  for(auto f : m.faces()) {
    int c = 0;
    for(auto v : vertices_around_face(m.halfedge(f), m)) F(f.idx(), c++) = int(v.idx());
  }
  const Vector img = face_areas(Y, F), src = face_areas(X, F);
  Vector P = population.empty() ? src : Vector(Eigen::Map<const Vector>(population.data(), population.size()));
  // density uses the flat face-to-vertex weights in TDEM; the 3D ones are close and suffice here
  var = -1;
  darea = log_area_ratio(src, img).cwiseAbs().mean();
  (void)P;
}

int main(int argc, char** argv)
{
  // the BLAS kernels of this CPU, as dem runs them (internal/openblas.h)
  CGAL::Density_equalizing_maps::internal::restart_with_openblas_kernels_of_this_cpu(argv);
  const std::string dir = argc > 1 ? argv[1] : "../shared/data";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  const char* names[] = {"tdem_torus_0", "tdem_torus_1", "tdem_torus_2", "tdem_torus_3", "tdem_torus_4",
                         "tdem_torus_5_1", "tdem_torus_5_2", "tdem_torus_R2", "tdem_torus_R4", "tdem_torus_R6",
                         "tdem_torus_R8", "tdem_torus_R10"};
  std::cout << std::setprecision(4);
  for(const char* name : names) {
    Mesh m;
    if(!CGAL::IO::read_polygon_mesh(dir + "/" + name + ".off", m)) { std::cerr << "cannot read " << name << "\n"; return 1; }
    auto params = read_params(dir + "/" + name + ".params.txt");
    const std::vector<double> pop = read_values(dir + "/" + name + ".population.txt");
    auto pmap = m.add_property_map<Mesh::Face_index, double>("f:pop").first;
    for(auto f : m.faces()) pmap[f] = pop[f.idx()];
    auto out = m.add_property_map<vertex_descriptor, K::Point_3>("v:out").first;
    double best = 1e30, best_cpu = 1e30;
    DEM::Map_report r;
    for(int k = 0; k < repeats; ++k) {
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      r = DEM::toroidal_density_equalizing_map(
        m, out, PM::combine(PM::torus_radii(std::array<double, 2>{params["R"], params["r"]}), PM::face_population_map(pmap)));
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      best_cpu = std::min(best_cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    std::cout << name << ": iterations " << r.iterations << " (" << DEM::to_string(r.termination)
              << "), final Var " << r.final_error * r.final_error << ", fold-overs " << r.fold_overs
              << ", repairs " << r.repairs << ", time " << best << " s (cpu " << best_cpu << " s)\n";
  }
  Mesh bob;
  if(!CGAL::IO::read_polygon_mesh(dir + "/bob_genus1.off", bob)) { std::cerr << "cannot read bob\n"; return 1; }
  auto params = read_params(dir + "/bob_genus1.params.txt");
  std::vector<std::pair<vertex_descriptor, vertex_descriptor> > cut;
  {
    std::ifstream in(dir + "/bob_genus1.cut_edges.txt");
    std::string line;
    while(std::getline(in, line)) {
      if(line.empty() || line[0] == '#') continue;
      std::istringstream s(line);
      int i, j;
      if(s >> i >> j) cut.emplace_back(vertex_descriptor(i), vertex_descriptor(j));
    }
  }
  auto out = bob.add_property_map<vertex_descriptor, K::Point_3>("v:out").first;
  const std::array<double, 2> radii{params["R"], params["r"]};
  for(int mode = 0; mode < 2; ++mode) {
    double best = 1e30, best_cpu = 1e30, var, darea = 0;
    DEM::Map_report r;
    for(int k = 0; k < repeats; ++k) {
      const std::clock_t c0 = std::clock();
      const auto t0 = std::chrono::steady_clock::now();
      if(mode == 0) r = DEM::toroidal_parameterization(bob, out, PM::torus_radii(radii));
      else r = DEM::toroidal_parameterization(bob, out, PM::combine(PM::torus_radii(radii), PM::cut_edges(cut)));
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      best_cpu = std::min(best_cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    measures(bob, out, {}, var, darea);
    std::cout << "bob_genus1 (" << (mode == 0 ? "tree-cotree" : "authors' cut") << "): iterations " << r.iterations
              << " (" << DEM::to_string(r.termination) << "), final sd/mean " << r.final_error << ", mean |d_area| "
              << darea << ", fold-overs " << r.fold_overs << ", repairs " << r.repairs << ", time " << best << " s (cpu "
              << best_cpu << " s)\n";
  }
  return 0;
}
