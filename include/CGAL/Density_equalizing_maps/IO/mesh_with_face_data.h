// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_MESH_WITH_FACE_DATA_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_MESH_WITH_FACE_DATA_H

/// \file mesh_with_face_data.h
/// Writers of a triangle mesh carrying its `Face_data` and colours, for
/// MeshLab (PLY) and ParaView (VTK legacy `.vtk`, VTK XML `.vtp`).
///
/// Every file holds the four per-face scalars `population`, `density_ratio`,
/// `log_area_ratio`, `abs_mu` and a per-face colour of the chosen quantity
/// (viridis over the range of `color_range()`); the PLY and VTK files also hold a
/// per-vertex colour: the parameter t of a vertex is the mean of the t of its
/// incident faces weighted by their areas in the written geometry, so smooth
/// shading shows the same scale. The range used is recorded in the file
/// (a PLY comment, the VTK title line, a VTP field `color_range`).

#include <CGAL/Density_equalizing_maps/IO/color_map.h>
#include <CGAL/Density_equalizing_maps/IO/face_data.h>
#include <CGAL/Density_equalizing_maps/IO/triangle_soup.h>

#include <CGAL/IO/Color.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh/IO/PLY.h>

#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

namespace internal {

/// Colours of the faces and vertices of a soup for one quantity.
struct Colors
{
  Color_range range;
  std::vector<Rgb> face, vertex;
};

inline Colors colors_of(const Triangle_soup& s, const std::vector<double>& values, Color_by by)
{
  if(values.size() != s.faces.size())
    throw Invalid_input("face data has " + std::to_string(values.size()) + " values for " +
                        std::to_string(s.faces.size()) + " faces");
  Colors c;
  c.range = color_range(by, values);
  const std::vector<double> area = face_areas(s);
  std::vector<double> t_sum(s.points.size(), 0.), w_sum(s.points.size(), 0.);
  for(std::size_t k = 0; k < s.faces.size(); ++k) {
    const double t = c.range.parameter(values[k]);
    c.face.push_back(viridis(t));
    for(std::size_t i : s.faces[k]) {
      t_sum[i] += area[k] * t;
      w_sum[i] += area[k];
    }
  }
  for(std::size_t i = 0; i < s.points.size(); ++i) c.vertex.push_back(viridis(w_sum[i] > 0 ? t_sum[i] / w_sum[i] : 0.));
  return c;
}

inline std::string range_description(Color_by by, const Color_range& r)
{
  std::ostringstream o;
  o << std::setprecision(6) << "colored by " << color_by_name(by) << ", viridis over [" << r.low << ", " << r.high
    << "]" << (r.logarithmic ? " (log scale)" : "");
  return o.str();
}

struct Named_values
{
  const char* name;
  const std::vector<double>* values;
};

/// The name of the array of the quantity `by` in the files.
inline const char* array_name(Color_by by)
{
  switch(by) {
  case Color_by::log_area_ratio: return "log_area_ratio";
  case Color_by::beltrami: return "abs_mu";
  case Color_by::density: return "density_ratio";
  default: return "population";
  }
}

inline std::vector<Named_values> named_values(const Face_data& d)
{
  return {{"population", &d.population}, {"density_ratio", &d.density_ratio},
          {"log_area_ratio", &d.log_area_ratio}, {"abs_mu", &d.abs_mu}};
}

inline void check_sizes(const Triangle_soup& s, const Face_data& d)
{
  for(const Named_values& nv : named_values(d))
    if(nv.values->size() != s.faces.size())
      throw Invalid_input(std::string("face data \"") + nv.name + "\" has " + std::to_string(nv.values->size()) +
                          " values for " + std::to_string(s.faces.size()) + " faces");
}

/// The geometry of a writer's mesh with its colours, after the size checks.
struct Colored_soup
{
  Triangle_soup soup;
  Colors colors;
};

template <class TriangleMesh, class PointMap>
Colored_soup colored_soup(const TriangleMesh& tm, PointMap points, const Face_data& d, Color_by by)
{
  Colored_soup c;
  c.soup = triangle_soup(tm, points);
  check_sizes(c.soup, d);
  c.colors = colors_of(c.soup, d.values(by), by);
  return c;
}

inline std::ofstream open_for_writing(const std::string& filename, bool binary = false)
{
  std::ofstream out(filename, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if(!out) throw Invalid_input("cannot write " + filename);
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  return out;
}

inline void close_checked(std::ofstream& out, const std::string& filename)
{
  out.close();
  if(!out) throw Invalid_input("error while writing " + filename);
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes `tm` with the positions `points` as an ASCII PLY file through
/// `CGAL::IO::write_PLY()`: per-face `double` properties `population`, `density_ratio`,
/// `log_area_ratio`, `abs_mu`, per-face and per-vertex `red green blue alpha` of
/// the quantity `by`; a comment line records the colour range.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam PointMap a model of `ReadablePropertyMap` from vertices to 3D points
/// \param filename the file to write
/// \param tm the triangle mesh (the input or the mapped mesh: same connectivity)
/// \param points the geometry to write (e.g. the mapped positions)
/// \param d the face data, in the order of `faces(tm)`
/// \param by the quantity of the colours
/// \throws Invalid_input if a face is not a triangle, `d` has the wrong size, or the file cannot be written
template <class TriangleMesh, class PointMap>
void write_PLY_with_face_data(const std::string& filename, const TriangleMesh& tm, PointMap points,
                              const Face_data& d, Color_by by)
{
  typedef CGAL::Simple_cartesian<double>::Point_3 Point;
  typedef CGAL::Surface_mesh<Point> Mesh;
  const internal::Colored_soup cs = internal::colored_soup(tm, points, d, by);
  const Triangle_soup& s = cs.soup;
  const internal::Colors& colors = cs.colors;

  Mesh out;
  std::vector<Mesh::Vertex_index> v;
  for(const auto& p : s.points) v.push_back(out.add_vertex(Point(p[0], p[1], p[2])));
  for(const auto& t : s.faces)
    if(out.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face())
      throw Invalid_input(filename + ": the mesh is not an oriented 2-manifold, it cannot be stored in a Surface_mesh");
  for(const internal::Named_values& nv : internal::named_values(d)) {
    auto pm = out.add_property_map<Mesh::Face_index, double>(std::string("f:") + nv.name, 0.).first;
    for(std::size_t k = 0; k < s.faces.size(); ++k) pm[Mesh::Face_index(Mesh::size_type(k))] = (*nv.values)[k];
  }
  auto fcolor = out.add_property_map<Mesh::Face_index, CGAL::IO::Color>("f:color").first;
  auto vcolor = out.add_property_map<Mesh::Vertex_index, CGAL::IO::Color>("v:color").first;
  for(std::size_t k = 0; k < s.faces.size(); ++k) {
    const Rgb& c = colors.face[k];
    fcolor[Mesh::Face_index(Mesh::size_type(k))] = CGAL::IO::Color(c[0], c[1], c[2]);
  }
  for(std::size_t i = 0; i < s.points.size(); ++i) {
    const Rgb& c = colors.vertex[i];
    vcolor[Mesh::Vertex_index(Mesh::size_type(i))] = CGAL::IO::Color(c[0], c[1], c[2]);
  }
  std::ofstream os = internal::open_for_writing(filename);
  if(!CGAL::IO::write_PLY(os, out, internal::range_description(by, colors.range)))
    throw Invalid_input("error while writing " + filename);
  internal::close_checked(os, filename);
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes `tm` with the positions `points` as an ASCII VTK legacy file
/// (`DATASET UNSTRUCTURED_GRID` of triangles, the legacy dataset that ParaView, VisIt
/// and meshio all read) with `CELL_DATA` scalars `population`, `density_ratio`,
/// `log_area_ratio`, `abs_mu`, `colors` (unsigned char RGB of the quantity `by`) and
/// `POINT_DATA` `colors`. The title line records the colour range. Parameters as
/// `write_PLY_with_face_data()`.
/// \param filename the file to write
/// \param tm the mesh
/// \param points the positions written
/// \param d the per-face values, from `face_data()`
/// \param by the quantity the colours show
template <class TriangleMesh, class PointMap>
void write_VTK_with_face_data(const std::string& filename, const TriangleMesh& tm, PointMap points,
                              const Face_data& d, Color_by by)
{
  const internal::Colored_soup cs = internal::colored_soup(tm, points, d, by);
  const Triangle_soup& s = cs.soup;
  const internal::Colors& colors = cs.colors;
  std::ofstream os = internal::open_for_writing(filename);
  const std::size_t n = s.points.size(), m = s.faces.size();
  os << "# vtk DataFile Version 3.0\n"
     << "Density_equalizing_maps: " << internal::range_description(by, colors.range) << "\n"
     << "ASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " << n << " double\n";
  for(const auto& p : s.points) os << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  os << "CELLS " << m << ' ' << 4 * m << '\n';
  for(const auto& t : s.faces) os << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  os << "CELL_TYPES " << m << '\n';
  for(std::size_t k = 0; k < m; ++k) os << "5\n"; // VTK_TRIANGLE
  os << "CELL_DATA " << m << '\n';
  for(const internal::Named_values& nv : internal::named_values(d)) {
    os << "SCALARS " << nv.name << " double 1\nLOOKUP_TABLE default\n";
    for(double x : *nv.values) os << x << '\n';
  }
  auto write_colors = [&os](const std::vector<Rgb>& c) {
    os << "SCALARS colors unsigned_char 3\nLOOKUP_TABLE default\n";
    for(const Rgb& x : c) os << int(x[0]) << ' ' << int(x[1]) << ' ' << int(x[2]) << '\n';
  };
  write_colors(colors.face);
  os << "POINT_DATA " << n << '\n';
  write_colors(colors.vertex);
  internal::close_checked(os, filename);
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes `tm` with the positions `points` as a VTK XML PolyData file (`.vtp`,
/// ASCII data arrays): `CellData` arrays `population`, `density_ratio`, `log_area_ratio`,
/// `abs_mu` (Float64) and `colors` (UInt8, 3 components, of the quantity `by`),
/// `PointData` `colors`, and a `FieldData` array `color_range` = {low, high}.
/// Parameters as `write_PLY_with_face_data()`.
/// \param filename the file to write
/// \param tm the mesh
/// \param points the positions written
/// \param d the per-face values, from `face_data()`
/// \param by the quantity the colours show
template <class TriangleMesh, class PointMap>
void write_VTP_with_face_data(const std::string& filename, const TriangleMesh& tm, PointMap points,
                              const Face_data& d, Color_by by)
{
  const internal::Colored_soup cs = internal::colored_soup(tm, points, d, by);
  const Triangle_soup& s = cs.soup;
  const internal::Colors& colors = cs.colors;
  std::ofstream os = internal::open_for_writing(filename);
  const std::size_t n = s.points.size(), m = s.faces.size();
  auto array_header = [&os](const char* type, const std::string& name, int components, std::size_t tuples = 0) {
    os << "<DataArray type=\"" << type << "\"" << (name.empty() ? "" : " Name=\"" + name + "\"")
       << " NumberOfComponents=\"" << components << "\"";
    if(tuples > 0) os << " NumberOfTuples=\"" << tuples << "\"";
    os << " format=\"ascii\">\n";
  };
  auto write_colors = [&](const std::vector<Rgb>& c) {
    array_header("UInt8", "colors", 3);
    for(const Rgb& x : c) os << int(x[0]) << ' ' << int(x[1]) << ' ' << int(x[2]) << '\n';
    os << "</DataArray>\n";
  };
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << "<!-- Density_equalizing_maps: " << internal::range_description(by, colors.range) << " -->\n"
     << "<PolyData>\n<FieldData>\n";
  array_header("Float64", "color_range", 1, 2);
  os << colors.range.low << ' ' << colors.range.high << "\n</DataArray>\n</FieldData>\n"
     << "<Piece NumberOfPoints=\"" << n << "\" NumberOfPolys=\"" << m << "\">\n<Points>\n";
  array_header("Float64", "", 3);
  for(const auto& p : s.points) os << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  os << "</DataArray>\n</Points>\n<Polys>\n";
  array_header("Int64", "connectivity", 1);
  for(const auto& t : s.faces) os << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  os << "</DataArray>\n";
  array_header("Int64", "offsets", 1);
  for(std::size_t k = 1; k <= m; ++k) os << 3 * k << '\n';
  os << "</DataArray>\n</Polys>\n<CellData Scalars=\"" << internal::array_name(by) << "\">\n";
  for(const internal::Named_values& nv : internal::named_values(d)) {
    array_header("Float64", nv.name, 1);
    for(double x : *nv.values) os << x << '\n';
    os << "</DataArray>\n";
  }
  write_colors(colors.face);
  os << "</CellData>\n<PointData>\n";
  write_colors(colors.vertex);
  os << "</PointData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  internal::close_checked(os, filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_MESH_WITH_FACE_DATA_H
