// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_LANDMARK_PAIRS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_LANDMARK_PAIRS_H

/// \file landmark_pairs.h
/// Reader of the landmark pairs of `register_surfaces()`: one pair per line,
/// `source_vertex target_vertex` (0-based indices in the order of the two mesh
/// files), `#` comments and blank lines as in the other sidecar files.

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>

#include <istream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// Reads landmark pairs `source_vertex target_vertex`. Rejects a malformed line, an index out
/// of range of its mesh (when the vertex count is not zero), a pair given twice and a vertex of
/// either side in two pairs, and fewer than 3 pairs; every message names the source and the line.
/// \param in the stream
/// \param source_vertices number of vertices of the source mesh, or 0 for no check
/// \param target_vertices number of vertices of the target mesh, or 0 for no check
/// \param source name used in messages (e.g. the file name)
/// \returns the pairs (source index, target index) in file order
/// \throws Invalid_input naming the line and the problem
inline std::vector<std::pair<std::size_t, std::size_t> >
read_landmark_pairs(std::istream& in, std::size_t source_vertices = 0, std::size_t target_vertices = 0,
                    const std::string& source = "landmark pairs")
{
  std::vector<std::pair<std::size_t, std::size_t> > result;
  std::map<std::size_t, std::size_t> line_of_source, line_of_target;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> line_of_pair;
  internal::for_each_data_line(in, source, [&](std::size_t n, const std::string& line,
                                               const std::vector<std::string>& t) {
    std::size_t i = 0, j = 0;
    if(t.size() != 2 || !internal::parse_index(t[0], i) || !internal::parse_index(t[1], j))
      throw Invalid_input(internal::where(source, n) + "expected \"source_vertex target_vertex\" (two indices), got \"" +
                          line + "\"");
    if(source_vertices > 0 && i >= source_vertices)
      throw Invalid_input(internal::where(source, n) + "source vertex " + std::to_string(i) +
                          " out of range (the source has " + std::to_string(source_vertices) + " vertices)");
    if(target_vertices > 0 && j >= target_vertices)
      throw Invalid_input(internal::where(source, n) + "target vertex " + std::to_string(j) +
                          " out of range (the target has " + std::to_string(target_vertices) + " vertices)");
    const auto p = line_of_pair.find({i, j});
    if(p != line_of_pair.end())
      throw Invalid_input(internal::where(source, n) + "duplicate pair " + std::to_string(i) + " " + std::to_string(j) +
                          " (first on line " + std::to_string(p->second) + ")");
    const auto s = line_of_source.find(i);
    if(s != line_of_source.end())
      throw Invalid_input(internal::where(source, n) + "source vertex " + std::to_string(i) +
                          " is already paired on line " + std::to_string(s->second));
    const auto d = line_of_target.find(j);
    if(d != line_of_target.end())
      throw Invalid_input(internal::where(source, n) + "target vertex " + std::to_string(j) +
                          " is already paired on line " + std::to_string(d->second));
    line_of_pair.emplace(std::make_pair(i, j), n);
    line_of_source.emplace(i, n);
    line_of_target.emplace(j, n);
    result.emplace_back(i, j);
  });
  if(result.size() < 3)
    throw Invalid_input(source + ": " + std::to_string(result.size()) +
                        " landmark pair(s); registration needs at least 3");
  return result;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// File version of `read_landmark_pairs()`.
/// \param filename the file to read
/// \param source_vertices number of vertices of the source mesh, or 0 for no check
/// \param target_vertices number of vertices of the target mesh, or 0 for no check
/// \returns the pairs in file order
inline std::vector<std::pair<std::size_t, std::size_t> >
read_landmark_pairs(const std::string& filename, std::size_t source_vertices, std::size_t target_vertices)
{
  std::vector<std::pair<std::size_t, std::size_t> > v;
  internal::read_from_file(filename, [&](std::istream& in, const std::string& s) {
    v = read_landmark_pairs(in, source_vertices, target_vertices, s);
  });
  return v;
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_LANDMARK_PAIRS_H
