// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_OBJ_WITH_TEXTURE_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_OBJ_WITH_TEXTURE_H

/// \file OBJ_with_texture.h
/// Writer of a `Textured_mesh` as a Wavefront OBJ file with one `vt` per
/// corner: `v x y z` lines, `vt u v` lines, and faces `f p/t p/t p/t` (1-based).

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/IO/texture_coordinates.h>

#include <fstream>
#include <iomanip>
#include <limits>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes `t` as an OBJ file with texture coordinates.
/// \param filename the file to write
/// \param t the mesh and its texture coordinates (e.g. from `equirectangular_texture()`)
/// \param comment a line written as an OBJ comment at the top (optional)
/// \throws Invalid_input if an index is out of range or the file cannot be written
inline void write_OBJ_with_texture(const std::string& filename, const Textured_mesh& t,
                                   const std::string& comment = std::string())
{
  if(t.faces.size() != t.uv_faces.size()) throw Invalid_input("textured mesh: one texture triangle per face is needed");
  for(std::size_t k = 0; k < t.faces.size(); ++k)
    for(int c = 0; c < 3; ++c)
      if(t.faces[k][c] >= t.points.size() || t.uv_faces[k][c] >= t.uv.size())
        throw Invalid_input("textured mesh: face " + std::to_string(k) + " has an index out of range");
  std::ofstream os(filename);
  if(!os) throw Invalid_input("cannot write " + filename);
  os << std::setprecision(std::numeric_limits<double>::max_digits10);
  if(!comment.empty()) os << "# " << comment << '\n';
  for(const auto& p : t.points) os << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for(const auto& q : t.uv) os << "vt " << q[0] << ' ' << q[1] << '\n';
  for(std::size_t k = 0; k < t.faces.size(); ++k) {
    os << 'f';
    for(int c = 0; c < 3; ++c) os << ' ' << t.faces[k][c] + 1 << '/' << t.uv_faces[k][c] + 1;
    os << '\n';
  }
  os.close();
  if(!os) throw Invalid_input("error while writing " + filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_OBJ_WITH_TEXTURE_H
