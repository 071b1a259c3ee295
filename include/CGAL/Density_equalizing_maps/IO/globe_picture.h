// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_GLOBE_PICTURE_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_GLOBE_PICTURE_H

/// \file globe_picture.h
/// Pictures and meshes of a (deformed) globe with coloured regions: an SVG of two
/// orthographic hemispheres, and a PLY of the mesh with a region label per face.

#include <CGAL/Density_equalizing_maps/IO/color_map.h>
#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/spherical_regions.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// What `write_globe_SVG()` draws.
struct Globe_picture
{
  /// mesh on the unit sphere (n x 3) and its triangles (m x 3), faces oriented outward
  Eigen::Matrix<double, Eigen::Dynamic, 3> positions;
  Eigen::Matrix<int, Eigen::Dynamic, 3> triangles;
  std::vector<Rgb> face_color;              ///< one colour per triangle
  /// the colour of the discs, under the faces: faces of this colour (the sea) are not drawn
  Rgb background = {{223, 233, 242}};
  std::vector<Spherical_region> borders;    ///< the region rings to draw on top (may be empty)
  double center_longitude[2] = {80, -100};  ///< longitudes of the centres of the two hemispheres
  double center_latitude = 10;              ///< latitude of both centres
  std::string title;                        ///< written above the picture (may be empty)
  std::string caption;                      ///< written below the picture (may be empty)
};

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes an SVG picture of a globe: two orthographic hemispheres side by side, the
/// faces filled with their colours (the visible ones, back to front on a sphere, none overlap)
/// and the borders drawn as polylines.
/// \param filename the SVG file
/// \param p the globe, colours and borders
/// \param size the diameter of each hemisphere in pixels
/// \throws Invalid_input if the sizes do not match or the file cannot be written
inline void write_globe_SVG(const std::string& filename, const Globe_picture& p, int size = 480)
{
  if(p.face_color.size() != std::size_t(p.triangles.rows()))
    throw Invalid_input(filename + ": " + std::to_string(p.face_color.size()) + " colours for " +
                        std::to_string(p.triangles.rows()) + " faces");
  std::ofstream out(filename);
  if(!out) throw Invalid_input("cannot write " + filename);
  const double margin = 10, top = p.title.empty() ? margin : 34, bottom = p.caption.empty() ? margin : 30;
  const double W = 2 * size + 3 * margin, H = size + top + bottom, R = 0.5 * size;
  char buf[160];
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
      << " " << H << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if(!p.title.empty())
    out << "<text x=\"" << W / 2 << "\" y=\"24\" font-family=\"sans-serif\" font-size=\"18\" text-anchor=\"middle\">"
        << p.title << "</text>\n";
  const double deg = 3.14159265358979323846 / 180;
  for(int h = 0; h < 2; ++h) {
    const double cx = margin + R + h * (size + margin), cy = top + R;
    const double l0 = p.center_longitude[h] * deg, p0 = p.center_latitude * deg;
    // orthographic frame: forward (towards the viewer), east, north
    const Eigen::Vector3d fwd(std::cos(p0) * std::cos(l0), std::cos(p0) * std::sin(l0), std::sin(p0));
    const Eigen::Vector3d east(-std::sin(l0), std::cos(l0), 0);
    const Eigen::Vector3d north = fwd.cross(east);
    auto project = [&](const Eigen::Vector3d& v, double& x, double& y) {
      x = cx + R * v.dot(east);
      y = cy - R * v.dot(north);
    };
    std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", p.background[0], p.background[1], p.background[2]);
    out << "<g>\n<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << R << "\" fill=\"" << buf
        << "\" stroke=\"#555\"/>\n";
    // One path per colour, a subpath per visible face: a tenth of the elements of a
    // path per face for a renderer to set up (100,000 faces: rsvg-convert 4 s -> 1 s),
    // and no seams inside a region. The stroke in the fill colour covers the seams
    // between colours.
    std::map<Rgb, std::string> faces_of_color;
    for(Eigen::Index f = 0; f < p.triangles.rows(); ++f) {
      Eigen::Vector3d v[3];
      for(int j = 0; j < 3; ++j) v[j] = p.positions.row(p.triangles(f, j)).transpose();
      if((v[0] + v[1] + v[2]).dot(fwd) <= 0) continue;
      const Rgb& c = p.face_color[std::size_t(f)];
      if(c == p.background) continue;
      double x[3], y[3];
      for(int j = 0; j < 3; ++j) project(v[j], x[j], y[j]);
      std::snprintf(buf, sizeof(buf), "M%.1f %.1fL%.1f %.1fL%.1f %.1fz", x[0], y[0], x[1], y[1], x[2], y[2]);
      faces_of_color[c] += buf;
    }
    for(const auto& [c, path] : faces_of_color) {
      std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c[0], c[1], c[2]);
      out << "<path fill=\"" << buf << "\" stroke=\"" << buf << "\" stroke-width=\"0.4\" stroke-linejoin=\"round\" d=\""
          << path << "\"/>\n";
    }
    out << "<g fill=\"none\" stroke=\"#222\" stroke-width=\"0.5\" stroke-linejoin=\"round\">\n";
    for(const Spherical_region& r : p.borders)
      for(const Spherical_polygon& poly : r.polygons)
        for(const auto& ring : poly.rings) {
          std::string path;
          bool open = false;
          for(std::size_t i = 0; i <= ring.size(); ++i) {
            const Eigen::Vector3d v = ::CGAL::Density_equalizing_maps::internal::unit_vector(ring[i % ring.size()]);
            if(v.dot(fwd) <= 0) { open = false; continue; }
            double x, y;
            project(v, x, y);
            std::snprintf(buf, sizeof(buf), "%c%.1f %.1f", open ? 'L' : 'M', x, y);
            path += buf;
            open = true;
          }
          if(!path.empty()) out << "<path d=\"" << path << "\"/>\n";
        }
    out << "</g>\n<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << R << "\" fill=\"none\" stroke=\"#555\"/>\n</g>\n";
  }
  if(!p.caption.empty())
    out << "<text x=\"" << W / 2 << "\" y=\"" << H - 10 << "\" font-family=\"sans-serif\" font-size=\"13\" "
        << "text-anchor=\"middle\">" << p.caption << "</text>\n";
  out << "</svg>\n";
  out.flush();
  if(!out) throw Invalid_input("error while writing " + filename);
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes a triangle mesh as an ASCII PLY file with an integer `region` and a colour
/// (`red green blue`) per face.
/// \param filename the PLY file
/// \param positions the vertices (n x 3)
/// \param triangles the faces (m x 3)
/// \param region the label of each face (-1: none, e.g. the sea)
/// \param color the colour of each face
/// \throws Invalid_input if the sizes do not match or the file cannot be written
inline void write_PLY_with_face_labels(const std::string& filename, const Eigen::Matrix<double, Eigen::Dynamic, 3>& positions,
                                       const Eigen::Matrix<int, Eigen::Dynamic, 3>& triangles,
                                       const std::vector<long>& region, const std::vector<Rgb>& color)
{
  if(region.size() != std::size_t(triangles.rows()) || color.size() != region.size())
    throw Invalid_input(filename + ": one label and one colour per face expected");
  std::ofstream out(filename);
  if(!out) throw Invalid_input("cannot write " + filename);
  out << "ply\nformat ascii 1.0\ncomment region: index of the region in the GeoJSON order, -1 = no region\n"
      << "element vertex " << positions.rows() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "element face " << triangles.rows() << "\nproperty list uchar int vertex_indices\nproperty int region\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  char buf[128];
  for(Eigen::Index i = 0; i < positions.rows(); ++i) {
    std::snprintf(buf, sizeof(buf), "%.17g %.17g %.17g\n", positions(i, 0), positions(i, 1), positions(i, 2));
    out << buf;
  }
  for(Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const Rgb& c = color[std::size_t(f)];
    out << "3 " << triangles(f, 0) << " " << triangles(f, 1) << " " << triangles(f, 2) << " " << region[std::size_t(f)]
        << " " << int(c[0]) << " " << int(c[1]) << " " << int(c[2]) << "\n";
  }
  out.flush();
  if(!out) throw Invalid_input("error while writing " + filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_GLOBE_PICTURE_H
