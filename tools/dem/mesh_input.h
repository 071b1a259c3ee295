// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Reading the dem tool's input mesh as a polygon soup: CGAL reads it; if it
// cannot, the file is scanned for the cause (mesh_diagnosis.h); with
// --repair the soup goes through soup_repair.h first. Errors are thrown
// as Invalid_input (exit 3).

#ifndef DEM_TOOL_MESH_INPUT_H
#define DEM_TOOL_MESH_INPUT_H

#include "mesh_diagnosis.h"
#include "soup_repair.h"

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace dem_cli {

/// Reads `path` into a soup; throws `Invalid_input` naming the cause.
template <class Point>
void read_input_soup(const std::string& path, std::vector<Point>& points,
                     std::vector<std::vector<std::size_t> >& polygons)
{
  typedef CGAL::Density_equalizing_maps::Invalid_input Invalid_input;
  {
    std::ifstream probe(path);
    if(!probe) throw Invalid_input("cannot open " + path);
  }
  // The scan runs first: CGAL's readers trust the counts of a header (a face
  // announcing 999999999 corners took them 30 s) and one crashed on a PLY
  // header with a malformed element line (both found by test_cli_fuzz).
  {
    const std::string cause = diagnose_mesh_file(path);
    if(!cause.empty()) throw Invalid_input("cannot read a mesh from " + path + ": " + cause);
  }
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception& e) {
    throw Invalid_input("cannot read " + path + ": " + e.what());
  }
  if(!ok) throw Invalid_input("cannot read a mesh from " + path + " (unknown format or syntax error)");
  if(polygons.empty()) throw Invalid_input("no face in " + path);
  // Formats the scan does not know (and any reader's slip): the same facts.
  for(std::size_t k = 0; k < polygons.size(); ++k)
    for(std::size_t v : polygons[k])
      if(v >= points.size())
        throw Invalid_input("cannot read a mesh from " + path + ": face " + std::to_string(k) + ": vertex index " +
                            std::to_string(v) + " out of range");
  for(std::size_t i = 0; i < points.size(); ++i)
    if(!std::isfinite(CGAL::to_double(points[i].x())) || !std::isfinite(CGAL::to_double(points[i].y())) ||
       !std::isfinite(CGAL::to_double(points[i].z())))
      throw Invalid_input("cannot read a mesh from " + path + ": non-finite coordinate at vertex " + std::to_string(i));
}

/// The validation message, with a pointer to --repair where it can help.
inline std::string with_repair_hint(const std::string& message)
{
  const char* repairable[] = {"non-manifold", "orientation", "open boundary", "not connected", "degenerate",
                              "isolated", "repeated vertex"};
  for(const char* r : repairable)
    if(message.find(r) != std::string::npos)
      return message + " (dem --repair can merge duplicated vertices, remove duplicated and degenerate faces, "
                       "orient the faces consistently and keep the largest connected component)";
  return message;
}

} // namespace dem_cli

#endif // DEM_TOOL_MESH_INPUT_H
