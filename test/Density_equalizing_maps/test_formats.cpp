// Copyright (c) 2026 Density_equalizing_maps contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// File formats of IO/: the PLY/VTK/VTP writers of the face data, the textured
// OBJ (equirectangular and flat-torus texture coordinates), FreeSurfer surfaces
// and curv files, GIfTI surfaces and data arrays. Round trips on generated
// meshes, properties of the texture charts, and the errors of bad files.
// The files are left in formats_out/ for check_formats.py, which reads them with
// third-party readers (nibabel, vtk, meshio).

#include <CGAL/Density_equalizing_maps/IO/FreeSurfer.h>
#include <CGAL/Density_equalizing_maps/IO/GIfTI.h>
#include <CGAL/Density_equalizing_maps/IO/OBJ_with_texture.h>
#include <CGAL/Density_equalizing_maps/IO/mesh_with_face_data.h>
#include <CGAL/Density_equalizing_maps/IO/texture_coordinates.h>
#include <CGAL/Density_equalizing_maps/spherical_conformal_map.h>
#include <CGAL/Density_equalizing_maps/toroidal_density_equalizing_map.h>

#include "dem_test_meshes.h"

#include <CGAL/Surface_mesh/IO/PLY.h>

#ifdef CGAL_DEM_USE_ZLIB
#include <zlib.h>
#endif

#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>

using namespace dem_test;
namespace DEM = CGAL::Density_equalizing_maps;
namespace DIO = CGAL::Density_equalizing_maps::IO;
namespace PM = CGAL::Density_equalizing_maps::parameters;

