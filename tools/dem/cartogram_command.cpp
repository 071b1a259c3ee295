// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem cartogram REGIONS.geojson --values VALUES.csv --id-property NAME ...`:
// a globe cartogram (globe_cartogram.h) from regions in GeoJSON and values in
// CSV, written as deformed regions (GeoJSON), the deformed globe mesh with a
// region per face (PLY), a picture (SVG, PNG through rsvg-convert) and metrics
// (JSON). Every input problem is reported before anything is written (exit 3).

#include "commands.h"
#include "dem_stages.h"
#include "output_files.h"

#include <CGAL/Density_equalizing_maps/IO/csv_values.h>
#include <CGAL/Density_equalizing_maps/IO/geojson.h>
#include <CGAL/Density_equalizing_maps/IO/globe_picture.h>
#include <CGAL/Density_equalizing_maps/globe_cartogram.h>
#include <CGAL/Density_equalizing_maps/internal/uniform_domain_mesh.h>
#include <CGAL/Density_equalizing_maps/remeshing.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace dem_cli {

namespace {

namespace DEM = CGAL::Density_equalizing_maps;
typedef CGAL::Simple_cartesian<double>::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Globe;

struct Cartogram_options
{
  std::string regions, values, id_property, value_column, sea = "mean";
  std::string output_geojson, output, image, metrics;
  std::size_t vertices = 50000, passes = 8;
  std::optional<double> time_step, tolerance;
  std::optional<std::size_t> max_iterations;
  double area_tolerance = 0.01;
  bool quiet = false, single_level = false;
};

const char* cartogram_usage =
  "usage: dem cartogram REGIONS.geojson --values VALUES.csv --id-property NAME [options]\n"
  "  REGIONS.geojson          FeatureCollection of Polygon / MultiPolygon features (RFC 7946)\n"
  "  --values FILE            CSV with a header row: an identifier column (named NAME, else the first)\n"
  "                           and a value column\n"
  "  --id-property NAME       the feature property (or \"id\") identifying a region in the CSV\n"
  "  --value-column COL       the value column (default: the other column of a 2-column table)\n"
  "  --sea-density mean|D     population per steradian of the sea (default mean: the mean land density)\n"
  "  --vertices N             vertices of the globe mesh, an icosahedral geodesic sphere (default 50000;\n"
  "                           the nearest 10 f^2 + 2 with f = f0 2^k, f0 <= 20, is used: k midpoint\n"
  "                           subdivisions of a coarse globe, on which the passes run; see --single-level)\n"
  "  --single-level           the nearest 10 f^2 + 2 vertices, the passes and the correction on that globe\n"
  "                           alone (minutes instead of seconds on 100,000 faces)\n"
  "  --passes P               at most P density-equalizing passes (default 8; they stop at the\n"
  "                           first that does not halve the largest area error, and a\n"
  "                           region-area correction follows if the tolerance is not met)\n"
  "  --area-tolerance E       stop when every region covering >= 50 faces is within E (default 0.01)\n"
  "  --time-step DT --tolerance EPS --max-iterations N   SDEM options of each pass\n"
  "  --output-geojson FILE    the deformed regions (longitude/latitude on the deformed globe)\n"
  "  --output FILE.ply        the deformed globe, with a region index and a colour per face\n"
  "  --image FILE.svg|.png    two orthographic hemispheres, regions coloured by density, borders drawn\n"
  "  --metrics FILE           JSON: relative area errors (max, mean), per-region shares, too-small regions\n"
  "  --quiet                  no progress on stderr\n";

int usage_error(const std::string& m)
{
  std::cerr << "dem cartogram: " << m << "\n(dem cartogram --help prints the usage)\n";
  return 2;
}

bool parse_number(const std::string& s, double& v)
{
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size() && std::isfinite(v);
}

int parse(const std::vector<std::string>& args, Cartogram_options& o)
{
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if(a == "--help" || a == "-h") { std::cout << cartogram_usage; return 0; }
    if(a == "--quiet") { o.quiet = true; continue; }
    if(a == "--single-level") { o.single_level = true; continue; }
    if(a.size() > 1 && a[0] == '-' && a[1] == '-') {
      if(i + 1 >= args.size()) return usage_error("option " + a + " needs a value");
      const std::string& v = args[++i];
      double x = 0;
      auto count = [&](std::size_t& n) {
        if(!parse_number(v, x) || x < 1 || x != std::floor(x)) return false;
        n = std::size_t(x);
        return true;
      };
      std::size_t n = 0;
      if(a == "--values") o.values = v;
      else if(a == "--id-property") o.id_property = v;
      else if(a == "--value-column") o.value_column = v;
      else if(a == "--sea-density") o.sea = v;
      else if(a == "--output-geojson") o.output_geojson = v;
      else if(a == "--output") o.output = v;
      else if(a == "--image") o.image = v;
      else if(a == "--metrics") o.metrics = v;
      else if(a == "--vertices") { if(!count(o.vertices)) return usage_error("--vertices: \"" + v + "\" is not a positive integer"); }
      else if(a == "--passes") { if(!count(o.passes)) return usage_error("--passes: \"" + v + "\" is not a positive integer"); }
      else if(a == "--max-iterations") { if(!count(n)) return usage_error("--max-iterations: \"" + v + "\" is not a positive integer"); o.max_iterations = n; }
      else if(a == "--time-step" || a == "--tolerance" || a == "--area-tolerance") {
        if(!parse_number(v, x) || !(x > 0)) return usage_error(a + ": \"" + v + "\" is not a positive number");
        if(a == "--time-step") o.time_step = x;
        else if(a == "--tolerance") o.tolerance = x;
        else o.area_tolerance = x;
      } else return usage_error("unknown option " + a);
    } else if(o.regions.empty()) o.regions = a;
    else return usage_error("unexpected argument " + a);
  }
  if(o.regions.empty()) return usage_error("no REGIONS.geojson given");
  if(o.values.empty()) return usage_error("--values VALUES.csv is required");
  if(o.id_property.empty()) return usage_error("--id-property NAME is required");
  if(o.vertices < 12) return usage_error("--vertices must be at least 12");
  if(o.sea != "mean") {
    double x = 0;
    if(!parse_number(o.sea, x) || !(x > 0)) return usage_error("--sea-density: \"" + o.sea + "\" is neither mean nor a positive number");
  }
  return -1;
}

