// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_CSV_VALUES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_CSV_VALUES_H

/// \file csv_values.h
/// A table of one value per region identifier, read from a CSV file (RFC 4180:
/// comma-separated, a header row, fields optionally in double quotes with `""`
/// for a quote inside).

#include <CGAL/Density_equalizing_maps/Map_report.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

namespace internal {

/// The fields of one CSV line; false if a quoted field is not closed.
inline bool split_csv_line(const std::string& line, std::vector<std::string>& fields)
{
  fields.assign(1, std::string());
  bool quoted = false;
  for(std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if(quoted) {
      if(c == '"' && i + 1 < line.size() && line[i + 1] == '"') { fields.back() += '"'; ++i; }
      else if(c == '"') quoted = false;
      else fields.back() += c;
    } else if(c == '"') quoted = true;
    else if(c == ',') fields.emplace_back();
    else if(c != '\r') fields.back() += c;
  }
  for(std::string& f : fields) { // surrounding blanks are not part of a value
    const std::size_t a = f.find_first_not_of(" \t"), b = f.find_last_not_of(" \t");
    f = a == std::string::npos ? std::string() : f.substr(a, b - a + 1);
  }
  return !quoted;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads one non-negative value per identifier from a CSV file with a header row.
///
/// The identifier column is the column named `id_column`, or the first column if no
/// column has that name. The value column is the column named `value_column`; if
/// `value_column` is empty, the table must have exactly two columns and the value is the
/// other one. Blank lines are skipped.
///
/// \param filename the CSV file
/// \param id_column the name of the identifier column
/// \param value_column the name of the value column (may be empty, see above)
/// \returns the value of each identifier
/// \throws Invalid_input naming the file and the line: unreadable file, no header, unknown
///   value column, a line with too few fields or an unclosed quote, an empty or repeated
///   identifier, a value that is not a number, not finite or negative
inline std::map<std::string, double> read_CSV_values(const std::string& filename, const std::string& id_column,
                                                     const std::string& value_column)
{
  std::ifstream in(filename);
  if(!in) throw Invalid_input(filename + ": cannot open the values file");
  std::string line;
  std::vector<std::string> header, fields;
  std::size_t line_number = 0;
  while(std::getline(in, line)) {
    ++line_number;
    if(line.find_first_not_of(" \t\r") != std::string::npos) break;
  }
  const std::string at_header = filename + ":" + std::to_string(line_number);
  if(line_number == 0 || line.find_first_not_of(" \t\r") == std::string::npos)
    throw Invalid_input(filename + ": the values file is empty (a header row is expected)");
  if(!internal::split_csv_line(line, header)) throw Invalid_input(at_header + ": unclosed quote in the header row");
  if(header.size() > 0 && header[0].size() >= 3 && header[0].compare(0, 3, "\xEF\xBB\xBF") == 0)
    header[0].erase(0, 3); // byte order mark
  std::size_t id = 0, value = header.size();
  for(std::size_t k = 0; k < header.size(); ++k)
    if(header[k] == id_column) id = k;
  std::string columns;
  for(const std::string& h : header) columns += (columns.empty() ? "" : ", ") + h;
  if(value_column.empty()) {
    if(header.size() != 2)
      throw Invalid_input(at_header + ": the table has " + std::to_string(header.size()) +
                          " columns (" + columns + "): name the value column");
    value = 1 - id;
  } else {
    for(std::size_t k = 0; k < header.size(); ++k)
      if(header[k] == value_column) value = k;
    if(value == header.size())
      throw Invalid_input(at_header + ": no column named \"" + value_column + "\" (columns: " + columns + ")");
  }
  if(value == id) throw Invalid_input(at_header + ": the value column is the identifier column");
  std::map<std::string, double> out;
  while(std::getline(in, line)) {
    ++line_number;
    if(line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string at = filename + ":" + std::to_string(line_number);
    if(!internal::split_csv_line(line, fields)) throw Invalid_input(at + ": unclosed quote");
    if(fields.size() <= std::max(id, value))
      throw Invalid_input(at + ": " + std::to_string(fields.size()) + " fields, the header has " +
                          std::to_string(header.size()));
    const std::string& key = fields[id];
    if(key.empty()) throw Invalid_input(at + ": empty identifier");
    const std::string& text = fields[value];
    char* end = nullptr;
    errno = 0;
    const double v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
    if(text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
      throw Invalid_input(at + ": the value \"" + text + "\" of \"" + key + "\" is not a number");
    if(v < 0) throw Invalid_input(at + ": the value " + text + " of \"" + key + "\" is negative");
    if(!out.emplace(key, v).second) throw Invalid_input(at + ": the identifier \"" + key + "\" is repeated");
  }
  return out;
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_CSV_VALUES_H