namespace {

const std::string out_dir = "formats_out";
std::string out(const std::string& f) { return out_dir + "/" + f; }

std::string file_text(const std::string& f)
{
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::string& f, const std::string& text)
{
  std::ofstream o(f, std::ios::binary);
  o << text;
}

/// A rotation that puts no vertex of the icosphere on the z axis (the poles fall inside faces).
Point rotated(const Point& p)
{
  const double a = 0.3, b = 0.7;
  const double x1 = std::cos(a) * p.x() - std::sin(a) * p.y(), y1 = std::sin(a) * p.x() + std::cos(a) * p.y();
  return Point(x1, std::cos(b) * y1 - std::sin(b) * p.z(), std::sin(b) * y1 + std::cos(b) * p.z());
}

struct Texture_summary
{
  std::size_t negative = 0;
  double total = 0, min_v = 1e9, max_v = -1e9, min_u = 1e9, max_u = -1e9;
  double polar_band = 0; // v-height of the faces that reach a pole line, summed over both poles
};

Texture_summary summarize(const DIO::Textured_mesh& t)
{
  Texture_summary s;
  for(std::size_t k = 0; k < t.faces.size(); ++k) {
    const double a = DIO::texture_area(t, k);
    if(!(a > 0)) ++s.negative;
    s.total += a;
  }
  for(const auto& q : t.uv) {
    s.min_u = std::min(s.min_u, q[0]);
    s.max_u = std::max(s.max_u, q[0]);
    s.min_v = std::min(s.min_v, q[1]);
    s.max_v = std::max(s.max_v, q[1]);
  }
  double low_top = 1, high_bottom = 0;
  for(const auto& f : t.uv_faces) {
    bool top = false, bottom = false;
    for(std::size_t i : f) {
      top = top || t.uv[i][1] == 1;
      bottom = bottom || t.uv[i][1] == 0;
    }
    for(std::size_t i : f) {
      if(top) low_top = std::min(low_top, t.uv[i][1]);
      if(bottom) high_bottom = std::max(high_bottom, t.uv[i][1]);
    }
  }
  s.polar_band = (1 - low_top) + high_bottom;
  return s;
}

// ---------------------------------------------------------------- face data

void test_face_data_writers()
{
  Mesh m = bumpy(3);
  auto sphere = m.add_property_map<vertex_descriptor, Point>("v:sphere").first;
  DEM::spherical_conformal_map(m, sphere);
  auto pop = m.add_property_map<face_descriptor, double>("f:pop").first;
  for(auto f : m.faces()) {
    const Point c = m.point(m.target(m.halfedge(f)));
    pop[f] = 1 + 0.5 * (c.z() > 0);
  }
  const DIO::Face_data d = DIO::face_data(m, sphere, PM::face_population_map(pop));
  check(d.population.size() == m.number_of_faces() && d.abs_mu.size() == m.number_of_faces(), "face data sizes");
  // the density ratio has mean 1 and the variance the measures report
  double mean = 0, var = 0;
  for(double r : d.density_ratio) mean += r;
  mean /= double(d.density_ratio.size());
  for(double r : d.density_ratio) var += (r - mean) * (r - mean);
  var /= double(d.density_ratio.size() - 1);
  check_close(mean, 1, 1e-12, "density ratio has mean 1");
  check_close(var, DEM::density_variance(m, sphere, PM::face_population_map(pop)).face, 1e-10,
              "variance of the density ratio = density_variance().face");

  DIO::write_PLY_with_face_data(out("bumpy_sphere.ply"), m, sphere, d, DIO::Color_by::log_area_ratio);
  DIO::write_VTK_with_face_data(out("bumpy_sphere.vtk"), m, sphere, d, DIO::Color_by::log_area_ratio);
  DIO::write_VTP_with_face_data(out("bumpy_sphere.vtp"), m, sphere, d, DIO::Color_by::beltrami);
  DIO::write_PLY_with_face_data(out("bumpy_input_by_mu.ply"), m, m.points(), d, DIO::Color_by::beltrami);
  // expected values for the Python check: one line per face "population density_ratio darea mu"
  {
    std::ofstream o(out("bumpy_sphere_face_data.txt"));
    o.precision(17);
    for(std::size_t k = 0; k < d.population.size(); ++k)
      o << d.population[k] << ' ' << d.density_ratio[k] << ' ' << d.log_area_ratio[k] << ' ' << d.abs_mu[k] << '\n';
  }

  // read the PLY back with CGAL's reader: the properties and the colours
  Mesh back;
  std::ifstream in(out("bumpy_sphere.ply"));
  check(CGAL::IO::read_PLY(in, back), "CGAL reads the PLY");
  check(back.number_of_faces() == m.number_of_faces() && back.number_of_vertices() == m.number_of_vertices(),
        "PLY: same size");
  const char* names[] = {"f:population", "f:density_ratio", "f:log_area_ratio", "f:abs_mu"};
  const std::vector<double>* values[] = {&d.population, &d.density_ratio, &d.log_area_ratio, &d.abs_mu};
  for(int q = 0; q < 4; ++q) {
    auto r = back.property_map<face_descriptor, double>(names[q]);
    if(!check(r.second, std::string("PLY has ") + names[q])) continue;
    double err = 0;
    for(auto f : back.faces()) err = std::max(err, std::abs(r.first[f] - (*values[q])[f.idx()]));
    check(err == 0, std::string("PLY ") + names[q] + " round trips exactly");
  }
  auto fc = back.property_map<face_descriptor, CGAL::IO::Color>("f:color");
  auto vc = back.property_map<vertex_descriptor, CGAL::IO::Color>("v:color");
  check(fc.second && vc.second, "PLY has face and vertex colours");
  if(fc.second) {
    const DIO::Color_range range = DIO::color_range(DIO::Color_by::log_area_ratio, d.log_area_ratio);
    check(range.low < 0 && range.high == -range.low, "darea range symmetric about 0");
    std::size_t wrong = 0;
    for(auto f : back.faces()) {
      const DIO::Rgb c = DIO::viridis(range.parameter(d.log_area_ratio[f.idx()]));
      if(fc.first[f].red() != c[0] || fc.first[f].green() != c[1] || fc.first[f].blue() != c[2]) ++wrong;
    }
    check(wrong == 0, "PLY face colours = viridis of the log area ratio");
  }
  check(contains(file_text(out("bumpy_sphere.ply")), "comment colored by darea, viridis over ["),
        "PLY records the colour range");

  // the VTK legacy file: counts of its sections
  const std::string vtk = file_text(out("bumpy_sphere.vtk"));
  check(contains(vtk, "CELL_DATA " + std::to_string(m.number_of_faces())), "VTK CELL_DATA count");
  for(const char* n : {"population", "density_ratio", "log_area_ratio", "abs_mu", "colors"})
    check(contains(vtk, std::string("SCALARS ") + n + " "), std::string("VTK has ") + n);

  // viridis: the anchors and monotone lightness (the sum of channels rises from 0 to 1)
  check(DIO::viridis(0) == DIO::Rgb{{68, 1, 84}} && DIO::viridis(1) == DIO::Rgb{{253, 231, 37}}, "viridis ends");
  bool rising = true;
  for(int i = 1; i <= 64; ++i) {
    const DIO::Rgb a = DIO::viridis((i - 1) / 64.), b = DIO::viridis(i / 64.);
    if(0.30 * b[0] + 0.59 * b[1] + 0.11 * b[2] <= 0.30 * a[0] + 0.59 * a[1] + 0.11 * a[2]) rising = false;
  }
  check(rising, "viridis luma strictly increasing");
  check(DIO::color_range(DIO::Color_by::density, {0.5, 1., 1.5}).high == 2 &&
          DIO::color_range(DIO::Color_by::density, {0.5, 1., 1.5}).low == 0.5,
        "density range symmetric in log about 1");
  check(DIO::color_range(DIO::Color_by::beltrami, {0.1, 0.2}).high == 1, "|mu| range [0, 1]");

  const std::string msg = expect_throw<DEM::Invalid_input>(
    [&] { DIO::Face_data bad = d; bad.abs_mu.pop_back(); DIO::write_PLY_with_face_data(out("bad.ply"), m, sphere, bad, DIO::Color_by::beltrami); },
    "face data of the wrong size");
  check(contains(msg, "abs_mu"), "the wrong-size message names the array: " + msg);
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::color_by_from_name("area"); }, "bad colour name"),
                 "darea, mu, density or population"),
        "colour name message lists the names");
}

