// Maps a genus-0 mesh conformally onto an ellipsoid: first with the
// bounding-box radii, then with radii optimized for low area distortion.
// Usage: ellipsoidal_conformal_map_example [mesh.off] [output.off]
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/boost/graph/generators.h>

#include <CGAL/Density_equalizing_maps/ellipsoidal_conformal_map.h>

#include <cstdlib>
#include <iostream>

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
  } else { // a stretched icosahedron
    CGAL::make_icosahedron(mesh, Point_3(0, 0, 0), 1.);
    for(vertex_descriptor v : vertices(mesh)) {
      const Point_3 p = mesh.point(v);
      mesh.point(v) = Point_3(p.x(), 0.7 * p.y(), 1.8 * p.z());
    }
  }

  auto ellipsoid = mesh.add_property_map<vertex_descriptor, Point_3>("v:ellipsoid").first;
  try {
    // Default: bounding-box radii of the centred, principal-axis aligned mesh (mean 1).
    DEM::Map_report report = DEM::ellipsoidal_conformal_map(mesh, ellipsoid);
    std::cout << "radii " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2]
              << ", fold-overs " << report.fold_overs << "\n";

    // Radii optimized for area distortion (the map stays conformal).
    report = DEM::ellipsoidal_conformal_map(mesh, ellipsoid, DEM::parameters::optimize_radii(true));
    std::cout << "optimized radii " << report.radii[0] << " " << report.radii[1] << " " << report.radii[2]
              << ", " << report.message << ", fold-overs " << report.fold_overs << "\n";
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "invalid input: " << e.what() << "\n";
    return EXIT_FAILURE;
  }

  if(argc > 2) {
    Mesh out = mesh;
    for(vertex_descriptor v : vertices(out)) out.point(v) = get(ellipsoid, v);
    CGAL::IO::write_polygon_mesh(argv[2], out, CGAL::parameters::stream_precision(17));
  }
  return EXIT_SUCCESS;
}
