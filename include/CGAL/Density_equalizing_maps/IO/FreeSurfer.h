// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_FREESURFER_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_FREESURFER_H

/// \file FreeSurfer.h
/// FreeSurfer's binary triangle surfaces (`lh.white`, `lh.sphere`, ...) and
/// per-vertex "curv" files (`lh.curv`, `lh.thickness`, ...), both big-endian.
///
/// Triangle surface: the 3 bytes `FF FF FE`, a text line `created by ... on ...`
/// ended by two newlines, int32 vertex count, int32 face count, float32 x y z per
/// vertex, int32 i j k per face (0-based); FreeSurfer may append tags (volume
/// geometry), which are ignored on reading and not written.
/// Curv ("new" format): `FF FF FF`, int32 vertex count, int32 face count, int32
/// values per vertex (1), float32 per vertex.
/// Vertices and faces keep the order of the file, and the corners of a face
/// their order (no reorientation).

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/IO/triangle_soup.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

namespace internal {

inline unsigned magic_number(const unsigned char b[3]) { return (unsigned(b[0]) << 16) | (unsigned(b[1]) << 8) | b[2]; }

/// Big-endian binary input with messages naming the file.
class Big_endian_reader
{
public:
  Big_endian_reader(const std::string& filename) : m_name(filename), m_in(filename, std::ios::binary)
  {
    if(!m_in) throw Invalid_input("cannot open " + filename);
  }
  unsigned magic()
  {
    unsigned char b[3];
    bytes(b, 3, "magic number");
    return magic_number(b);
  }
  std::int32_t int32(const char* what)
  {
    unsigned char b[4];
    bytes(b, 4, what);
    return std::int32_t((std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) | b[3]);
  }
  float float32(const char* what)
  {
    const std::int32_t i = int32(what);
    float f;
    std::memcpy(&f, &i, 4);
    return f;
  }
  std::istream& stream() { return m_in; }
  const std::string& name() const { return m_name; }

private:
  void bytes(unsigned char* b, std::size_t n, const char* what)
  {
    if(!m_in.read(reinterpret_cast<char*>(b), std::streamsize(n)))
      throw Invalid_input(m_name + ": file ends before the " + what + " (truncated FreeSurfer file?)");
  }
  std::string m_name;
  std::ifstream m_in;
};

inline void put_int32(std::ostream& os, std::int32_t v)
{
  const std::uint32_t u = std::uint32_t(v);
  const char b[4] = {char(u >> 24), char(u >> 16), char(u >> 8), char(u)};
  os.write(b, 4);
}

inline void put_float32(std::ostream& os, float f)
{
  std::int32_t i;
  std::memcpy(&i, &f, 4);
  put_int32(os, i);
}

inline void put_magic(std::ostream& os, unsigned m)
{
  const char b[3] = {char(m >> 16), char(m >> 8), char(m)};
  os.write(b, 3);
}

/// A count read from the file, checked against a bound that keeps allocation sane.
inline std::size_t checked_count(Big_endian_reader& r, const char* what)
{
  const std::int32_t n = r.int32(what);
  if(n < 0 || n > (1 << 28)) throw Invalid_input(r.name() + ": implausible " + std::string(what) + " " + std::to_string(n));
  return std::size_t(n);
}

constexpr unsigned freesurfer_triangle_magic = 0xFFFFFE;
constexpr unsigned freesurfer_quad_magic = 0xFFFFFF;
constexpr unsigned freesurfer_new_quad_magic = 0xFFFFFD;
constexpr unsigned freesurfer_curv_magic = 0xFFFFFF;

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// True if the file starts with the magic number of a FreeSurfer triangle surface.
/// \param filename the file to test
/// \returns true if the file starts with the magic number of a FreeSurfer triangle surface (FF FF FE)
inline bool is_FreeSurfer_surface(const std::string& filename)
{
  std::ifstream in(filename, std::ios::binary);
  unsigned char b[3];
  return in.read(reinterpret_cast<char*>(b), 3) && internal::magic_number(b) == internal::freesurfer_triangle_magic;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads a FreeSurfer binary triangle surface.
/// \param filename the file
/// \param created_by if not null, receives the text of the `created by` line
/// \returns the points (float32 in the file) and triangles in file order
/// \throws Invalid_input for a missing or truncated file, another magic number (a quadrangle
///         surface is named as such), a non-finite coordinate or a vertex index out of range
inline Triangle_soup read_FreeSurfer_surface(const std::string& filename, std::string* created_by = nullptr)
{
  internal::Big_endian_reader r(filename);
  const unsigned magic = r.magic();
  if(magic == internal::freesurfer_quad_magic || magic == internal::freesurfer_new_quad_magic)
    throw Invalid_input(filename + ": a FreeSurfer quadrangle surface; only triangle surfaces are read "
                        "(convert it with FreeSurfer's mris_convert)");
  if(magic != internal::freesurfer_triangle_magic)
    throw Invalid_input(filename + ": not a FreeSurfer triangle surface (magic number FFFFFE expected)");
  std::string line;
  std::getline(r.stream(), line);
  if(!r.stream()) throw Invalid_input(filename + ": file ends in the \"created by\" line");
  if(r.stream().peek() == '\n') r.stream().get();
  if(created_by) *created_by = line;
  const std::size_t n = internal::checked_count(r, "vertex count"), m = internal::checked_count(r, "face count");
  Triangle_soup s;
  s.points.resize(n);
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < 3; ++c) {
      s.points[i][c] = r.float32("vertex coordinates");
      if(!std::isfinite(s.points[i][c]))
        throw Invalid_input(filename + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  s.faces.resize(m);
  for(std::size_t k = 0; k < m; ++k)
    for(int c = 0; c < 3; ++c) {
      const std::int32_t v = r.int32("face indices");
      if(v < 0 || std::size_t(v) >= n)
        throw Invalid_input(filename + ": face " + std::to_string(k) + " has the vertex index " + std::to_string(v) +
                            " outside 0.." + std::to_string(n - 1));
      s.faces[k][c] = std::size_t(v);
    }
  return s;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes a FreeSurfer binary triangle surface (coordinates rounded to float32).
/// \param filename the file
/// \param s the points and triangles
/// \param created_by the program named in the `created by ... on ...` line
/// \throws Invalid_input if the file cannot be written or the mesh is too large for int32 counts
inline void write_FreeSurfer_surface(const std::string& filename, const Triangle_soup& s,
                                     const std::string& created_by = "Density_equalizing_maps")
{
  if(s.points.size() > (std::size_t(1) << 31) - 1 || s.faces.size() > (std::size_t(1) << 31) - 1)
    throw Invalid_input(filename + ": too many vertices or faces for a FreeSurfer surface");
  std::ofstream os(filename, std::ios::binary);
  if(!os) throw Invalid_input("cannot write " + filename);
  internal::put_magic(os, internal::freesurfer_triangle_magic);
  os << "created by " << created_by << "\n\n";
  internal::put_int32(os, std::int32_t(s.points.size()));
  internal::put_int32(os, std::int32_t(s.faces.size()));
  for(const auto& p : s.points)
    for(double x : p) internal::put_float32(os, float(x));
  for(const auto& f : s.faces)
    for(std::size_t i : f) internal::put_int32(os, std::int32_t(i));
  os.close();
  if(!os) throw Invalid_input("error while writing " + filename);
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads a FreeSurfer curv file (new format, one float32 per vertex).
/// \param filename the file
/// \param expected_vertices the number of vertices of the surface, or 0 for no check
/// \returns the values in vertex order
/// \throws Invalid_input for the old (16-bit) format, a truncated file, several values per
///         vertex, a non-finite value or a count different from `expected_vertices`
inline std::vector<double> read_FreeSurfer_curv(const std::string& filename, std::size_t expected_vertices = 0)
{
  internal::Big_endian_reader r(filename);
  if(r.magic() != internal::freesurfer_curv_magic)
    throw Invalid_input(filename + ": not a FreeSurfer curv file in the new format (magic number FFFFFF expected; "
                        "old 16-bit curv files are not read)");
  const std::size_t n = internal::checked_count(r, "vertex count");
  internal::checked_count(r, "face count");
  const std::int32_t per_vertex = r.int32("values per vertex");
  if(per_vertex != 1)
    throw Invalid_input(filename + ": " + std::to_string(per_vertex) + " values per vertex; one is expected");
  if(expected_vertices > 0 && n != expected_vertices)
    throw Invalid_input(filename + ": " + std::to_string(n) + " values for a surface of " +
                        std::to_string(expected_vertices) + " vertices");
  std::vector<double> v(n);
  for(std::size_t i = 0; i < n; ++i) {
    v[i] = r.float32("values");
    if(!std::isfinite(v[i])) throw Invalid_input(filename + ": value " + std::to_string(i) + " is not finite");
  }
  return v;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes a FreeSurfer curv file (new format) of per-vertex values.
/// \param filename the file
/// \param values one value per vertex (rounded to float32)
/// \param number_of_faces the face count recorded in the header (FreeSurfer checks it against the surface)
inline void write_FreeSurfer_curv(const std::string& filename, const std::vector<double>& values,
                                  std::size_t number_of_faces)
{
  std::ofstream os(filename, std::ios::binary);
  if(!os) throw Invalid_input("cannot write " + filename);
  internal::put_magic(os, internal::freesurfer_curv_magic);
  internal::put_int32(os, std::int32_t(values.size()));
  internal::put_int32(os, std::int32_t(number_of_faces));
  internal::put_int32(os, 1);
  for(double x : values) internal::put_float32(os, float(x));
  os.close();
  if(!os) throw Invalid_input("error while writing " + filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_FREESURFER_H
