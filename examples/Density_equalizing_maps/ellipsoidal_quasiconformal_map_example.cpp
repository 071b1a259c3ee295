// Landmark-aligned quasi-conformal map onto an ellipsoid (FEQCM): a few
// vertices are pulled toward prescribed points on the ellipsoid; a larger
// landmark weight lambda matches them better at the price of more distortion.
// Usage: ellipsoidal_quasiconformal_map_example [mesh.off]
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/generators.h>

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <utility>
#include <vector>

typedef CGAL::Simple_cartesian<double> K;
typedef K::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef boost::graph_traits<Mesh>::vertex_descriptor vertex_descriptor;
namespace DEM = CGAL::Density_equalizing_maps;

int main(int argc, char** argv)
{
  Mesh mesh;
  if(argc > 1) {
    if(!CGAL::IO::read_polygon_mesh(argv[1], mesh)) {
      std::cerr << "cannot read " << argv[1] << "\n";
      return EXIT_FAILURE;
    }
  } else {
    CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.);
  }

  const std::array<double, 3> radii = {1., 1., 1.5};
  auto ellipsoid = mesh.add_property_map<vertex_descriptor, Point_3>("v:ellipsoid").first;
  try {
    // Where the conformal map puts the vertices...
    DEM::ellipsoidal_conformal_map(mesh, ellipsoid, DEM::parameters::ellipsoid_radii(radii));

    // ...and landmarks: three vertices, each sent to its conformal image
    // rotated by 30 degrees about the z axis (targets lie on the ellipsoid).
    std::vector<std::pair<vertex_descriptor, Point_3>> landmarks;
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    std::size_t step = std::max<std::size_t>(1, num_vertices(mesh) / 3), k = 0;
    for(vertex_descriptor v : vertices(mesh)) {
      if(k++ % step != 0 || landmarks.size() == 3) continue;
      const Point_3 p = get(ellipsoid, v);
      const double x = c * p.x() - s * p.y(), y = s * p.x() + c * p.y();
      // the rotated point is scaled back onto the ellipsoid (a = b here, so it already is)
      landmarks.emplace_back(v, Point_3(x, y, p.z()));
    }

    for(double lambda : {0.1, 1., 10.}) {
      const DEM::Map_report report = DEM::ellipsoidal_quasiconformal_map(
        mesh, landmarks, ellipsoid,
        DEM::parameters::combine(DEM::parameters::ellipsoid_radii(radii), DEM::parameters::landmark_weight(lambda)));
      std::cout << "lambda " << lambda << ": mean landmark error " << report.landmark_error << ", fold-overs "
                << report.fold_overs << "\n";
    }
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << "\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
