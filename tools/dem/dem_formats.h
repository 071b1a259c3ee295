// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The file formats of the `dem` tool: which reader or writer a file name
// selects, checked before any computation, and the writers of the mapped mesh
// with its per-face data, texture coordinates or neuroimaging formats.
//
// Input surfaces: FreeSurfer triangle surfaces (recognised by their magic
// number, whatever the name: lh.white, rh.pial, ...), GIfTI (.gii), and what
// CGAL::IO::read_polygon_soup reads (.off .obj .ply .stl .ts; .vtp only when
// CGAL is built with VTK, which this tool is not).
//
// Output (--output, by extension unless --output-format is given):
//   .ply   CGAL's PLY writer, per-face population, density_ratio, log_area_ratio,
//          abs_mu and face/vertex colours of --color-by
//   .vtk   VTK legacy unstructured grid of triangles with the same CELL_DATA
//   .vtp   VTK XML PolyData with the same CellData
//   .obj   OBJ with texture coordinates (equirectangular on the sphere and the
//          ellipsoid, flat-torus coordinates on the torus)
//   .gii   GIfTI surface (float32 POINTSET, int32 TRIANGLE)
//   FreeSurfer binary triangle surface: --output-format freesurfer, or a name
//          without extension, or a name starting with lh. / rh. whose extension
//          is not one of the above (lh.sphere, rh.sphere.reg, lh.white)
//   .off .stl .ts: positions only, through CGAL::IO::write_polygon_soup
// Per-vertex data (--vertex-population): FreeSurfer curv (magic number), GIfTI
// data array (.gii, the first array that is not POINTSET/TRIANGLE), or a text
// file with one value per line.

#ifndef DEM_TOOL_DEM_FORMATS_H
#define DEM_TOOL_DEM_FORMATS_H

#include "mesh_input.h"

#include <CGAL/Density_equalizing_maps/IO/FreeSurfer.h>
#include <CGAL/Density_equalizing_maps/IO/GIfTI.h>
#include <CGAL/Density_equalizing_maps/IO/OBJ_with_texture.h>
#include <CGAL/Density_equalizing_maps/IO/mesh_with_face_data.h>
#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>
#include <CGAL/Density_equalizing_maps/IO/texture_coordinates.h>
#include <CGAL/Density_equalizing_maps/Map_report.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <cctype>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace dem_cli {

namespace DIO = CGAL::Density_equalizing_maps::IO;

/// A usage error (exit 2): a format the tool cannot write, a bad option value.
struct Format_usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

enum class Output_kind { POSITIONS, PLY, VTK, VTP, OBJ, GIFTI, FREESURFER };

