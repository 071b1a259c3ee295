// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A globe cartogram (paper 001 Sec. 5.3): three regions of the globe, one across
// the antimeridian and one around the south pole, with values 6 : 3 : 1; the
// rest of the globe is sea with the mean land density. After the map, each
// region's share of the land area is its share of the values, and the region
// borders are carried through the map. The globe is built for the regions
// (make_cartogram_globe): a coarse geodesic sphere snapped to their borders,
// subdivided, so that the cartogram can run coarse to fine. (`dem cartogram`
// does the same from GeoJSON and CSV files.)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Density_equalizing_maps/globe_cartogram.h>

#include <iostream>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace DEM = CGAL::Density_equalizing_maps;

int main()
{
  // rings of (longitude, latitude), great-circle edges; each encloses its smaller side
  auto region = [](const char* id, std::vector<DEM::Lon_lat> ring) {
    DEM::Spherical_region r;
    r.id = id;
    r.polygons.push_back(DEM::Spherical_polygon{{ring}});
    return r;
  };
  std::vector<DEM::Lon_lat> south;
  for(int k = 0; k < 36; ++k) south.push_back({-180. + 10 * k, -65.});
  const std::vector<DEM::Spherical_region> regions = {
    region("Pacific", {{150, -30}, {-150, -30}, {-150, 30}, {150, 30}}), // across the antimeridian
    region("Eurasia", {{0, 20}, {90, 20}, {90, 70}, {0, 70}}),
    region("Antarctica", south)};                                        // around the south pole
  const std::vector<double> values = {6, 3, 1};

  // about 20,000 vertices: two midpoint subdivisions of a coarse globe whose vertices
  // next to a border are moved onto it (no face holds a thin sliver of a region)
  Mesh globe;
  const DEM::Cartogram_globe built = DEM::make_cartogram_globe(globe, regions, 20000);

  // the passes run on the coarse globe, the map is carried up and corrected on each globe
  auto cartogram = globe.add_property_map<Mesh::Vertex_index, K::Point_3>("v:cartogram").first;
  const DEM::Globe_cartogram_report r = DEM::globe_cartogram(
    globe, regions, values, cartogram, DEM::parameters::coarse_globe_vertices(built.coarse_globe_vertices));
  for(std::size_t k = 0; k < regions.size(); ++k)
    std::cout << regions[k].id << ": value share " << r.value_share[k] << ", land area share " << r.area_share[k]
              << " before the map " << r.populations.region_area[k] / r.populations.land_area << "\n";
  std::cout << globe.number_of_vertices() << " vertices from a coarse globe of " << built.coarse_globe_vertices
            << ", " << r.passes << " passes on it, largest relative area error " << r.max_relative_error << ", "
            << r.fold_overs << " fold-overs\n";

  const std::vector<DEM::Spherical_region> moved = DEM::push_forward_region_boundaries(globe, cartogram, regions);
  std::cout << "the Pacific border has " << moved[0].polygons[0].rings[0].size() << " points on the cartogram\n";
  // the output polygons measured as spherical polygons, as a reader of them would
  const std::vector<double> area = DEM::pushed_forward_region_areas(regions, moved);
  std::cout << "the Pacific's area on the cartogram: " << area[0] << " (of 4 pi)\n";
  return r.fold_overs == 0 ? 0 : 1;
}
