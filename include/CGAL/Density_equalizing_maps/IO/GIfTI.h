// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_GIFTI_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_GIFTI_H

/// \file GIfTI.h
/// GIfTI surfaces (`.surf.gii`) and data arrays (`.shape.gii`, `.func.gii`),
/// written and read after the GIfTI 1.0 format specification (XML with one
/// `DataArray` per array), without a library: the package stays header-only
/// and the part of the format surfaces use is small.
///
/// Writing: a surface is a `NIFTI_INTENT_POINTSET` array (n x 3 float32, with an
/// identity `CoordinateSystemTransformMatrix`) and a `NIFTI_INTENT_TRIANGLE` array
/// (m x 3 int32), both `Base64Binary`, little-endian, row-major.
/// Reading: `ASCII`, `Base64Binary` and `GZipBase64Binary` encodings (the last one,
/// nibabel's default, needs zlib: define `CGAL_DEM_USE_ZLIB` and link zlib, which the
/// package's CMake target does when zlib is found), either endianness, row- or
/// column-major order, and the data types `NIFTI_TYPE_UINT8`, `INT8`, `INT16`, `UINT16`,
/// `INT32`, `UINT32`, `INT64`, `FLOAT32`, `FLOAT64`. External data files are not read.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/IO/triangle_soup.h>

#ifdef CGAL_DEM_USE_ZLIB
#include <zlib.h>
#endif

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// One GIfTI data array, converted to doubles in row-major order.
struct GIfTI_data_array
{
  std::string intent;             ///< e.g. `NIFTI_INTENT_POINTSET`, `NIFTI_INTENT_TRIANGLE`, `NIFTI_INTENT_SHAPE`
  std::string data_type;          ///< e.g. `NIFTI_TYPE_FLOAT32`
  std::vector<std::size_t> dims;  ///< `Dim0`, `Dim1`, ...
  std::vector<double> values;     ///< the product of `dims` values, row-major
};