// ---------------------------------------------------------------- texture coordinates

Texture_summary sphere_texture(int level, bool rotate, const std::string& file = "")
{
  Mesh m = icosphere(level);
  if(rotate)
    for(auto v : m.vertices()) m.point(v) = rotated(m.point(v));
  const DIO::Textured_mesh t = DIO::equirectangular_texture(m, m.points());
  if(!file.empty()) DIO::write_OBJ_with_texture(out(file), t, "equirectangular texture");
  const Texture_summary s = summarize(t);
  if(rotate) check(t.faces.size() == m.number_of_faces() + 4, "rotated icosphere: both pole faces split in three");
  return s;
}

void test_equirectangular()
{
  // The check: every texture triangle is counter-clockwise (the chart keeps the
  // orientation of an outward mesh), the coordinates stay in u in [0, 2), v in
  // [0, 1], and the texture areas sum to the area of the unit square up to the
  // discretization, so the sum is not exactly 1. Two effects: the images of the
  // chords are curves in the chart (second order in the edge length), and next to
  // a pole the pole line v = 1 (or 0) is touched only at one point per face, leaving
  // uncovered triangles between the faces around the pole, whose area is at most the
  // v-height of those faces (first order). The test asserts |sum - 1| <= that
  // polar band, and that the error shrinks from level 3 to level 4.
  for(bool rotate : {false, true}) {
    const std::string tag = rotate ? " (rotated: poles inside faces)" : " (vertices on the poles)";
    const Texture_summary s3 = sphere_texture(3, rotate), s4 = sphere_texture(4, rotate, rotate ? "sphere_equirectangular.obj" : "");
    check(s3.negative == 0 && s4.negative == 0, "equirectangular: every texture triangle has positive area" + tag);
    check(s4.min_u >= 0 && s4.max_u < 2 && s4.min_v >= 0 && s4.max_v <= 1, "equirectangular: range" + tag);
    check(std::abs(s4.total - 1) <= s4.polar_band, "equirectangular: |total texture area - 1| within the polar band" +
                                                     tag + ": " + std::to_string(s4.total) + ", band " +
                                                     std::to_string(s4.polar_band));
    check(std::abs(s4.total - 1) < std::abs(s3.total - 1), "equirectangular: area error shrinks with refinement" + tag);
    check(s4.max_u > 1, "equirectangular: seam faces carry u > 1" + tag);
  }
  // an ellipsoid with its radii
  Mesh e = ellipsoid(2, 1, 0.5, 4);
  const DIO::Textured_mesh te = DIO::equirectangular_texture(e, e.points(), {{2., 1., 0.5}});
  const Texture_summary se = summarize(te);
  check(se.negative == 0, "ellipsoid chart: positive texture areas");
  check(std::abs(se.total - 1) <= se.polar_band, "ellipsoid chart: |total texture area - 1| within the polar band: " +
                                                   std::to_string(se.total));
  DIO::write_OBJ_with_texture(out("ellipsoid_equirectangular.obj"), te);
  check(contains(expect_throw<DEM::Invalid_input>([&] { DIO::equirectangular_texture(e, e.points(), {{1., 0., 1.}}); },
                                                  "zero radius"), "positive"),
        "zero radius rejected");
}