/// The colour of a density ratio (region density / mean land density), log viridis over [1/100, 100].
DEM::IO::Rgb density_color(double ratio)
{
  DEM::IO::Color_range r;
  r.low = 1e-2;
  r.high = 1e2;
  r.logarithmic = true;
  return DEM::IO::viridis(r.parameter(std::max(ratio, 1e-300)));
}

bool write_image(const std::string& path, const DEM::IO::Globe_picture& pic, std::string& error)
{
  if(lower_extension(path) == "svg") {
    DEM::IO::write_globe_SVG(path, pic);
    return true;
  }
  const std::string svg = path + ".svg";
  DEM::IO::write_globe_SVG(svg, pic);
  const std::string command = "rsvg-convert -o '" + path + "' '" + svg + "'";
  const int status = std::system(command.c_str());
  std::error_code ec;
  fs::remove(svg, ec);
  if(status != 0) { error = "rsvg-convert failed (status " + std::to_string(status) + "); is librsvg2-bin installed?"; return false; }
  return true;
}

int cartogram_command(const std::vector<std::string>& args)
{
  Cartogram_options o;
  if(const int s = parse(args, o); s >= 0) return s;
  const std::vector<std::string> inputs = {o.regions, o.values};
  struct Out { const char* option; std::string path; std::vector<std::string> ext; };
  const std::vector<Out> outs = {{"--output-geojson", o.output_geojson, {"geojson", "json"}},
                                 {"--output", o.output, {"ply"}},
                                 {"--image", o.image, {"svg", "png"}},
                                 {"--metrics", o.metrics, {"json"}}};
  for(const Out& out : outs) {
    if(out.path.empty()) continue;
    if(std::find(out.ext.begin(), out.ext.end(), lower_extension(out.path)) == out.ext.end()) {
      std::string list;
      for(const std::string& e : out.ext) list += (list.empty() ? "." : " or .") + e;
      return usage_error(std::string(out.option) + " " + out.path + ": the file must end in " + list);
    }
    if(const Output_problem p = output_path_problem(out.option, out.path, false, inputs)) {
      std::cerr << "dem cartogram: " << p.message << "\n";
      return p.status;
    }
  }
  auto remove_stale = [&]() { for(const Out& out : outs) remove_stale_output(out.path, inputs); };

  const auto t0 = std::chrono::steady_clock::now();
  std::optional<Stage_progress> stages;
  stages.emplace(o.quiet);
  DEM::IO::GeoJSON_regions geo;
  std::vector<double> values;
  Globe globe;
  DEM::Globe_cartogram_report rep;
  std::vector<DEM::Spherical_region> deformed;
  std::vector<Point> mapped;
  std::size_t snapped_vertices = 0, coarse_vertices = 0;
  try {
    stages->begin("reading " + o.regions);
    geo = DEM::IO::read_GeoJSON_regions(o.regions, o.id_property);
    const std::map<std::string, double> table = DEM::IO::read_CSV_values(o.values, o.id_property, o.value_column);
    for(std::size_t r = 0; r < geo.regions.size(); ++r) {
      const auto it = table.find(geo.regions[r].id);
      if(it == table.end())
        throw DEM::Invalid_input(o.regions + ": feature " + std::to_string(geo.feature[r]) + " (" + o.id_property +
                                 " \"" + geo.regions[r].id + "\"): no value for it in " + o.values);
      values.push_back(it->second);
    }
    stages->begin("globe mesh");
    if(o.single_level) {
      const int f = std::max(1, int(std::lround(std::sqrt(std::max(0., double(o.vertices) - 2) / 10))));
      const DEM::internal::Triangle_arrays t = DEM::internal::geodesic_sphere(f);
      DEM::internal::write_triangle_mesh(t.X, t.F, globe);
      // the globe's vertices next to a border onto it: no thin slivers for the exact overlaps
      snapped_vertices = DEM::snap_globe_to_region_borders(globe, geo.regions);
    } else {
      const DEM::Cartogram_globe g = DEM::make_cartogram_globe(globe, geo.regions, o.vertices);
      coarse_vertices = g.coarse_globe_vertices;
      snapped_vertices = g.snapped_vertices;
    }
    stages->begin("cartogram (population, density-equalizing passes, region-area correction)", o.tolerance.value_or(1e-3));
    auto out_map = globe.add_property_map<Globe::Vertex_index, Point>("v:cartogram").first;
    Stage_progress* sp = &*stages;
    const bool quiet = o.quiet;
    auto progress = [sp](std::size_t k, double e) { return sp->iteration(k, e); };
    auto pass_report = [quiet](std::size_t pass, double err) {
      if(!quiet) std::cerr << "\ndem: cartogram pass " << pass << ": largest relative area error " << err << std::endl;
    };
    auto base = DEM::parameters::relative_area_tolerance(o.area_tolerance);
    auto np = DEM::parameters::combine(
      base, DEM::parameters::coarse_globe_vertices(coarse_vertices),
      DEM::parameters::number_of_passes(o.passes), DEM::parameters::pass_callback(pass_report),
      DEM::parameters::progress_callback(progress), DEM::parameters::time_step(o.time_step.value_or(0.1)),
      DEM::parameters::stopping_tolerance(o.tolerance.value_or(1e-3)),
      DEM::parameters::number_of_iterations((unsigned int)(o.max_iterations.value_or(200))),
      DEM::parameters::concurrency_tag(CGAL::Parallel_if_available_tag()));
    if(o.sea == "mean") rep = DEM::globe_cartogram(globe, geo.regions, values, out_map, np);
    else {
      double d = 0;
      parse_number(o.sea, d);
      rep = DEM::globe_cartogram(globe, geo.regions, values, out_map,
                                 DEM::parameters::combine(np, DEM::parameters::sea_density(d)));
    }
    if(rep.fold_overs > 0) {
      stages.reset();
      std::cerr << "dem: the cartogram map has " << rep.fold_overs << " fold-over(s) (exact count); nothing written\n";
      remove_stale();
      return 4;
    }
    stages->begin("region boundaries through the map");
    deformed = DEM::push_forward_region_boundaries(globe, out_map, geo.regions);
    for(auto v : globe.vertices()) mapped.push_back(out_map[v]);
    stages->end();
  } catch(const DEM::Invalid_input& e) {
    stages.reset();
    std::cerr << "dem: invalid input: " << e.what() << "\n";
    remove_stale();
    return 3;
  } catch(const std::bad_alloc&) {
    stages.reset();
    std::cerr << "dem: out of memory\n";
    remove_stale();
    return 4;
  } catch(const std::exception& e) {
    stages.reset();
    std::cerr << "dem: cartogram failed: " << e.what() << "\n";
    remove_stale();
    return 4;
  }

  // per face: the region of largest share (-1 for the sea) and its colour
  const DEM::Region_populations& pop = rep.populations;
  const std::size_t nf = pop.face_parts.size();
  std::vector<long> label(nf, -1);
  std::vector<DEM::IO::Rgb> color(nf, DEM::IO::Globe_picture().background); // the sea
  for(std::size_t k = 0; k < nf; ++k) {
    double best = 0, covered = 0;
    for(const auto& p : pop.face_parts[k]) {
      covered += p.second;
      if(p.second > best) { best = p.second; label[k] = long(p.first); }
    }
    if(1 - covered > best) label[k] = -1;
    if(label[k] >= 0) {
      const std::size_t r = std::size_t(label[k]);
      color[k] = density_color(pop.region_area[r] > 0 ? values[r] / pop.region_area[r] / pop.mean_land_density : 0);
    }
  }
  Eigen::Matrix<double, Eigen::Dynamic, 3> Y(Eigen::Index(mapped.size()), 3);
  for(std::size_t i = 0; i < mapped.size(); ++i) Y.row(Eigen::Index(i)) << mapped[i].x(), mapped[i].y(), mapped[i].z();
  Eigen::Matrix<int, Eigen::Dynamic, 3> F(Eigen::Index(nf), 3);
  {
    Eigen::Index k = 0;
    for(auto f : globe.faces()) {
      int c = 0;
      for(auto v : vertices_around_face(globe.halfedge(f), globe)) F(k, c++) = int(v.idx());
      ++k;
    }
  }
  const double seconds_before_writing = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  nlohmann::json m;
  m["method"] = "cartogram";
  m["vertices"] = globe.number_of_vertices();
  m["faces"] = nf;
  m["vertices_snapped_to_borders"] = snapped_vertices;
  nlohmann::json coarse = nlohmann::json::array();
  for(const auto& c : rep.coarse_globes)
    coarse.push_back({{"vertices", c.vertices}, {"correction_iterations", c.correction_iterations},
                      {"max_relative_area_error_on_mesh", c.max_relative_error_on_mesh}});
  m["coarse_globes"] = coarse;
  if(!rep.coarse_globe_message.empty()) m["coarse_globe_message"] = rep.coarse_globe_message;
  m["regions"] = geo.regions.size();
  m["passes"] = rep.passes;
  m["max_error_after_pass"] = rep.max_error_after_pass;
  m["max_relative_area_error_before_correction"] = rep.max_error_before_correction;
  m["correction_iterations"] = rep.correction_iterations;
  if(!rep.correction_message.empty()) m["correction_message"] = rep.correction_message;
  m["converged"] = rep.converged;
  m["area_tolerance"] = o.area_tolerance;
  m["fold_overs"] = rep.fold_overs;
  m["max_relative_area_error"] = rep.max_relative_error;
  m["mean_relative_area_error"] = rep.mean_relative_error;
  m["max_relative_area_error_on_mesh"] = rep.max_relative_error_on_mesh;
  m["minimum_faces"] = rep.minimum_faces;
  m["sea_area_share"] = rep.sea_area_share;
  m["sea_target_share"] = rep.sea_target_share;
  m["sea_density"] = pop.sea_density;
  m["mean_land_density"] = pop.mean_land_density;
  m["input_overlap_area"] = pop.overlapping_area;
  m["sampled_overlaps"] = pop.sampled_overlaps;
  m["last_pass_iterations"] = rep.last_pass.iterations;
  m["last_pass_termination"] = rep.last_pass.termination == DEM::Termination::CONVERGED ? "converged" : "not converged";
  nlohmann::json too_small = nlohmann::json::array(), per = nlohmann::json::array();
  for(std::size_t r : rep.too_small) too_small.push_back(geo.regions[r].id);
  m["regions_too_small"] = too_small;
  std::vector<nlohmann::json> props = geo.properties;
  for(std::size_t r = 0; r < geo.regions.size(); ++r) {
    nlohmann::json e;
    e["id"] = geo.regions[r].id;
    e["value"] = values[r];
    e["value_share"] = rep.value_share[r];
    e["area_share"] = rep.area_share[r];
    e["relative_error"] = rep.relative_error[r];
    e["faces"] = rep.faces_covered[r];
    per.push_back(e);
    props[r]["cartogram_value"] = values[r];
    props[r]["cartogram_value_share"] = rep.value_share[r];
    props[r]["cartogram_area_share"] = rep.area_share[r];
    props[r]["cartogram_relative_error"] = rep.relative_error[r];
  }
  m["per_region"] = per;

  try {
    stages->begin("writing");
    if(!o.output_geojson.empty())
      write_output_atomically(o.output_geojson, [&](const std::string& f) {
        DEM::IO::write_GeoJSON_regions(f, deformed, props, o.id_property);
      });
    if(!o.output.empty())
      write_output_atomically(o.output, [&](const std::string& f) {
        DEM::IO::write_PLY_with_face_labels(f, Y, F, label, color);
      });
    if(!o.image.empty()) {
      DEM::IO::Globe_picture pic;
      pic.positions = Y;
      pic.triangles = F;
      pic.face_color = color;
      pic.borders = deformed;
      char caption[200];
      std::snprintf(caption, sizeof caption, "area = value (%zu regions; largest relative area error %.2f %%); colour: "
                    "value per area before the map, log scale 1/100 .. 100 x the mean", geo.regions.size(),
                    100 * rep.max_relative_error);
      pic.caption = caption;
      std::string error;
      write_output_atomically(o.image, [&](const std::string& f) {
        if(!write_image(f, pic, error)) throw DEM::Invalid_input(error);
      });
    }
    m["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    m["seconds_before_writing"] = seconds_before_writing;
    if(!o.metrics.empty())
      write_output_atomically(o.metrics, [&](const std::string& f) {
        std::ofstream out(f);
        out << m.dump(2) << "\n";
        if(!out) throw DEM::Invalid_input("write error");
      });
    stages.reset();
  } catch(const std::exception& e) {
    stages.reset();
    std::cerr << "dem: " << e.what() << "\n";
    remove_stale();
    return 3;
  }
  std::cout << "cartogram: " << geo.regions.size() << " regions, " << nf << " faces, " << rep.passes
            << " passes, " << rep.correction_iterations << " correction iterations, max relative area error "
            << rep.max_relative_error << ", mean " << rep.mean_relative_error
            << " (" << rep.too_small.size() << " regions too small), " << rep.coarse_globes.size()
            << " coarse globe(s), " << snapped_vertices
            << " vertices snapped to the borders, " << pop.sampled_overlaps << " overlaps sampled, fold-overs "
            << rep.fold_overs << ", "
            << m["seconds"].get<double>() << " s" << std::endl;
  if(!rep.converged)
    std::cerr << "dem: note: the area tolerance " << o.area_tolerance << " was not reached in " << rep.passes
              << " passes and " << rep.correction_iterations << " correction iterations (largest relative error "
              << rep.max_relative_error << (rep.correction_message.empty() ? "" : "; " + rep.correction_message) << ")\n";
  return 0;
}

} // namespace

const Application cartogram_application = {
  "cartogram",
  "cartogram REGIONS.geojson --values VALUES.csv --id-property NAME [options] --output-geojson F --output F.ply --image F.svg|png --metrics F",
  cartogram_command};

} // namespace dem_cli
