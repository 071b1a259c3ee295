// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_SIDECAR_FILES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_SIDECAR_FILES_H

/// \file sidecar_files.h
/// Readers for the small text files that accompany a mesh: a per-face
/// population, landmarks, a cut graph and `key=value` parameters. They work on
/// 0-based indices in the order of the mesh file (the order in which
/// `CGAL::IO::read_polygon_soup()` returns points and faces, which
/// `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()` keeps for
/// `CGAL::Surface_mesh`). Common syntax: `#` starts a comment that runs to the
/// end of the line, blank lines are ignored, values are separated by blanks.
/// Every error throws `Invalid_input` whose message names the file (or
/// stream) and the 1-based line.

#include <CGAL/Density_equalizing_maps/Map_report.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// A landmark read from a file: a 0-based vertex index and its target point.
struct Indexed_landmark
{
  std::size_t vertex = 0;
  std::array<double, 3> target{{0., 0., 0.}};
  std::size_t line = 0; ///< 1-based line of the file, for messages
};

namespace internal {

/// The tokens of one logical line, comment stripped.
inline std::vector<std::string> tokens_of(const std::string& line)
{
  const std::string body = line.substr(0, line.find('#'));
  std::istringstream in(body);
  std::vector<std::string> t;
  std::string s;
  while(in >> s) t.push_back(s);
  return t;
}

inline std::string where(const std::string& source, std::size_t line)
{
  return source + " line " + std::to_string(line) + ": ";
}

/// Strict conversion: the whole token must be a finite or infinite/NaN
/// floating-point literal (checked by the caller).
inline bool parse_double(const std::string& s, double& value)
{
  if(s.empty()) return false;
  const char* b = s.c_str();
  char* e = nullptr;
  errno = 0;
  value = std::strtod(b, &e);
  return e == b + s.size() && errno != ERANGE;
}

/// Strict conversion of a non-negative integer (no sign, no fraction).
inline bool parse_index(const std::string& s, std::size_t& value)
{
  if(s.empty() || s.size() > 18) return false;
  value = 0;
  for(char c : s) {
    if(c < '0' || c > '9') return false;
    value = 10 * value + std::size_t(c - '0');
  }
  return true;
}

template <class Reader>
void read_from_file(const std::string& filename, Reader reader)
{
  std::ifstream in(filename);
  if(!in) throw Invalid_input("cannot open " + filename);
  reader(in, filename);
}

/// Calls `visit(line_number, line, tokens)` for every line of `in` that has
/// tokens once its comment is stripped (line numbers 1-based, counting the
/// blank and comment lines), then fails on a read error: the loop that every
/// sidecar reader shares.
template <class Visitor>
void for_each_data_line(std::istream& in, const std::string& source, Visitor visit)
{
  std::string line;
  std::size_t n = 0;
  while(std::getline(in, line)) {
    ++n;
    const std::vector<std::string> t = tokens_of(line);
    if(!t.empty()) visit(n, line, t);
  }
  if(in.bad()) throw Invalid_input(source + ": read error");
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// Reads one value per face (a population): one number per non-blank line.
/// Rejects a malformed line, a non-finite or non-positive value, and a count
/// different from `expected_count` (when it is not zero).
/// \param in the stream
/// \param expected_count number of faces of the mesh, or 0 for no check
/// \param source name used in messages (e.g. the file name)
/// \returns the values in file order
/// \throws Invalid_input naming the line and the problem
inline std::vector<double> read_face_values(std::istream& in, std::size_t expected_count = 0,
                                            const std::string& source = "population")
{
  std::vector<double> values;
  if(expected_count > 0) values.reserve(expected_count);
  internal::for_each_data_line(in, source, [&](std::size_t n, const std::string& line,
                                               const std::vector<std::string>& t) {
    double v = 0;
    if(t.size() != 1 || !internal::parse_double(t[0], v))
      throw Invalid_input(internal::where(source, n) + "expected one number, got \"" + line + "\"");
    if(!std::isfinite(v) || !(v > 0))
      throw Invalid_input(internal::where(source, n) + "value " + t[0] + " is not a positive finite number");
    values.push_back(v);
  });
  if(expected_count > 0 && values.size() != expected_count)
    throw Invalid_input(source + ": " + std::to_string(values.size()) + " values for " +
                        std::to_string(expected_count) + " faces (one value per face is needed)");
  return values;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// File version of `read_face_values()`; messages name the file.
/// \param filename the file to read
/// \param expected_count number of faces of the mesh, or 0 for no check
/// \returns the values in file order
inline std::vector<double> read_face_values(const std::string& filename, std::size_t expected_count)
{
  std::vector<double> v;
  internal::read_from_file(filename, [&](std::istream& in, const std::string& s) {
    v = read_face_values(in, expected_count, s);
  });
  return v;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Reads landmarks, lines `vertex_index x y z` (0-based index). Rejects
/// malformed lines, non-finite coordinates, an index `>= number_of_vertices`
/// (when that is not zero) and a vertex given twice. An empty file is an error.
/// \param in the stream
/// \param number_of_vertices number of vertices of the mesh, or 0 for no check
/// \param source name used in messages (e.g. the file name)
/// \returns the landmarks in file order
inline std::vector<Indexed_landmark> read_landmarks(std::istream& in, std::size_t number_of_vertices = 0,
                                                    const std::string& source = "landmarks")
{
  std::vector<Indexed_landmark> result;
  std::map<std::size_t, std::size_t> seen; // vertex -> line
  internal::for_each_data_line(in, source, [&](std::size_t n, const std::string& line,
                                               const std::vector<std::string>& t) {
    Indexed_landmark l;
    l.line = n;
    bool ok = t.size() == 4 && internal::parse_index(t[0], l.vertex);
    for(int c = 0; ok && c < 3; ++c) ok = internal::parse_double(t[c + 1], l.target[c]);
    if(!ok)
      throw Invalid_input(internal::where(source, n) + "expected \"vertex_index x y z\", got \"" + line + "\"");
    for(int c = 0; c < 3; ++c)
      if(!std::isfinite(l.target[c]))
        throw Invalid_input(internal::where(source, n) + "non-finite target coordinate");
    if(number_of_vertices > 0 && l.vertex >= number_of_vertices)
      throw Invalid_input(internal::where(source, n) + "landmark vertex " + std::to_string(l.vertex) +
                          " out of range (the mesh has " + std::to_string(number_of_vertices) + " vertices)");
    auto it = seen.find(l.vertex);
    if(it != seen.end())
      throw Invalid_input(internal::where(source, n) + "vertex " + std::to_string(l.vertex) +
                          " already has a landmark (line " + std::to_string(it->second) + ")");
    seen.emplace(l.vertex, n);
    result.push_back(l);
  });
  if(result.empty()) throw Invalid_input(source + ": no landmark");
  return result;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// File version of `read_landmarks()`.
/// \param filename the file to read
/// \param number_of_vertices number of vertices of the mesh, or 0 for no check
/// \returns the landmarks in file order
inline std::vector<Indexed_landmark> read_landmarks(const std::string& filename, std::size_t number_of_vertices)
{
  std::vector<Indexed_landmark> v;
  internal::read_from_file(filename, [&](std::istream& in, const std::string& s) {
    v = read_landmarks(in, number_of_vertices, s);
  });
  return v;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Reads vertex pairs `i j` (0-based), e.g. the edges of a cut graph. Rejects
/// malformed lines, an index `>= number_of_vertices` (when that is not zero)
/// and a pair `i i`. Whether the pairs are mesh edges is checked by the method.
/// \param in the stream
/// \param number_of_vertices number of vertices of the mesh, or 0 for no check
/// \param source name used in messages (e.g. the file name)
/// \returns the pairs in file order
inline std::vector<std::pair<std::size_t, std::size_t>>
read_vertex_pairs(std::istream& in, std::size_t number_of_vertices = 0, const std::string& source = "cut edges")
{
  std::vector<std::pair<std::size_t, std::size_t>> result;
  internal::for_each_data_line(in, source, [&](std::size_t n, const std::string& line,
                                               const std::vector<std::string>& t) {
    std::size_t i = 0, j = 0;
    if(t.size() != 2 || !internal::parse_index(t[0], i) || !internal::parse_index(t[1], j))
      throw Invalid_input(internal::where(source, n) + "expected two vertex indices, got \"" + line + "\"");
    if(number_of_vertices > 0 && (i >= number_of_vertices || j >= number_of_vertices))
      throw Invalid_input(internal::where(source, n) + "vertex " + std::to_string(i >= number_of_vertices ? i : j) +
                          " out of range (the mesh has " + std::to_string(number_of_vertices) + " vertices)");
    if(i == j) throw Invalid_input(internal::where(source, n) + "an edge needs two distinct vertices");
    result.emplace_back(i, j);
  });
  if(result.empty()) throw Invalid_input(source + ": no vertex pair");
  return result;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// File version of `read_vertex_pairs()`.
/// \param filename the file to read
/// \param number_of_vertices number of vertices of the mesh, or 0 for no check
/// \returns the pairs in file order
inline std::vector<std::pair<std::size_t, std::size_t>> read_vertex_pairs(const std::string& filename,
                                                                           std::size_t number_of_vertices)
{
  std::vector<std::pair<std::size_t, std::size_t>> v;
  internal::read_from_file(filename, [&](std::istream& in, const std::string& s) {
    v = read_vertex_pairs(in, number_of_vertices, s);
  });
  return v;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// Reads `key=value` lines with numeric values (e.g. `a=1`, `R=3`): blanks
/// around `=` are allowed; a malformed line, a non-numeric value or a
/// repeated key is an error.
/// \param in the stream
/// \param source name used in messages (e.g. the file name)
/// \returns the values by key
inline std::map<std::string, double> read_numeric_parameters(std::istream& in, const std::string& source = "parameters")
{
  std::map<std::string, double> result;
  internal::for_each_data_line(in, source, [&](std::size_t n, const std::string& line, const std::vector<std::string>&) {
    const std::string body = line.substr(0, line.find('#'));
    const std::size_t eq = body.find('=');
    if(eq == std::string::npos)
      throw Invalid_input(internal::where(source, n) + "expected key=value, got \"" + line + "\"");
    const std::vector<std::string> k = internal::tokens_of(body.substr(0, eq));
    const std::vector<std::string> v = internal::tokens_of(body.substr(eq + 1));
    double value = 0;
    if(k.size() != 1 || v.size() != 1 || !internal::parse_double(v[0], value) || !std::isfinite(value))
      throw Invalid_input(internal::where(source, n) + "expected key=number, got \"" + line + "\"");
    if(!result.emplace(k[0], value).second)
      throw Invalid_input(internal::where(source, n) + "key " + k[0] + " given twice");
  });
  return result;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// File version of `read_numeric_parameters()`.
/// \param filename the file to read
/// \returns the values by key
inline std::map<std::string, double> read_numeric_parameters(const std::string& filename)
{
  std::map<std::string, double> v;
  internal::read_from_file(filename, [&](std::istream& in, const std::string& s) {
    v = read_numeric_parameters(in, s);
  });
  return v;
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_SIDECAR_FILES_H