void test_flat_torus_texture()
{
  Mesh m = torus(3, 1, 24, 12);
  auto out_pm = m.add_property_map<vertex_descriptor, Point>("v:torus").first;
  auto uv = m.add_property_map<vertex_descriptor, Point_2>("v:uv").first;
  auto om = m.add_property_map<Mesh::Halfedge_index, std::array<int, 2> >("h:offset").first;
  const DEM::Map_report r = DEM::toroidal_density_equalizing_map(
    m, out_pm, PM::combine(PM::torus_radii(std::array<double, 2>{3, 1}), PM::flat_torus_coordinates(uv),
                           PM::flat_torus_offsets(om)));
  check(r.fold_overs == 0, "TDEM fold-free");
  const DIO::Textured_mesh t = DIO::flat_torus_texture(m, out_pm, uv, om, 3, 1);
  const Texture_summary s = summarize(t);
  check(t.faces.size() == m.number_of_faces(), "flat torus texture: one triangle per face");
  check(s.negative == 0, "flat torus texture: every triangle has positive area (" + std::to_string(s.negative) + " not)");
  // exact: a seamless fold-free layout tiles the fundamental cell once
  check_close(s.total, 1, 1e-10, "flat torus texture areas sum to the unit cell");
  double max_extent = 0;
  for(std::size_t k = 0; k < t.faces.size(); ++k)
    for(int c = 0; c < 3; ++c)
      for(int i = 0; i < 2; ++i)
        max_extent = std::max(max_extent, std::abs(t.uv[t.uv_faces[k][c]][i] - t.uv[t.uv_faces[k][(c + 1) % 3]][i]));
  check(max_extent < 0.25, "flat torus texture: no face stretches across the cell: " + std::to_string(max_extent));
  DIO::write_OBJ_with_texture(out("torus_flat.obj"), t, "flat-torus texture");
  // offsets that do not close around a face are refused
  auto bad = m.add_property_map<Mesh::Halfedge_index, std::array<int, 2> >("h:bad").first;
  for(auto h : m.halfedges()) bad[h] = om[h];
  bad[m.halfedge(*m.faces().begin())][0] += 1;
  check(contains(expect_throw<DEM::Invalid_input>([&] { DIO::flat_torus_texture(m, out_pm, uv, bad, 3, 1); },
                                                  "open offsets"), "do not sum to zero"),
        "non-closing offsets rejected");
}

// ---------------------------------------------------------------- FreeSurfer