namespace internal {

inline const char* base64_alphabet() { return "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"; }

inline std::string base64_encode(const std::vector<unsigned char>& b)
{
  const char* a = base64_alphabet();
  std::string s;
  s.reserve(4 * ((b.size() + 2) / 3));
  for(std::size_t i = 0; i < b.size(); i += 3) {
    const std::uint32_t w = (std::uint32_t(b[i]) << 16) | (i + 1 < b.size() ? std::uint32_t(b[i + 1]) << 8 : 0u) |
                            (i + 2 < b.size() ? std::uint32_t(b[i + 2]) : 0u);
    s += a[(w >> 18) & 63];
    s += a[(w >> 12) & 63];
    s += i + 1 < b.size() ? a[(w >> 6) & 63] : '=';
    s += i + 2 < b.size() ? a[w & 63] : '=';
  }
  return s;
}

/// Decodes base64, skipping blanks; throws on any other character outside the alphabet.
inline std::vector<unsigned char> base64_decode(const std::string& s, const std::string& where)
{
  int value[256];
  for(int& v : value) v = -1;
  for(int i = 0; i < 64; ++i) value[static_cast<unsigned char>(base64_alphabet()[i])] = i;
  std::vector<unsigned char> b;
  std::uint32_t w = 0;
  int bits = 0;
  for(char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if(std::isspace(c)) continue;
    if(c == '=') break;
    if(value[c] < 0) throw Invalid_input(where + ": invalid character in base64 data");
    w = (w << 6) | std::uint32_t(value[c]);
    bits += 6;
    if(bits >= 8) {
      bits -= 8;
      b.push_back(static_cast<unsigned char>((w >> bits) & 0xFF));
    }
  }
  return b;
}

inline std::vector<unsigned char> inflate_zlib(const std::vector<unsigned char>& z, std::size_t expected,
                                               const std::string& where)
{
#ifdef CGAL_DEM_USE_ZLIB
  std::vector<unsigned char> out(expected);
  uLongf size = uLongf(expected);
  if(uncompress(out.data(), &size, z.data(), uLong(z.size())) != Z_OK || size != expected)
    throw Invalid_input(where + ": the GZipBase64Binary data does not inflate to the size the array declares");
  return out;
#else
  (void)z;
  (void)expected;
  throw Invalid_input(where + ": GZipBase64Binary data needs zlib, and this program was built without it "
                      "(define CGAL_DEM_USE_ZLIB and link zlib, or re-save the file with Base64Binary or ASCII encoding, "
                      "e.g. nibabel: darray.encoding = 'B64BIN')");
#endif
}

/// Bytes per value and a reader of one value for a NIFTI data type.
struct Nifti_type
{
  std::size_t size = 0;
  bool is_float = false, is_signed = false;
};

inline Nifti_type nifti_type(const std::string& t, const std::string& where)
{
  struct Entry { const char* name; Nifti_type type; };
  static const Entry table[] = {
    {"NIFTI_TYPE_UINT8", {1, false, false}},  {"NIFTI_TYPE_INT8", {1, false, true}},
    {"NIFTI_TYPE_INT16", {2, false, true}},   {"NIFTI_TYPE_UINT16", {2, false, false}},
    {"NIFTI_TYPE_INT32", {4, false, true}},   {"NIFTI_TYPE_UINT32", {4, false, false}},
    {"NIFTI_TYPE_INT64", {8, false, true}},   {"NIFTI_TYPE_FLOAT32", {4, true, true}},
    {"NIFTI_TYPE_FLOAT64", {8, true, true}}};
  for(const Entry& e : table)
    if(t == e.name) return e.type;
  throw Invalid_input(where + ": unsupported DataType \"" + t + "\"");
}

/// The value stored in `size` bytes at `p` (already in host order).
inline double binary_value(const unsigned char* p, const Nifti_type& t)
{
  if(t.is_float) {
    if(t.size == 4) { float f; std::memcpy(&f, p, 4); return f; }
    double d; std::memcpy(&d, p, 8); return d;
  }
  switch(t.size) {
  case 1: { if(t.is_signed) { std::int8_t v; std::memcpy(&v, p, 1); return v; } return p[0]; }
  case 2: { if(t.is_signed) { std::int16_t v; std::memcpy(&v, p, 2); return v; } std::uint16_t v; std::memcpy(&v, p, 2); return v; }
  case 4: { if(t.is_signed) { std::int32_t v; std::memcpy(&v, p, 4); return v; } std::uint32_t v; std::memcpy(&v, p, 4); return v; }
  default: { std::int64_t v; std::memcpy(&v, p, 8); return double(v); }
  }
}

inline bool host_is_little_endian()
{
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

/// The attribute `name` of an XML start tag (entities decoded), or "" if absent.
inline std::string attribute(const std::string& tag, const std::string& name)
{
  std::size_t p = 0;
  while((p = tag.find(name, p)) != std::string::npos) {
    const bool starts = p > 0 && std::isspace(static_cast<unsigned char>(tag[p - 1]));
    std::size_t q = p + name.size();
    while(q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
    if(starts && q < tag.size() && tag[q] == '=') {
      ++q;
      while(q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
      if(q >= tag.size() || (tag[q] != '"' && tag[q] != '\'')) return "";
      const std::size_t e = tag.find(tag[q], q + 1);
      if(e == std::string::npos) return "";
      std::string v = tag.substr(q + 1, e - q - 1), out;
      static const char* entities[][2] = {{"&amp;", "&"}, {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}};
      for(std::size_t i = 0; i < v.size();) {
        bool replaced = false;
        for(const auto& en : entities)
          if(v.compare(i, std::strlen(en[0]), en[0]) == 0) {
            out += en[1];
            i += std::strlen(en[0]);
            replaced = true;
            break;
          }
        if(!replaced) out += v[i++];
      }
      return out;
    }
    p = q;
  }
  return "";
}

/// The text between `<Data>` and `</Data>` of one DataArray element (CDATA markers removed).
inline std::string data_text(const std::string& element, const std::string& where)
{
  std::size_t p = 0;
  while((p = element.find("<Data", p)) != std::string::npos) {
    const char next = p + 5 < element.size() ? element[p + 5] : '\0';
    if(next == '>' || next == '/' || std::isspace(static_cast<unsigned char>(next))) break;
    p += 5;
  }
  if(p == std::string::npos) throw Invalid_input(where + ": a DataArray has no Data element");
  const std::size_t b = element.find('>', p);
  if(b == std::string::npos) throw Invalid_input(where + ": unterminated Data element");
  if(element[b - 1] == '/') return "";
  const std::size_t e = element.find("</Data>", b);
  if(e == std::string::npos) throw Invalid_input(where + ": a Data element is not closed");
  std::string t = element.substr(b + 1, e - b - 1);
  const std::size_t c = t.find("<![CDATA[");
  if(c != std::string::npos) {
    const std::size_t d = t.find("]]>", c);
    t = t.substr(c + 9, d == std::string::npos ? std::string::npos : d - c - 9);
  }
  return t;
}

inline GIfTI_data_array parse_data_array(const std::string& tag, const std::string& element, const std::string& where)
{
  GIfTI_data_array a;
  a.intent = attribute(tag, "Intent");
  a.data_type = attribute(tag, "DataType");
  const Nifti_type type = nifti_type(a.data_type, where);
  const std::string dimensionality = attribute(tag, "Dimensionality");
  const int nd = dimensionality.empty() ? 0 : std::atoi(dimensionality.c_str());
  if(nd < 1 || nd > 6) throw Invalid_input(where + ": DataArray with Dimensionality \"" + dimensionality + "\"");
  std::size_t count = 1;
  for(int d = 0; d < nd; ++d) {
    const std::string s = attribute(tag, "Dim" + std::to_string(d));
    const long long v = s.empty() ? -1 : std::atoll(s.c_str());
    if(v < 0 || v > (1LL << 31)) throw Invalid_input(where + ": DataArray Dim" + std::to_string(d) + " is missing or invalid");
    a.dims.push_back(std::size_t(v));
    count *= std::size_t(v);
  }
  const std::string encoding = attribute(tag, "Encoding");
  const std::string text = data_text(element, where);
  if(encoding == "ASCII") {
    std::istringstream in(text);
    double v;
    while(in >> v) a.values.push_back(v);
    if(!in.eof()) throw Invalid_input(where + ": invalid number in ASCII data");
  } else if(encoding == "Base64Binary" || encoding == "GZipBase64Binary") {
    std::vector<unsigned char> bytes = base64_decode(text, where);
    if(encoding == "GZipBase64Binary") bytes = inflate_zlib(bytes, count * type.size, where);
    if(bytes.size() != count * type.size)
      throw Invalid_input(where + ": " + std::to_string(bytes.size()) + " bytes of data for " + std::to_string(count) +
                          " values of " + a.data_type);
    const bool big = attribute(tag, "Endian") == "BigEndian";
    if(big == host_is_little_endian())
      for(std::size_t i = 0; i < count; ++i)
        for(std::size_t j = 0; j < type.size / 2; ++j) std::swap(bytes[i * type.size + j], bytes[(i + 1) * type.size - 1 - j]);
    a.values.resize(count);
    for(std::size_t i = 0; i < count; ++i) a.values[i] = binary_value(&bytes[i * type.size], type);
  } else if(encoding == "ExternalFileBinary") {
    throw Invalid_input(where + ": DataArray with external data files are not read");
  } else {
    throw Invalid_input(where + ": unknown DataArray Encoding \"" + encoding + "\"");
  }
  if(a.values.size() != count)
    throw Invalid_input(where + ": " + std::to_string(a.values.size()) + " values for the declared " +
                        std::to_string(count));
  if(nd == 2 && attribute(tag, "ArrayIndexingOrder") == "ColumnMajorOrder") {
    std::vector<double> row_major(count);
    for(std::size_t i = 0; i < a.dims[0]; ++i)
      for(std::size_t j = 0; j < a.dims[1]; ++j) row_major[i * a.dims[1] + j] = a.values[j * a.dims[0] + i];
    a.values.swap(row_major);
  }
  return a;
}

/// Little-endian bytes of the values converted to T.
template <class T>
std::vector<unsigned char> little_endian_bytes(const std::vector<T>& v)
{
  std::vector<unsigned char> b(v.size() * sizeof(T));
  std::memcpy(b.data(), v.data(), b.size());
  if(!host_is_little_endian())
    for(std::size_t i = 0; i < v.size(); ++i)
      for(std::size_t j = 0; j < sizeof(T) / 2; ++j) std::swap(b[i * sizeof(T) + j], b[(i + 1) * sizeof(T) - 1 - j]);
  return b;
}

inline void write_data_array(std::ostream& os, const char* intent, const char* type, std::size_t rows,
                             std::size_t columns, const std::vector<unsigned char>& bytes, bool pointset)
{
  os << "  <DataArray Intent=\"" << intent << "\" DataType=\"" << type
     << "\" ArrayIndexingOrder=\"RowMajorOrder\" Dimensionality=\"" << (columns > 1 ? 2 : 1) << "\" Dim0=\"" << rows
     << "\"";
  if(columns > 1) os << " Dim1=\"" << columns << "\"";
  os << " Encoding=\"Base64Binary\" Endian=\"LittleEndian\" ExternalFileName=\"\" ExternalFileOffset=\"\">\n"
     << "    <MetaData></MetaData>\n";
  if(pointset)
    os << "    <CoordinateSystemTransformMatrix>\n"
       << "      <DataSpace><![CDATA[NIFTI_XFORM_UNKNOWN]]></DataSpace>\n"
       << "      <TransformedSpace><![CDATA[NIFTI_XFORM_UNKNOWN]]></TransformedSpace>\n"
       << "      <MatrixData>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</MatrixData>\n"
       << "    </CoordinateSystemTransformMatrix>\n";
  os << "    <Data>" << base64_encode(bytes) << "</Data>\n  </DataArray>\n";
}

inline void write_gifti_header(std::ostream& os, int arrays)
{
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<!DOCTYPE GIFTI SYSTEM \"http://www.nitrc.org/frs/download.php/115/gifti.dtd\">\n"
     << "<GIFTI Version=\"1.0\" NumberOfDataArrays=\"" << arrays << "\">\n"
     << "  <MetaData>\n    <MD>\n      <Name><![CDATA[generator]]></Name>\n"
     << "      <Value><![CDATA[Density_equalizing_maps]]></Value>\n    </MD>\n  </MetaData>\n"
     << "  <LabelTable></LabelTable>\n";
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads every data array of a GIfTI file.
/// \throws Invalid_input for a missing file, a file without `<GIFTI`, or an array that cannot be decoded
///         (the message names the array and the reason)
/// \param filename the GIfTI file
/// \returns the data arrays in file order
inline std::vector<GIfTI_data_array> read_GIfTI_data_arrays(const std::string& filename)
{
  std::ifstream in(filename, std::ios::binary);
  if(!in) throw Invalid_input("cannot open " + filename);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string xml = buffer.str();
  if(xml.find("<GIFTI") == std::string::npos) throw Invalid_input(filename + ": not a GIfTI file (no <GIFTI> element)");
  std::vector<GIfTI_data_array> arrays;
  std::size_t p = 0;
  while((p = xml.find("<DataArray", p)) != std::string::npos) {
    const std::size_t tag_end = xml.find('>', p);
    const std::size_t end = xml.find("</DataArray>", p);
    if(tag_end == std::string::npos || end == std::string::npos)
      throw Invalid_input(filename + ": unterminated DataArray element");
    const std::string where = filename + " (DataArray " + std::to_string(arrays.size()) + ")";
    arrays.push_back(internal::parse_data_array(xml.substr(p, tag_end - p), xml.substr(tag_end, end - tag_end), where));
    p = end;
  }
  return arrays;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads a GIfTI surface: its `NIFTI_INTENT_POINTSET` (n x 3) and `NIFTI_INTENT_TRIANGLE` (m x 3) arrays.
/// \throws Invalid_input if either array is missing or malformed, or a vertex index is out of range
/// \param filename the `.surf.gii` file
/// \returns the vertices and triangles of the surface
inline Triangle_soup read_GIfTI_surface(const std::string& filename)
{
  const GIfTI_data_array *points = nullptr, *triangles = nullptr;
  const std::vector<GIfTI_data_array> arrays = read_GIfTI_data_arrays(filename);
  for(const GIfTI_data_array& a : arrays) {
    if(a.intent == "NIFTI_INTENT_POINTSET" && !points) points = &a;
    if(a.intent == "NIFTI_INTENT_TRIANGLE" && !triangles) triangles = &a;
  }
  if(!points || !triangles)
    throw Invalid_input(filename + ": a GIfTI surface needs a NIFTI_INTENT_POINTSET and a NIFTI_INTENT_TRIANGLE "
                        "data array (is it a data file such as .func.gii or .shape.gii?)");
  if(points->dims.size() != 2 || points->dims[1] != 3) throw Invalid_input(filename + ": the POINTSET array is not n x 3");
  if(triangles->dims.size() != 2 || triangles->dims[1] != 3) throw Invalid_input(filename + ": the TRIANGLE array is not m x 3");
  Triangle_soup s;
  s.points.resize(points->dims[0]);
  for(std::size_t i = 0; i < s.points.size(); ++i)
    for(int c = 0; c < 3; ++c) {
      s.points[i][c] = points->values[3 * i + c];
      if(!std::isfinite(s.points[i][c])) throw Invalid_input(filename + ": vertex " + std::to_string(i) + " is not finite");
    }
  s.faces.resize(triangles->dims[0]);
  for(std::size_t k = 0; k < s.faces.size(); ++k)
    for(int c = 0; c < 3; ++c) {
      const double v = triangles->values[3 * k + c];
      if(!(v >= 0) || v >= double(s.points.size()) || v != std::floor(v))
        throw Invalid_input(filename + ": triangle " + std::to_string(k) + " has an invalid vertex index");
      s.faces[k][c] = std::size_t(v);
    }
  return s;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads one value per vertex from a GIfTI data file (e.g. `.shape.gii`): the
/// data array number `index` among the arrays that are neither POINTSET nor TRIANGLE,
/// which must hold `expected_vertices` values (one column; 0 = no check).
/// \throws Invalid_input if there is no such array, its size differs, or a value is not finite
/// \param filename the GIfTI data file
/// \param expected_vertices the number of values required (0: no check)
/// \param index which per-vertex data array, counted from 0
/// \returns one value per vertex
inline std::vector<double> read_GIfTI_vertex_values(const std::string& filename, std::size_t expected_vertices = 0,
                                                    std::size_t index = 0)
{
  std::size_t k = 0;
  for(const GIfTI_data_array& a : read_GIfTI_data_arrays(filename)) {
    if(a.intent == "NIFTI_INTENT_POINTSET" || a.intent == "NIFTI_INTENT_TRIANGLE") continue;
    if(k++ != index) continue;
    if(a.dims.size() > 1 && !(a.dims.size() == 2 && a.dims[1] == 1))
      throw Invalid_input(filename + ": the data array has more than one value per vertex");
    if(expected_vertices > 0 && a.values.size() != expected_vertices)
      throw Invalid_input(filename + ": " + std::to_string(a.values.size()) + " values for a surface of " +
                          std::to_string(expected_vertices) + " vertices");
    for(std::size_t i = 0; i < a.values.size(); ++i)
      if(!std::isfinite(a.values[i])) throw Invalid_input(filename + ": value " + std::to_string(i) + " is not finite");
    return a.values;
  }
  throw Invalid_input(filename + ": no per-vertex data array number " + std::to_string(index) +
                      " (arrays other than POINTSET and TRIANGLE are counted from 0)");
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes a GIfTI surface (`.surf.gii`): float32 POINTSET and int32 TRIANGLE arrays, Base64Binary.
/// \throws Invalid_input if the file cannot be written
/// \param filename the file to write
/// \param s the surface
inline void write_GIfTI_surface(const std::string& filename, const Triangle_soup& s)
{
  std::vector<float> xyz;
  xyz.reserve(3 * s.points.size());
  for(const auto& p : s.points)
    for(double x : p) xyz.push_back(float(x));
  std::vector<std::int32_t> ijk;
  ijk.reserve(3 * s.faces.size());
  for(const auto& f : s.faces)
    for(std::size_t i : f) ijk.push_back(std::int32_t(i));
  std::ofstream os(filename, std::ios::binary);
  if(!os) throw Invalid_input("cannot write " + filename);
  internal::write_gifti_header(os, 2);
  internal::write_data_array(os, "NIFTI_INTENT_POINTSET", "NIFTI_TYPE_FLOAT32", s.points.size(), 3,
                             internal::little_endian_bytes(xyz), true);
  internal::write_data_array(os, "NIFTI_INTENT_TRIANGLE", "NIFTI_TYPE_INT32", s.faces.size(), 3,
                             internal::little_endian_bytes(ijk), false);
  os << "</GIFTI>\n";
  os.close();
  if(!os) throw Invalid_input("error while writing " + filename);
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes one float32 value per vertex as a GIfTI data file (`NIFTI_INTENT_SHAPE`, e.g. `.shape.gii`).
/// \throws Invalid_input if the file cannot be written
/// \param filename the file to write
/// \param values one value per vertex
inline void write_GIfTI_vertex_values(const std::string& filename, const std::vector<double>& values)
{
  const std::vector<float> v(values.begin(), values.end());
  std::ofstream os(filename, std::ios::binary);
  if(!os) throw Invalid_input("cannot write " + filename);
  internal::write_gifti_header(os, 1);
  internal::write_data_array(os, "NIFTI_INTENT_SHAPE", "NIFTI_TYPE_FLOAT32", v.size(), 1,
                             internal::little_endian_bytes(v), false);
  os << "</GIFTI>\n";
  os.close();
  if(!os) throw Invalid_input("error while writing " + filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_GIFTI_H
