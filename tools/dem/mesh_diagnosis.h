// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Why a mesh file cannot be read. CGAL's readers answer only "false" (and
// trust header counts), so the dem tool first scans the file itself (OFF, OBJ, PLY ascii and
// binary, STL ascii and binary) for the causes a user can fix: a non-finite
// coordinate (line k / vertex k), a face index out of range (face k), a file
// shorter than its header announces, a malformed line. The mesh itself is
// then read by CGAL.

#ifndef DEM_TOOL_MESH_DIAGNOSIS_H
#define DEM_TOOL_MESH_DIAGNOSIS_H

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dem_cli {
namespace diagnosis {

/// Splits a line into blank-separated tokens, dropping a '#' comment. The
/// blanks are the C locale's white space, where `>>` splits too; no stream
/// per line (the scan of a 1M-face OFF file spent most of its time there).
inline std::vector<std::string> tokens(const std::string& line)
{
  std::vector<std::string> t;
  const std::size_t end = std::min(line.find('#'), line.size());
  auto blank = [&](std::size_t i) { return std::isspace(static_cast<unsigned char>(line[i])) != 0; };
  for(std::size_t i = 0; i < end;) {
    while(i < end && blank(i)) ++i;
    std::size_t j = i;
    while(j < end && !blank(j)) ++j;
    if(j > i) t.emplace_back(line, i, j - i);
    i = j;
  }
  return t;
}

/// A decimal number token: `ok` false if it is not one; the value may be
/// non-finite ("nan", "inf", or out of the range of double).
inline double number(const std::string& s, bool& ok)
{
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  ok = end != s.c_str() && *end == '\0';
  if(ok && errno == ERANGE && std::abs(v) > 1) return HUGE_VAL; // overflow; underflow is a finite 0
  return v;
}

/// A non-negative integer token (no sign, no fraction).
inline bool index_token(const std::string& s, long long& v)
{
  if(s.empty()) return false;
  std::size_t i = (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if(i == s.size()) return false;
  for(std::size_t k = i; k < s.size(); ++k)
    if(!std::isdigit(static_cast<unsigned char>(s[k]))) return false;
  errno = 0;
  v = std::strtoll(s.c_str(), nullptr, 10);
  return errno != ERANGE;
}

inline std::string at_line(std::size_t line) { return "line " + std::to_string(line) + ": "; }

inline std::string check_coordinates(const std::vector<std::string>& t, std::size_t first, std::size_t vertex,
                                     std::size_t line)
{
  if(t.size() < first + 3) return at_line(line) + "vertex " + std::to_string(vertex) + " has fewer than 3 coordinates";
  for(std::size_t c = first; c < first + 3; ++c) {
    bool ok = false;
    const double v = number(t[c], ok);
    if(!ok) return at_line(line) + "vertex " + std::to_string(vertex) + ": \"" + t[c] + "\" is not a number";
    if(!std::isfinite(v))
      return at_line(line) + "non-finite coordinate \"" + t[c] + "\" at vertex " + std::to_string(vertex);
  }
  return "";
}

/// `first` is the index of the first vertex: 0, or 1 in OBJ files.
inline std::string index_out_of_range(std::size_t face, long long index, std::size_t vertices, std::size_t line,
                                      long long first = 0)
{
  return at_line(line) + "face " + std::to_string(face) + ": vertex index " + std::to_string(index) +
         " out of range (the file has " + std::to_string(vertices) + " vertices, indices " + std::to_string(first) +
         ".." + std::to_string((long long)vertices - 1 + first) + ")";
}

/// OFF (and its COFF/NOFF/... variants with extra per-vertex values).
inline std::string diagnose_off(std::istream& in)
{
  std::string line;
  std::size_t n = 0;
  auto next = [&](std::vector<std::string>& t) {
    while(std::getline(in, line)) {
      ++n;
      t = tokens(line);
      if(!t.empty()) return true;
    }
    return false;
  };
  std::vector<std::string> t;
  if(!next(t)) return "empty file";
  std::size_t first = 0;
  if(t[0].find("OFF") != std::string::npos) {
    if(t[0].find('4') != std::string::npos || t[0].find('n') != std::string::npos)
      return ""; // 4OFF / nOFF: dimensions other than 3, left to CGAL
    if(t.size() == 1 && !next(t)) return at_line(n) + "missing the counts line";
    if(t.size() > 1 && t.size() >= 4) first = 1; // counts on the OFF line
  }
  long long nv = 0, nf = 0;
  if(t.size() < first + 2 || !index_token(t[first], nv) || !index_token(t[first + 1], nf) || nv < 0 || nf < 0)
    return at_line(n) + "expected the counts \"vertices faces edges\"";
  for(long long i = 0; i < nv; ++i) {
    if(!next(t)) return "the header announces " + std::to_string(nv) + " vertices, the file ends after " +
                        std::to_string(i);
    const std::string e = check_coordinates(t, 0, std::size_t(i), n);
    if(!e.empty()) return e;
  }
  for(long long k = 0; k < nf; ++k) {
    if(!next(t)) return "the header announces " + std::to_string(nf) + " faces, the file ends after " +
                        std::to_string(k);
    long long m = 0;
    if(!index_token(t[0], m) || m < 0) return at_line(n) + "face " + std::to_string(k) + ": bad vertex count";
    if(std::size_t(m) + 1 > t.size())
      return at_line(n) + "face " + std::to_string(k) + " announces " + std::to_string(m) + " vertices, lists " +
             std::to_string(t.size() - 1);
    if(m < 3) return at_line(n) + "face " + std::to_string(k) + " has " + std::to_string(m) + " vertices (at least 3)";
    for(long long c = 1; c <= m; ++c) {
      long long v = 0;
      if(!index_token(t[c], v)) return at_line(n) + "face " + std::to_string(k) + ": \"" + t[c] + "\" is not an index";
      if(v < 0 || v >= nv) return index_out_of_range(std::size_t(k), v, std::size_t(nv), n);
    }
  }
  return "";
}

/// OBJ: "v x y z" and "f a b c" lines (a = index[/texture[/normal]], 1-based,
/// negative = relative to the last vertex).
inline std::string diagnose_obj(std::istream& in)
{
  std::string line;
  std::size_t n = 0, nv = 0, nf = 0;
  struct Pending { std::size_t face, line; long long index; };
  std::vector<Pending> forward; // positive indices are checked against the final count
  while(std::getline(in, line)) {
    ++n;
    const std::vector<std::string> t = tokens(line);
    if(t.empty()) continue;
    if(t[0] == "v") {
      const std::string e = check_coordinates(t, 1, nv, n);
      if(!e.empty()) return e;
      ++nv;
    } else if(t[0] == "f") {
      if(t.size() < 4) return at_line(n) + "face " + std::to_string(nf) + " has fewer than 3 vertices";
      for(std::size_t c = 1; c < t.size(); ++c) {
        long long v = 0;
        if(!index_token(t[c].substr(0, t[c].find('/')), v) || v == 0)
          return at_line(n) + "face " + std::to_string(nf) + ": \"" + t[c] + "\" is not a vertex reference";
        if(v < 0 && -v > (long long)nv) return index_out_of_range(nf, v, nv, n, 1) + " (negative: counted back from the last vertex)";
        if(v > 0) forward.push_back({nf, n, v});
      }
      ++nf;
    }
  }
  for(const Pending& p : forward)
    if(p.index > (long long)nv) return index_out_of_range(p.face, p.index, nv, p.line, 1);
  return "";
}

/// Binary STL: an 80-byte header, a triangle count, 50 bytes per triangle.
inline std::string diagnose_binary_stl(std::istream& in, std::uintmax_t size)
{
  char header[80];
  std::uint32_t count = 0;
  if(!in.read(header, 80) || !in.read(reinterpret_cast<char*>(&count), 4)) return "truncated binary STL header";
  if(size != 84 + 50 * std::uintmax_t(count))
    return "binary STL: the header announces " + std::to_string(count) + " triangles (" +
           std::to_string(84 + 50 * std::uintmax_t(count)) + " bytes), the file has " + std::to_string(size) + " bytes";
  for(std::uint32_t k = 0; k < count; ++k) {
    float f[12];
    char attribute[2];
    if(!in.read(reinterpret_cast<char*>(f), 48) || !in.read(attribute, 2)) return "truncated at triangle " + std::to_string(k);
    for(int c = 3; c < 12; ++c)
      if(!std::isfinite(f[c]))
        return "binary STL: non-finite coordinate at triangle " + std::to_string(k) + ", corner " +
               std::to_string((c - 3) / 3);
  }
  return "";
}

inline std::string diagnose_ascii_stl(std::istream& in)
{
  std::string line;
  std::size_t n = 0, corners = 0;
  while(std::getline(in, line)) {
    ++n;
    const std::vector<std::string> t = tokens(line);
    if(t.empty() || t[0] != "vertex") continue;
    const std::string e = check_coordinates(t, 1, corners, n);
    if(!e.empty()) return e + " (corner " + std::to_string(corners % 3) + " of triangle " +
                          std::to_string(corners / 3) + ")";
    ++corners;
  }
  if(corners % 3) return "ascii STL: " + std::to_string(corners) + " vertex lines, not a multiple of 3";
  return "";
}

/// PLY: header, then the elements; "vertex" (x, y, z) and "face" (a list of
/// indices) are checked, other elements skipped. ascii and both binary orders.
inline std::string diagnose_ply(std::istream& in)
{
  struct Property { std::string name, type, count_type; bool list = false; };
  struct Element { std::string name; long long count = 0; std::vector<Property> properties; };
  std::string line, format;
  std::vector<Element> elements;
  std::size_t n = 0;
  if(!std::getline(in, line) || tokens(line).empty() || tokens(line)[0] != "ply") return "PLY: missing \"ply\" magic line";
  n = 1;
  bool ended = false;
  while(std::getline(in, line)) {
    ++n;
    if(!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::vector<std::string> t;
    for(std::string s; ls >> s;) t.push_back(s);
    if(t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if(t[0] == "end_header") { ended = true; break; }
    if(t[0] == "format" && t.size() >= 2) format = t[1];
    else if(t[0] == "element" && t.size() == 3) {
      Element e;
      e.name = t[1];
      if(!index_token(t[2], e.count) || e.count < 0) return at_line(n) + "bad element count \"" + t[2] + "\"";
      elements.push_back(e);
    } else if(t[0] == "property" && !elements.empty()) {
      Property p;
      if(t.size() == 5 && t[1] == "list") { p.list = true; p.count_type = t[2]; p.type = t[3]; p.name = t[4]; }
      else if(t.size() == 3) { p.type = t[1]; p.name = t[2]; }
      else return at_line(n) + "malformed property line";
      elements.back().properties.push_back(p);
    } else return at_line(n) + "unexpected header line \"" + line + "\"";
  }
  if(!ended) return "PLY: no end_header";
  if(format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    return "PLY: unknown format \"" + format + "\"";
  const bool ascii = format == "ascii";
  const std::uint16_t probe = 1;
  const bool little_endian_host = *reinterpret_cast<const unsigned char*>(&probe) == 1;
  const bool swap = (format == "binary_big_endian") == little_endian_host;
  auto type_size = [](const std::string& s) -> int {
    if(s == "char" || s == "uchar" || s == "int8" || s == "uint8") return 1;
    if(s == "short" || s == "ushort" || s == "int16" || s == "uint16") return 2;
    if(s == "int" || s == "uint" || s == "float" || s == "int32" || s == "uint32" || s == "float32") return 4;
    if(s == "double" || s == "float64") return 8;
    return 0;
  };
  for(const Element& e : elements)
    for(const Property& p : e.properties)
      if(!type_size(p.type) || (p.list && !type_size(p.count_type))) return "PLY: unknown property type in " + e.name;
  // one binary value, converted to double
  auto read_binary = [&](const std::string& type, double& v) {
    unsigned char b[8];
    const int s = type_size(type);
    if(!in.read(reinterpret_cast<char*>(b), s)) return false;
    if(swap) std::reverse(b, b + s);
    auto as = [&](auto x) { std::memcpy(&x, b, sizeof x); v = double(x); };
    if(type == "char" || type == "int8") as(std::int8_t());
    else if(type == "uchar" || type == "uint8") as(std::uint8_t());
    else if(type == "short" || type == "int16") as(std::int16_t());
    else if(type == "ushort" || type == "uint16") as(std::uint16_t());
    else if(type == "int" || type == "int32") as(std::int32_t());
    else if(type == "uint" || type == "uint32") as(std::uint32_t());
    else if(type == "float" || type == "float32") as(float());
    else as(double());
    return true;
  };
  std::vector<std::string> ascii_tokens;
  std::size_t ascii_next = 0;
  auto read_ascii = [&](double& v, bool& is_number) {
    while(ascii_next >= ascii_tokens.size()) {
      if(!std::getline(in, line)) return false;
      ++n;
      ascii_tokens = tokens(line);
      ascii_next = 0;
    }
    v = number(ascii_tokens[ascii_next++], is_number);
    return true;
  };
  auto read_value = [&](const std::string& type, double& v, bool& is_number) {
    is_number = true;
    return ascii ? read_ascii(v, is_number) : read_binary(type, v);
  };
  const std::string where_prefix = ascii ? "" : "binary PLY: ";
  long long vertex_count = -1;
  for(const Element& e : elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    if(vertex) vertex_count = e.count;
    for(long long r = 0; r < e.count; ++r) {
      for(const Property& p : e.properties) {
        double v = 0;
        bool is_number = true;
        const std::string here = ascii ? at_line(n + 1) : where_prefix;
        if(!read_value(p.list ? p.count_type : p.type, v, is_number))
          return "PLY: the header announces " + std::to_string(e.count) + " " + e.name + " elements, the file ends in " +
                 e.name + " " + std::to_string(r);
        if(!is_number) return (ascii ? at_line(n) : where_prefix) + e.name + " " + std::to_string(r) + ": not a number";
        if(!p.list) {
          if(vertex && (p.name == "x" || p.name == "y" || p.name == "z") && !std::isfinite(v))
            return (ascii ? at_line(n) : where_prefix) + "non-finite coordinate " + p.name + " at vertex " +
                   std::to_string(r);
          continue;
        }
        if(!(v >= 0) || v != std::floor(v) || v > 1e6) return here + e.name + " " + std::to_string(r) + ": bad list length";
        const long long m = (long long)v;
        for(long long c = 0; c < m; ++c) {
          if(!read_value(p.type, v, is_number)) return "PLY: the file ends in " + e.name + " " + std::to_string(r);
          if(!is_number) return (ascii ? at_line(n) : where_prefix) + e.name + " " + std::to_string(r) + ": not a number";
          if(face && (p.name == "vertex_indices" || p.name == "vertex_index") && vertex_count >= 0 &&
             (v < 0 || v >= double(vertex_count) || v != std::floor(v))) {
            std::string s = index_out_of_range(std::size_t(r), (long long)v, std::size_t(vertex_count), n);
            if(!ascii) s = where_prefix + s.substr(s.find(':') + 2);
            return s;
          }
        }
        if(face && m < 3) return here + "face " + std::to_string(r) + " has " + std::to_string(m) + " vertices";
      }
    }
  }
  return "";
}

} // namespace diagnosis

/// A specific reason why `path` is not a readable mesh, or "" if none is
/// found (the caller then reports a generic failure).
inline std::string diagnose_mesh_file(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  std::ifstream in(path, std::ios::binary);
  if(!in) return "cannot open the file";
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if(!ec && size == 0) return "the file is empty";
  if(ext == ".off") return diagnosis::diagnose_off(in);
  if(ext == ".obj") return diagnosis::diagnose_obj(in);
  if(ext == ".ply") return diagnosis::diagnose_ply(in);
  if(ext == ".stl") {
    char head[6] = {0};
    in.read(head, 5);
    in.clear();
    in.seekg(0);
    // "solid" starts ascii files, and some binary headers; the size decides
    if(std::string(head) == "solid" && !(size >= 84 && diagnosis::diagnose_binary_stl(in, size).empty())) {
      in.clear();
      in.seekg(0);
      return diagnosis::diagnose_ascii_stl(in);
    }
    in.clear();
    in.seekg(0);
    return diagnosis::diagnose_binary_stl(in, size);
  }
  return "";
}

} // namespace dem_cli

#endif // DEM_TOOL_MESH_DIAGNOSIS_H