void test_freesurfer()
{
  const Mesh m = bumpy(2);
  const DIO::Triangle_soup s = DIO::triangle_soup(m, m.points());
  DIO::write_FreeSurfer_surface(out("lh.bumpy"), s, "test_formats");
  check(DIO::is_FreeSurfer_surface(out("lh.bumpy")), "FreeSurfer magic number written");
  std::string created;
  const DIO::Triangle_soup r = DIO::read_FreeSurfer_surface(out("lh.bumpy"), &created);
  check(contains(created, "created by test_formats"), "created-by line: " + created);
  check(r.faces == s.faces, "FreeSurfer faces round trip");
  double err = 0;
  for(std::size_t i = 0; i < s.points.size(); ++i)
    for(int c = 0; c < 3; ++c) err = std::max(err, std::abs(r.points[i][c] - double(float(s.points[i][c]))));
  check(r.points.size() == s.points.size() && err == 0, "FreeSurfer points round trip (float32)");
  // big-endian layout: the vertex count right after the two newlines
  const std::string bytes = file_text(out("lh.bumpy"));
  const std::size_t p = bytes.find("\n\n") + 2;
  const unsigned n = (unsigned(static_cast<unsigned char>(bytes[p])) << 24) | (unsigned(static_cast<unsigned char>(bytes[p + 1])) << 16) |
                     (unsigned(static_cast<unsigned char>(bytes[p + 2])) << 8) | unsigned(static_cast<unsigned char>(bytes[p + 3]));
  check(n == s.points.size(), "vertex count stored big-endian");
  check(bytes.size() == p + 8 + 12 * s.points.size() + 12 * s.faces.size(), "FreeSurfer file size");

  std::vector<double> curv;
  for(const auto& q : s.points) curv.push_back(q[2] - 0.25);
  DIO::write_FreeSurfer_curv(out("lh.bumpy.curv"), curv, s.faces.size());
  const std::vector<double> cr = DIO::read_FreeSurfer_curv(out("lh.bumpy.curv"), s.points.size());
  bool same = cr.size() == curv.size();
  for(std::size_t i = 0; same && i < curv.size(); ++i) same = cr[i] == double(float(curv[i]));
  check(same, "curv round trip");
  {
    std::ofstream o(out("lh.bumpy.expected_curv.txt"));
    o.precision(9);
    for(double c : curv) o << float(c) << '\n';
  }

  // bad files
  write_text(out("truncated.surf"), bytes.substr(0, bytes.size() - 5));
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_FreeSurfer_surface(out("truncated.surf")); }, "truncated"),
                 "truncated"), "truncated surface named");
  std::string quad = bytes;
  quad[2] = char(0xFF);
  write_text(out("quad.surf"), quad);
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_FreeSurfer_surface(out("quad.surf")); }, "quad"),
                 "quadrangle"), "quad surface named");
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_FreeSurfer_surface(out("lh.bumpy.curv")); }, "curv as surface"),
                 "quadrangle"), "a curv file is not a triangle surface (same magic as a quad surface)");
  std::string bad_index = bytes;
  bad_index[bad_index.size() - 4] = char(0x7F); // the high byte of the last index
  write_text(out("bad_index.surf"), bad_index);
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_FreeSurfer_surface(out("bad_index.surf")); }, "index"),
                 "outside 0.."), "index out of range named");
  check(contains(expect_throw<DEM::Invalid_input>([&] { DIO::read_FreeSurfer_curv(out("lh.bumpy.curv"), s.points.size() + 1); },
                                                  "curv count"), "values for a surface of"), "curv count mismatch named");
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_FreeSurfer_curv(out("lh.bumpy")); }, "surface as curv"),
                 "not a FreeSurfer curv"), "a surface is not a curv file");
}

// ---------------------------------------------------------------- GIfTI

