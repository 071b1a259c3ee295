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
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch(const std::exception& e) {
    ok = false;
    const std::string cause = diagnose_mesh_file(path);
    throw Invalid_input("cannot read " + path + ": " + (cause.empty() ? std::string(e.what()) : cause));
  }
  if(!ok || polygons.empty()) {
    const std::string cause = diagnose_mesh_file(path);
    throw Invalid_input("cannot read a mesh from " + path + ": " +
                        (cause.empty() ? std::string(polygons.empty() && ok ? "no face"
                                                                            : "unknown format or syntax error")
                                       : cause));
  }
  // CGAL's readers accept some files the scan refuses (OBJ indices past the
  // end are kept as they are, "nan" parses): name the cause with its line.
  auto refuse = [&](const std::string& fallback) {
    const std::string cause = diagnose_mesh_file(path);
    throw Invalid_input("cannot read a mesh from " + path + ": " + (cause.empty() ? fallback : cause));
  };
  for(std::size_t k = 0; k < polygons.size(); ++k)
    for(std::size_t v : polygons[k])
      if(v >= points.size())
        refuse("face " + std::to_string(k) + ": vertex index " + std::to_string(v) + " out of range");
  // the STL reader merges equal corners, and a NaN corner can vanish in the
  // merge: scan STL files even when they were read
  if(std::filesystem::path(path).extension().string() == ".stl" ||
     std::filesystem::path(path).extension().string() == ".STL") {
    const std::string cause = diagnose_mesh_file(path);
    if(!cause.empty()) throw Invalid_input("cannot read a mesh from " + path + ": " + cause);
  }
  for(std::size_t i = 0; i < points.size(); ++i)
    if(!std::isfinite(CGAL::to_double(points[i].x())) || !std::isfinite(CGAL::to_double(points[i].y())) ||
       !std::isfinite(CGAL::to_double(points[i].z())))
      refuse("non-finite coordinate at vertex " + std::to_string(i));
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
