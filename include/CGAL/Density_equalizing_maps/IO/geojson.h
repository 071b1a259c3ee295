// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_IO_GEOJSON_H
#define CGAL_DENSITY_EQUALIZING_MAPS_IO_GEOJSON_H

/// \file geojson.h
/// Regions of the globe in GeoJSON (RFC 7946): a FeatureCollection of Features
/// whose geometry is a Polygon or a MultiPolygon. Parsed with nlohmann::json
/// (Debian: nlohmann-json3-dev), which this header needs.

#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/internal/spherical_regions.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace IO {

/// \ingroup PkgDensityEqualizingMapsIO
/// Regions read from a GeoJSON file, with the properties of their features.
struct GeoJSON_regions
{
  std::vector<Spherical_region> regions; ///< one per distinct identifier, in order of first appearance
  std::vector<nlohmann::json> properties; ///< the properties of each region's first feature
  std::vector<std::size_t> feature;       ///< the index of each region's first feature in the file
};

namespace internal {

inline std::string feature_name(std::size_t k, const std::string& id_property, const std::string& id)
{
  std::string s = "feature " + std::to_string(k);
  if(!id.empty()) s += " (" + id_property + " \"" + id + "\")";
  return s;
}

inline std::vector<Lon_lat> read_ring(const nlohmann::json& ring, const std::string& where)
{
  if(!ring.is_array()) throw Invalid_input(where + ": a ring is not an array of positions");
  std::vector<Lon_lat> out;
  for(std::size_t i = 0; i < ring.size(); ++i) {
    const nlohmann::json& p = ring[i];
    if(!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      throw Invalid_input(where + ", position " + std::to_string(i) + ": not an array of numbers [longitude, latitude]");
    Lon_lat x;
    x.lon = p[0].get<double>();
    x.lat = p[1].get<double>();
    if(!(std::abs(x.lon) <= 180 && std::abs(x.lat) <= 90))
      throw Invalid_input(where + ", position " + std::to_string(i) + ": (" + p[0].dump() + ", " + p[1].dump() +
                          ") is outside longitude [-180, 180], latitude [-90, 90]");
    out.push_back(x);
  }
  if(out.size() < 4) throw Invalid_input(where + ": a ring needs at least 4 positions (got " + std::to_string(out.size()) + ")");
  if(out.front().lon != out.back().lon || out.front().lat != out.back().lat)
    throw Invalid_input(where + ": the ring is not closed (its last position differs from its first)");
  out.pop_back();
  return out;
}

inline Spherical_polygon read_polygon(const nlohmann::json& rings, const std::string& where)
{
  if(!rings.is_array() || rings.empty()) throw Invalid_input(where + ": a polygon must be a non-empty array of rings");
  Spherical_polygon p;
  for(std::size_t r = 0; r < rings.size(); ++r)
    p.rings.push_back(read_ring(rings[r], where + ", ring " + std::to_string(r)));
  return p;
}

} // namespace internal

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Reads the regions of a GeoJSON FeatureCollection (a single Feature is accepted too).
///
/// Each Feature has a `Polygon` or `MultiPolygon` geometry (rings of `[longitude, latitude]`
/// positions, closed, holes after the exterior ring) and its identifier in the property
/// `id_property` (or in the Feature's `id` member when `id_property` is `"id"`); a number is
/// turned into its decimal text. Features with the same identifier form one region. Edges are
/// great-circle arcs and each ring encloses its smaller side (see `Spherical_polygon`), so
/// rings crossing the antimeridian and rings around a pole need no special form.
///
/// \param filename the GeoJSON file
/// \param id_property the property that identifies a region
/// \returns the regions and their properties
/// \throws Invalid_input naming the file and, where it applies, the feature (its index and
///   identifier): unreadable file, malformed JSON (with the line and column of the parser),
///   no features, a geometry that is missing or of another type, a ring that is not closed,
///   has fewer than 4 positions or a position out of range, a missing identifier
inline GeoJSON_regions read_GeoJSON_regions(const std::string& filename, const std::string& id_property)
{
  std::ifstream in(filename);
  if(!in) throw Invalid_input(filename + ": cannot open the GeoJSON file");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch(const nlohmann::json::exception& e) {
    throw Invalid_input(filename + ": malformed JSON: " + e.what());
  }
  std::vector<const nlohmann::json*> features;
  if(doc.is_object() && doc.value("type", "") == "FeatureCollection" && doc.contains("features") &&
     doc["features"].is_array())
    for(const auto& f : doc["features"]) features.push_back(&f);
  else if(doc.is_object() && doc.value("type", "") == "Feature")
    features.push_back(&doc);
  else
    throw Invalid_input(filename + ": not a GeoJSON FeatureCollection (an object with \"type\": \"FeatureCollection\" "
                                   "and an array \"features\")");
  if(features.empty()) throw Invalid_input(filename + ": the FeatureCollection has no features");
  GeoJSON_regions out;
  std::map<std::string, std::size_t> index;
  for(std::size_t k = 0; k < features.size(); ++k) {
    const nlohmann::json& f = *features[k];
    std::string where = filename + ": " + internal::feature_name(k, id_property, "");
    if(!f.is_object() || f.value("type", "") != "Feature") throw Invalid_input(where + ": not a GeoJSON Feature");
    const nlohmann::json* id = nullptr;
    if(f.contains("properties") && f["properties"].is_object() && f["properties"].contains(id_property))
      id = &f["properties"][id_property];
    else if(id_property == "id" && f.contains("id"))
      id = &f["id"];
    if(id == nullptr || !(id->is_string() || id->is_number()))
      throw Invalid_input(where + ": no property \"" + id_property + "\" (a string or a number) to identify it");
    const std::string key = id->is_string() ? id->get<std::string>() : id->dump();
    if(key.empty()) throw Invalid_input(where + ": the property \"" + id_property + "\" is empty");
    where = filename + ": " + internal::feature_name(k, id_property, key);
    if(!f.contains("geometry") || f["geometry"].is_null() || !f["geometry"].is_object())
      throw Invalid_input(where + ": no geometry");
    const nlohmann::json& g = f["geometry"];
    const std::string type = g.value("type", "");
    if(type != "Polygon" && type != "MultiPolygon")
      throw Invalid_input(where + ": unknown geometry type \"" + type + "\" (Polygon or MultiPolygon expected)");
    if(!g.contains("coordinates") || !g["coordinates"].is_array())
      throw Invalid_input(where + ": the geometry has no array \"coordinates\"");
    std::vector<Spherical_polygon> polygons;
    if(type == "Polygon") polygons.push_back(internal::read_polygon(g["coordinates"], where));
    else
      for(std::size_t p = 0; p < g["coordinates"].size(); ++p)
        polygons.push_back(internal::read_polygon(g["coordinates"][p], where + ", polygon " + std::to_string(p)));
    auto it = index.find(key);
    if(it == index.end()) {
      index[key] = out.regions.size();
      Spherical_region r;
      r.id = key;
      r.polygons = std::move(polygons);
      out.regions.push_back(std::move(r));
      out.feature.push_back(k);
      out.properties.push_back(f.contains("properties") && f["properties"].is_object() ? f["properties"]
                                                                                       : nlohmann::json::object());
    } else {
      auto& dst = out.regions[it->second].polygons;
      dst.insert(dst.end(), polygons.begin(), polygons.end());
    }
  }
  return out;
}

/// \ingroup PkgDensityEqualizingMapsIO
/// \brief Writes regions as a GeoJSON FeatureCollection: one Feature per region with a
/// `MultiPolygon` geometry (rings closed by repeating their first position, in the order and
/// orientation of the input) and the given properties.
///
/// \param filename the file to write
/// \param regions the regions
/// \param properties the properties of each region (same size as `regions`, or empty: then
///   only the identifier, under `id_property`)
/// \param id_property the property the identifier is written under (overriding `properties`)
/// \param digits decimal digits of the coordinates
/// \throws Invalid_input if the sizes differ or the file cannot be written
inline void write_GeoJSON_regions(const std::string& filename, const std::vector<Spherical_region>& regions,
                                  const std::vector<nlohmann::json>& properties, const std::string& id_property,
                                  int digits = 6)
{
  if(!properties.empty() && properties.size() != regions.size())
    throw Invalid_input(filename + ": " + std::to_string(properties.size()) + " property sets for " +
                        std::to_string(regions.size()) + " regions");
  std::ofstream out(filename);
  if(!out) throw Invalid_input("cannot write " + filename);
  char buffer[64];
  auto number = [&](double v) {
    std::snprintf(buffer, sizeof(buffer), "%.*f", digits, v);
    return std::string(buffer);
  };
  out << "{\"type\":\"FeatureCollection\",\"features\":[\n";
  for(std::size_t r = 0; r < regions.size(); ++r) {
    nlohmann::json props = properties.empty() ? nlohmann::json::object() : properties[r];
    props[id_property] = regions[r].id;
    out << (r ? ",\n" : "") << "{\"type\":\"Feature\",\"properties\":" << props.dump()
        << ",\"geometry\":{\"type\":\"MultiPolygon\",\"coordinates\":[";
    for(std::size_t p = 0; p < regions[r].polygons.size(); ++p) {
      out << (p ? "," : "") << "[";
      const auto& rings = regions[r].polygons[p].rings;
      for(std::size_t g = 0; g < rings.size(); ++g) {
        out << (g ? "," : "") << "[";
        for(std::size_t i = 0; i <= rings[g].size(); ++i) {
          const Lon_lat& x = rings[g][i % rings[g].size()];
          out << (i ? "," : "") << "[" << number(x.lon) << "," << number(x.lat) << "]";
        }
        out << "]";
      }
      out << "]";
    }
    out << "]}}";
  }
  out << "\n]}\n";
  out.flush();
  if(!out) throw Invalid_input("error while writing " + filename);
}

} // namespace IO
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_IO_GEOJSON_H