inline std::string lower(std::string s)
{
  for(char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

inline std::string base_name(const std::string& file)
{
  const std::size_t slash = file.find_last_of("/\\");
  return slash == std::string::npos ? file : file.substr(slash + 1);
}

/// The extension of the base name, lower case, with the dot ("" if none).
inline std::string extension(const std::string& file)
{
  const std::string b = base_name(file);
  const std::size_t dot = b.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? "" : lower(b.substr(dot));
}

inline bool has_hemisphere_prefix(const std::string& file)
{
  const std::string b = lower(base_name(file));
  return b.rfind("lh.", 0) == 0 || b.rfind("rh.", 0) == 0;
}

inline const char* output_formats_text()
{
  return ".ply (face data + colours), .vtk / .vtp (VTK, cell data), .obj (texture coordinates), .gii (GIfTI), "
         "FreeSurfer (no extension, lh.* / rh.*, or --output-format freesurfer), .off / .stl / .ts (positions only)";
}

/// The writer `file` selects; `forced` is the value of --output-format ("" = by name).
/// \throws Format_usage_error naming the accepted formats
inline Output_kind output_kind(const std::string& file, const std::string& forced = "")
{
  if(!forced.empty()) {
    const std::string f = lower(forced);
    if(f == "freesurfer") return Output_kind::FREESURFER;
    if(f == "gifti" || f == "gii") return Output_kind::GIFTI;
    if(f == "ply") return Output_kind::PLY;
    if(f == "vtk") return Output_kind::VTK;
    if(f == "vtp") return Output_kind::VTP;
    if(f == "obj") return Output_kind::OBJ;
    if(f == "off" || f == "stl" || f == "ts") return Output_kind::POSITIONS;
    throw Format_usage_error("unknown --output-format \"" + forced +
                             "\" (expected freesurfer, gifti, ply, vtk, vtp, obj, off, stl or ts)");
  }
  const std::string e = extension(file);
  if(e == ".ply") return Output_kind::PLY;
  if(e == ".vtk") return Output_kind::VTK;
  if(e == ".vtp") return Output_kind::VTP;
  if(e == ".obj") return Output_kind::OBJ;
  if(e == ".gii") return Output_kind::GIFTI;
  if(e == ".off" || e == ".stl" || e == ".ts") return Output_kind::POSITIONS;
  if(e.empty() || has_hemisphere_prefix(file)) return Output_kind::FREESURFER;
  throw Format_usage_error("cannot tell the format of \"" + file + "\": unsupported format " + e +
                           "; written formats: " + output_formats_text());
}

/// The colour writers of --output-input-colored: .ply, .vtk or .vtp.
inline Output_kind colored_output_kind(const std::string& file)
{
  const Output_kind k = output_kind(file);
  if(k != Output_kind::PLY && k != Output_kind::VTK && k != Output_kind::VTP)
    throw Format_usage_error("--output-input-colored writes colours, which only .ply, .vtk and .vtp carry (got \"" +
                             file + "\")");
  return k;
}

enum class Input_kind { CGAL_SOUP, FREESURFER, GIFTI };

/// The reader of an input surface, decided before anything is computed.
/// \throws Invalid_input for a missing file or a format this build cannot read, naming what to do
inline Input_kind input_kind(const std::string& file)
{
  {
    std::ifstream probe(file, std::ios::binary);
    if(!probe) throw CGAL::Density_equalizing_maps::Invalid_input("cannot open " + file);
  }
  if(DIO::is_FreeSurfer_surface(file)) return Input_kind::FREESURFER;
  const std::string e = extension(file);
  if(e == ".gii") return Input_kind::GIFTI;
  if(e == ".vtp" || e == ".vtu" || e == ".vtk")
    throw CGAL::Density_equalizing_maps::Invalid_input(
      file + ": VTK " + (e == ".vtk" ? std::string("legacy") : std::string("XML")) +
      " input is not read: CGAL reads VTK files only when it is built with VTK, and this build is not; "
      "convert it to PLY or OFF first (e.g. meshio convert " + base_name(file) + " mesh.ply, or ParaView: Save Data as PLY)");
  if(e != ".off" && e != ".obj" && e != ".ply" && e != ".stl" && e != ".ts") {
    if(has_hemisphere_prefix(file))
      throw CGAL::Density_equalizing_maps::Invalid_input(
        file + ": named like a FreeSurfer surface but it does not start with the triangle-surface magic number FF FF FE "
               "(a quadrangle surface or a curv file?)");
    throw CGAL::Density_equalizing_maps::Invalid_input(
      file + ": unknown input format \"" + e + "\"; read: .off .obj .ply .stl .ts, FreeSurfer triangle surfaces, .gii");
  }
  return Input_kind::CGAL_SOUP;
}

/// Per-vertex values from a FreeSurfer curv file, a GIfTI data array or a text file (one value per line).
/// \throws Invalid_input if the file is malformed or does not hold `n` values
inline std::vector<double> read_vertex_values(const std::string& file, std::size_t n)
{
  std::ifstream in(file, std::ios::binary);
  if(!in) throw CGAL::Density_equalizing_maps::Invalid_input("cannot open " + file);
  unsigned char b[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(b), 3);
  if(in && b[0] == 0xFF && b[1] == 0xFF && b[2] == 0xFF) return DIO::read_FreeSurfer_curv(file, n);
  if(extension(file) == ".gii") return DIO::read_GIfTI_vertex_values(file, n);
  std::vector<double> v;
  std::ifstream text(file);
  std::string line;
  std::size_t k = 0;
  while(std::getline(text, line)) {
    ++k;
    const std::size_t h = line.find('#');
    std::istringstream ls(line.substr(0, h));
    double x;
    std::string extra;
    if(!(ls >> x)) {
      if(line.substr(0, h).find_first_not_of(" \t\r") == std::string::npos) continue;
      throw CGAL::Density_equalizing_maps::Invalid_input(file + " line " + std::to_string(k) + ": not a number");
    }
    if(ls >> extra)
      throw CGAL::Density_equalizing_maps::Invalid_input(file + " line " + std::to_string(k) + ": one value per line expected");
    v.push_back(x);
  }
  if(v.size() != n)
    throw CGAL::Density_equalizing_maps::Invalid_input(file + ": " + std::to_string(v.size()) + " values for " +
                                                       std::to_string(n) + " vertices (one value per vertex)");
  return v;
}

/// The population of every face from a density per vertex: the input face area times the
/// mean of its three corner values (the integral of their linear interpolant over the face).
/// \throws Invalid_input at the first value that is not positive
inline std::vector<double> face_population_from_vertex_density(const DIO::Triangle_soup& input,
                                                               const std::vector<double>& density,
                                                               const std::string& source)
{
  for(std::size_t i = 0; i < density.size(); ++i)
    if(!(density[i] > 0) || !std::isfinite(density[i]))
      throw CGAL::Density_equalizing_maps::Invalid_input(
        source + ": vertex " + std::to_string(i) + " has the value " + std::to_string(density[i]) +
        "; a population density must be positive (curvature-like data must be transformed first, e.g. exp(curv))");
  const std::vector<double> area = DIO::internal::face_areas(input);
  std::vector<double> p(input.faces.size());
  for(std::size_t k = 0; k < p.size(); ++k) {
    const auto& f = input.faces[k];
    p[k] = area[k] * (density[f[0]] + density[f[1]] + density[f[2]]) / 3;
  }
  return p;
}

/// What the OBJ writer needs to lay out texture coordinates on the map's domain.
template <class Mesh>
struct Texture_domain
{
  enum Kind { SPHERE, ELLIPSOID, TORUS } kind = SPHERE;
  std::array<double, 3> radii{{1., 1., 1.}}; // the ellipsoid's semi-axes
  double R = 0, r = 0;                       // the torus radii
  // torus: the flat-torus point of every vertex and the lattice offset of every halfedge
  typename Mesh::template Property_map<typename Mesh::Vertex_index, typename CGAL::Simple_cartesian<double>::Point_2> flat;
  typename Mesh::template Property_map<typename Mesh::Halfedge_index, std::array<int, 2> > offsets;
};

/// Writes the mapped mesh `mesh` with the positions `mapped` in the format `kind`.
/// \throws Invalid_input if writing fails
template <class Mesh, class PointMap>
void write_mapped_mesh(Output_kind kind, const std::string& file, const Mesh& mesh, PointMap mapped,
                       const DIO::Face_data& data, DIO::Color_by by, const Texture_domain<Mesh>& domain)
{
  switch(kind) {
  case Output_kind::PLY: DIO::write_PLY_with_face_data(file, mesh, mapped, data, by); return;
  case Output_kind::VTK: DIO::write_VTK_with_face_data(file, mesh, mapped, data, by); return;
  case Output_kind::VTP: DIO::write_VTP_with_face_data(file, mesh, mapped, data, by); return;
  case Output_kind::GIFTI: DIO::write_GIfTI_surface(file, DIO::triangle_soup(mesh, mapped)); return;
  case Output_kind::FREESURFER: DIO::write_FreeSurfer_surface(file, DIO::triangle_soup(mesh, mapped), "dem"); return;
  case Output_kind::OBJ: {
    const DIO::Textured_mesh t =
      domain.kind == Texture_domain<Mesh>::TORUS
        ? DIO::flat_torus_texture(mesh, mapped, domain.flat, domain.offsets, domain.R, domain.r)
        : DIO::equirectangular_texture(mesh, mapped, domain.radii);
    DIO::write_OBJ_with_texture(file, t, domain.kind == Texture_domain<Mesh>::TORUS
                                           ? "dem: flat-torus texture coordinates, unit square = one period cell"
                                           : "dem: equirectangular texture coordinates (longitude, latitude) in [0,1]^2");
    return;
  }
  case Output_kind::POSITIONS: {
    const DIO::Triangle_soup s = DIO::triangle_soup(mesh, mapped);
    std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
    for(const auto& p : s.points) points.emplace_back(p[0], p[1], p[2]);
    if(!CGAL::IO::write_polygon_soup(file, points, s.faces, CGAL::parameters::stream_precision(17)))
      throw CGAL::Density_equalizing_maps::Invalid_input("cannot write " + file);
    return;
  }
  }
}

/// Reads an input surface as a polygon soup with the reader `input_kind()` chose:
/// the package's FreeSurfer and GIfTI readers, else CGAL's (through
/// read_input_soup(), which names the cause of a failure).
/// \throws Invalid_input if it cannot be read or has no face
template <class Point>
void read_surface(const std::string& file, std::vector<Point>& points, std::vector<std::vector<std::size_t> >& polygons)
{
  DIO::Triangle_soup soup;
  switch(input_kind(file)) {
  case Input_kind::FREESURFER: soup = DIO::read_FreeSurfer_surface(file); break;
  case Input_kind::GIFTI: soup = DIO::read_GIfTI_surface(file); break;
  default: read_input_soup(file, points, polygons); return;
  }
  points.clear();
  polygons.clear();
  for(const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
  for(const auto& f : soup.faces) polygons.push_back({f[0], f[1], f[2]});
}

} // namespace dem_cli

#endif // DEM_TOOL_DEM_FORMATS_H