void test_gifti()
{
  const Mesh m = bumpy(2);
  const DIO::Triangle_soup s = DIO::triangle_soup(m, m.points());
  DIO::write_GIfTI_surface(out("bumpy.surf.gii"), s);
  const DIO::Triangle_soup r = DIO::read_GIfTI_surface(out("bumpy.surf.gii"));
  check(r.faces == s.faces, "GIfTI faces round trip");
  double err = 0;
  for(std::size_t i = 0; i < s.points.size(); ++i)
    for(int c = 0; c < 3; ++c) err = std::max(err, std::abs(r.points[i][c] - double(float(s.points[i][c]))));
  check(r.points.size() == s.points.size() && err == 0, "GIfTI points round trip (float32)");
  Mesh back;
  DIO::triangle_soup_to_mesh(r, back);
  check(back.number_of_faces() == m.number_of_faces(), "soup to Surface_mesh");

  std::vector<double> values;
  for(const auto& q : s.points) values.push_back(1 + q[0] * q[0]);
  DIO::write_GIfTI_vertex_values(out("bumpy.shape.gii"), values);
  const std::vector<double> vr = DIO::read_GIfTI_vertex_values(out("bumpy.shape.gii"), s.points.size());
  bool same = vr.size() == values.size();
  for(std::size_t i = 0; same && i < values.size(); ++i) same = vr[i] == double(float(values[i]));
  check(same, "GIfTI data array round trip");
  {
    std::ofstream o(out("bumpy.expected_shape.txt"));
    o.precision(9);
    for(double c : values) o << float(c) << '\n';
  }

  // a hand-written file: ASCII encoding, column-major triangles, int16/float64 types
  const std::string ascii =
    "<?xml version=\"1.0\"?>\n<GIFTI Version=\"1.0\" NumberOfDataArrays=\"3\">\n"
    "<DataArray Intent=\"NIFTI_INTENT_POINTSET\" DataType=\"NIFTI_TYPE_FLOAT64\" ArrayIndexingOrder=\"RowMajorOrder\"\n"
    "  Dimensionality=\"2\" Dim0=\"4\" Dim1=\"3\" Encoding=\"ASCII\" Endian=\"LittleEndian\">\n"
    "<Data>0 0 0  1 0 0  0 1 0  0 0 1</Data></DataArray>\n"
    "<DataArray Intent=\"NIFTI_INTENT_TRIANGLE\" DataType=\"NIFTI_TYPE_INT16\" ArrayIndexingOrder=\"ColumnMajorOrder\" "
    "Dimensionality=\"2\" Dim0=\"4\" Dim1=\"3\" Encoding=\"ASCII\"><Data>\n0 0 0 1\n2 1 3 2\n1 3 2 3</Data></DataArray>\n"
    "<DataArray Intent=\"NIFTI_INTENT_SHAPE\" DataType=\"NIFTI_TYPE_FLOAT32\" Dimensionality=\"1\" Dim0=\"4\" "
    "Encoding=\"ASCII\"><Data><![CDATA[0.5 1 2 4]]></Data></DataArray>\n</GIFTI>\n";
  write_text(out("tetra_ascii.gii"), ascii);
  const DIO::Triangle_soup t = DIO::read_GIfTI_surface(out("tetra_ascii.gii"));
  check(t.points.size() == 4 && t.faces.size() == 4, "ASCII GIfTI sizes");
  if(t.faces.size() == 4)
    check(t.faces[0] == std::array<std::size_t, 3>{{0, 2, 1}} && t.faces[3] == std::array<std::size_t, 3>{{1, 2, 3}},
          "column-major triangles transposed");
  const std::vector<double> tv = DIO::read_GIfTI_vertex_values(out("tetra_ascii.gii"), 4);
  check(tv == std::vector<double>({0.5, 1, 2, 4}), "CDATA ASCII data array");

#ifdef CGAL_DEM_USE_ZLIB
  {
    // GZipBase64Binary big-endian int32 values, as nibabel may write them
    std::vector<unsigned char> raw;
    for(std::int32_t v : {7, -3, 1 << 20})
      for(int b = 3; b >= 0; --b) raw.push_back(static_cast<unsigned char>(std::uint32_t(v) >> (8 * b)));
    std::vector<unsigned char> z(compressBound(uLong(raw.size())));
    uLongf zn = uLongf(z.size());
    compress(z.data(), &zn, raw.data(), uLong(raw.size()));
    z.resize(zn);
    write_text(out("gz.gii"), "<GIFTI><DataArray Intent=\"NIFTI_INTENT_NONE\" DataType=\"NIFTI_TYPE_INT32\" "
                              "Dimensionality=\"1\" Dim0=\"3\" Encoding=\"GZipBase64Binary\" Endian=\"BigEndian\"><Data>" +
                                DIO::internal::base64_encode(z) + "</Data></DataArray></GIFTI>");
    check(DIO::read_GIfTI_vertex_values(out("gz.gii")) == std::vector<double>({7, -3, 1 << 20}),
          "GZipBase64Binary big-endian int32");
  }
#endif

  // bad files
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_GIfTI_surface(out("bumpy.shape.gii")); }, "no pointset"),
                 "NIFTI_INTENT_POINTSET"), "a data file is not a surface");
  std::string short_data = ascii;
  short_data.replace(short_data.find("0 0 1</Data>"), 5, "0 0");
  write_text(out("short.gii"), short_data);
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_GIfTI_surface(out("short.gii")); }, "short data"),
                 "values for the declared"), "missing values named");
  write_text(out("not.gii"), "<?xml version=\"1.0\"?><foo/>");
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_GIfTI_data_arrays(out("not.gii")); }, "not gifti"),
                 "not a GIfTI file"), "not GIfTI named");
  check(contains(expect_throw<DEM::Invalid_input>([&] { DIO::read_GIfTI_vertex_values(out("bumpy.shape.gii"), 3); },
                                                  "count"), "values for a surface of"), "GIfTI count mismatch named");
  std::string bad64 = file_text(out("bumpy.surf.gii"));
  bad64[bad64.find("<Data>") + 8] = '!';
  write_text(out("bad64.gii"), bad64);
  check(contains(expect_throw<DEM::Invalid_input>([] { DIO::read_GIfTI_surface(out("bad64.gii")); }, "base64"),
                 "base64"), "invalid base64 named");
}

// ---------------------------------------------------------------- the dem tool

struct Cli_result
{
  int status = -1;
  std::string output; // stdout + stderr
};

Cli_result run_dem(const std::string& args)
{
  const std::string log = out("cli_log.txt");
  const std::string cmd = std::string("\"") + DEM_CLI + "\" " + args + " > \"" + log + "\" 2>&1";
  const int s = std::system(cmd.c_str());
  Cli_result r;
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  r.output = file_text(log);
  return r;
}

void test_cli_formats()
{
  // lh.bumpy was written by test_freesurfer: a FreeSurfer input without extension
  Cli_result r = run_dem("spherical-conformal " + out("lh.bumpy") + " --quiet --output " + out("cli_sphere.ply") +
                         " --color-by mu --output-input-colored " + out("cli_input.vtp"));
  check(r.status == 0, "dem reads a FreeSurfer surface and writes PLY + VTP: " + r.output);
  Mesh back;
  std::ifstream in(out("cli_sphere.ply"));
  check(CGAL::IO::read_PLY(in, back) && back.property_map<face_descriptor, double>("f:abs_mu").second &&
          back.property_map<face_descriptor, CGAL::IO::Color>("f:color").second,
        "dem's PLY has abs_mu and face colours");
  double max_radius_error = 0;
  for(auto v : back.vertices())
    max_radius_error = std::max(max_radius_error, std::abs(std::sqrt((back.point(v) - CGAL::ORIGIN).squared_length()) - 1));
  check(max_radius_error < 1e-9, "dem's PLY: points on the unit sphere");
  check(contains(file_text(out("cli_sphere.ply")), "colored by mu, viridis over [0, 1]"), "PLY comment names mu and [0, 1]");
  check(contains(file_text(out("cli_input.vtp")), "<CellData Scalars=\"abs_mu\">"), "input coloured by mu (VTP)");

  r = run_dem("spherical-conformal " + out("lh.bumpy") + " --output " + out("cli.xyz"));
  check(r.status == 2 && contains(r.output, "cannot tell the format") && !std::ifstream(out("cli.xyz")),
        "unknown output extension: usage error, nothing written: " + r.output);
  r = run_dem("spherical-conformal " + out("lh.bumpy") + " --output-input-colored " + out("cli.obj"));
  check(r.status == 2 && contains(r.output, "only .ply, .vtk and .vtp"), "coloured input needs ply/vtk/vtp: " + r.output);
  write_text(out("cli_mesh.vtp"), "<VTKFile/>");
  r = run_dem("spherical-conformal " + out("cli_mesh.vtp"));
  check(r.status == 3 && contains(r.output, "built with VTK") && contains(r.output, "PLY"),
        "VTK XML input: the reason and what to do: " + r.output);
  r = run_dem("sdem " + out("lh.bumpy") + " --vertex-population " + out("lh.bumpy.curv"));
  check(r.status == 3 && contains(r.output, "must be positive"), "negative curv values are not a population: " + r.output);
  r = run_dem("sdem --help");
  check(r.status == 0 && contains(r.output, "--tolerance EPS") && contains(r.output, "default 0.001") &&
          contains(r.output, "examples:") && contains(r.output, ".gii"),
        "dem sdem --help: options, defaults, formats, examples: " + r.output);
  r = run_dem("spherical-conformal " + out("lh.bumpy") + " --color-by area");
  check(r.status == 2 && contains(r.output, "darea, mu, density, population"), "bad --color-by: " + r.output);
}

} // namespace

int main()
{
  ::mkdir(out_dir.c_str(), 0755);
  test_face_data_writers();
  test_equirectangular();
  test_flat_torus_texture();
  test_freesurfer();
  test_gifti();
  test_cli_formats();
  return finish("test_formats");
}
