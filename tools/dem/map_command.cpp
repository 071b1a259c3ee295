// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem METHOD INPUT [options]`: map a mesh with one of the nine methods,
// print the summary, write the metrics and the mapped mesh (DESIGN.md).
//
// Exit status: 0 done; 2 usage error (also an unsupported output format or an
// output that is an input); 3 invalid input (also an output folder that is
// missing or not writable); 4 the method failed on a valid input: fold-overs
// left, a stall, or a numerical failure (Algorithm_failure); the message says
// which. On 4 the metrics are still written, the output mesh is not. On 3 and
// 4 an output file of an earlier run is deleted (output_files.h).
//
// Formats (dem_formats.h) are decided before the work: an unknown output
// extension is a usage error (2), an unreadable input format invalid input (3).
// Stages that last more than a second are named on stderr (dem_stages.h).
//
// The input is read as a polygon soup and validated on index arrays before a
// halfedge structure is built, so that non-manifold edges or open boundaries,
// which a Surface_mesh cannot even store, are reported as invalid input.

#include "commands.h"
#include "maps.h"
#include "metrics.h"
#include "dem_formats.h"
#include "output_files.h"

#include <CGAL/Density_equalizing_maps/parameters.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace dem_cli {

namespace NP = CGAL::Density_equalizing_maps::parameters;

namespace {

/// What went wrong in a run that returned a map, as it is: fold-overs left
/// (exact count), or a stall with a fold-over-free but unconverged map.
std::string failure_description(const DEM::Map_report& r)
{
  if(r.fold_overs > 0)
    return "the map has " + std::to_string(r.fold_overs) + " fold-over(s) (exact count; " +
           DEM::to_string(r.termination) + ", " + std::to_string(r.iterations) + " iteration(s))";
  if(r.landmarks_given_up)
    return "no landmark-aligned map without fold-overs was found; the fallback gives up the landmarks (" +
           r.fallback + ")";
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "stalled after %zu iteration(s): no fold-over-free step could be found; the returned map has no "
                "fold-over but did not converge (final error %.3g)",
                r.iterations, r.final_error);
  return buffer;
}

} // namespace

Metrics map_metrics(const Problem& pb, const Options& opt, const Run& run)
{
  Metric_input mi;
  mi.X = &pb.X; mi.F = &pb.F; mi.Y = &run.Y;
  mi.initial = run.Y0.size() ? &run.Y0 : &pb.X;
  mi.population = &pb.population;
  mi.radii_count = domain_of(opt.method) == Domain::TORUS ? 2 : 3;
  std::vector<Eigen::Index> landmark_index;
  DI::Matrix targets;
  if(!pb.landmarks.empty()) {
    targets = landmark_targets(pb.landmarks, landmark_index);
    mi.landmark_index = &landmark_index;
    mi.landmark_targets = &targets;
  }
  Metrics m = compute_metrics(method_name(opt.method), run.report, run.seconds, mi);
  m.cpu_seconds = run.cpu_seconds;
  return m;
}

int map_command(const std::vector<std::string>& args)
{
  Options opt;
  {
    std::string error;
    const Parse_status s = parse_command_line(args, opt, error);
    if(s == Parse_status::HELP) { std::cout << (opt.method_help ? method_help_text(opt.method) : usage_text()); return 0; }
    if(s == Parse_status::VERSION) { std::cout << version_text() << std::endl; return 0; }
    if(s == Parse_status::ERROR) {
      std::cerr << "dem: " << error << "\n(dem --help prints the usage)\n";
      return 2;
    }
  }
  // Every file format is decided before any computation.
  Output_kind output_format = Output_kind::POSITIONS, colored_format = Output_kind::PLY;
  try {
    if(!opt.output_format.empty() && opt.output.empty()) throw Format_usage_error("--output-format needs --output FILE");
    if(!opt.output.empty()) output_format = output_kind(opt.output, opt.output_format);
    if(!opt.output_input_colored.empty()) colored_format = colored_output_kind(opt.output_input_colored);
    if(output_format == Output_kind::OBJ && domain_of(opt.method) == Domain::ELLIPSOID && opt.output_scale)
      throw Format_usage_error("--output-scale with an OBJ output of an ellipsoidal map is not supported");
  } catch(const Format_usage_error& e) {
    std::cerr << "dem: " << e.what() << "\n";
    return 2;
  }

  Stage_progress stages(opt.quiet);
  set_stage_progress(&stages);
  struct Unset { ~Unset() { set_stage_progress(nullptr); } } unset;
  // The files this run reads: no output may be one of them, and a stale
  // output is never deleted if it is one of them.
  std::vector<std::string> inputs = {opt.input, opt.landmarks, opt.cut_edges};
  if(opt.population != "area") inputs.push_back(opt.population);
  inputs.push_back(opt.vertex_population);
  if(!opt.output.empty() && (opt.output == opt.metrics || same_file(opt.output, opt.metrics))) {
    std::cerr << "dem: --output and --metrics name the same file " << opt.output << "\n";
    return 2;
  }
  for(const Output_problem& p : {output_path_problem("--output", opt.output, false, inputs),
                                 output_path_problem("--output-input-colored", opt.output_input_colored, false, inputs),
                                 output_path_problem("--metrics", opt.metrics, false, inputs)})
    if(p) {
      std::cerr << "dem: " << p.message << "\n";
      return p.status;
    }
  // On a failure, an output left by an earlier run must not look like this
  // run's result: it is deleted (the metrics too unless this run writes them).
  auto fail = [&](int status, bool metrics_written) {
    std::string deleted;
    if(remove_stale_output(opt.output, inputs)) deleted += " " + opt.output;
    if(remove_stale_output(opt.output_input_colored, inputs)) deleted += " " + opt.output_input_colored;
    if(!metrics_written && remove_stale_output(opt.metrics, inputs)) deleted += " " + opt.metrics;
    if(!deleted.empty()) std::cerr << "dem: deleted the output of an earlier run:" << deleted << "\n";
    return status;
  };

  Problem pb;
  Run run;
  try {
    input_kind(opt.input); // an unreadable format is reported before the mesh is parsed
    stages.begin("reading and validating " + opt.input);
    read_mesh(opt, pb);
    read_sidecars(opt, pb);
    stages.begin(std::string("mapping (") + method_name(opt.method) + ")",
                 opt.tolerance.value_or(method_defaults(opt.method).tolerance));
    run = run_map(pb, opt);
    stages.begin("metrics");
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: invalid input: " << e.what() << "\n";
    return fail(3, false);
  } catch(const DEM::Algorithm_failure& e) {
    std::cerr << "dem: " << method_name(opt.method) << " failed (the input is valid): " << e.what() << "\n";
    return fail(4, false);
  } catch(const std::bad_alloc&) {
    std::cerr << "dem: out of memory\n";
    return fail(4, false);
  } catch(const std::exception& e) {
    std::cerr << "dem: " << method_name(opt.method) << " failed: " << e.what() << "\n";
    return fail(4, false);
  }
  for(const std::string& n : run.notes) std::cerr << "dem: " << n << "\n";

  Metrics m = map_metrics(pb, opt, run);

  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return fail(3, false);
  }
  std::cout << summary_line(m) << std::endl;

  // a landmark map whose fallback gave up the landmarks is not the map asked for
  const bool failed = run.report.fold_overs > 0 || run.report.termination == DEM::Termination::STALLED ||
                      run.report.landmarks_given_up;
  // a result the user must not take for the method's usual one says so on stderr
  if(!run.report.fallback.empty())
    std::cerr << "dem: warning: " << method_name(opt.method) << " used a fallback: " << run.report.fallback
              << " (" << run.report.repairs << " repairs)\n";
  if(!failed && !run.report.converged())
    std::cerr << "dem: warning: " << method_name(opt.method) << " did not converge ("
              << DEM::to_string(run.report.termination) << ", stopping quantity " << run.report.initial_error << " -> "
              << run.report.final_error << ")" << (run.report.message.empty() ? "" : ": " + run.report.message)
              << "; the output is a bijective map (SDEM, EDEM, TDEM: the most uniform one of the run)\n";
  if(failed) {
    std::cerr << "dem: " << method_name(opt.method) << " failed: " << failure_description(run.report)
              << (run.report.message.empty() ? "" : " (" + run.report.message + ")") << "; "
              << (opt.output.empty() ? "" : "nothing written to " + opt.output + ", ")
              << (opt.metrics.empty() ? "no metrics requested" : "metrics written to " + opt.metrics) << "\n";
    return fail(4, true);
  }
  if(opt.output.empty() && opt.output_input_colored.empty()) return 0;
  try {
    const double scale = opt.output_scale.value_or(1.);
    Point_map out = fresh_point_map(pb.mesh, "v:dem_output");
    for(Vertex v : pb.mesh.vertices())
      out[v] = Point_3(scale * run.Y(v.idx(), 0), scale * run.Y(v.idx(), 1), scale * run.Y(v.idx(), 2));
    const DIO::Color_by by = DIO::color_by_from_name(opt.color_by);
    DIO::Face_data data;
    const bool colored = output_format == Output_kind::PLY || output_format == Output_kind::VTK ||
                         output_format == Output_kind::VTP || !opt.output_input_colored.empty();
    if(colored) data = DIO::face_data(pb.mesh, out, NP::face_population_map(pb.population_map));
    if(!opt.output.empty()) {
      stages.begin("writing " + opt.output);
      Texture_domain<Mesh> domain;
      if(domain_of(opt.method) == Domain::SPHERE) domain.radii = {{scale, scale, scale}};
      if(domain_of(opt.method) == Domain::ELLIPSOID && run.report.radii.size() == 3)
        domain = Texture_domain<Mesh>{Texture_domain<Mesh>::ELLIPSOID, {{run.report.radii[0], run.report.radii[1], run.report.radii[2]}}};
      if(domain_of(opt.method) == Domain::TORUS) {
        domain.kind = Texture_domain<Mesh>::TORUS;
        domain.R = (*opt.torus)[0];
        domain.r = (*opt.torus)[1];
        domain.flat = pb.mesh.property_map<Vertex, CGAL::Simple_cartesian<double>::Point_2>("v:dem_flat").first;
        domain.offsets = pb.mesh.property_map<Mesh::Halfedge_index, std::array<int, 2> >("h:dem_offset").first;
      }
      write_output_atomically(opt.output, [&](const std::string& f) {
        write_mapped_mesh(output_format, f, pb.mesh, out, data, by, domain);
      });
    }
    if(!opt.output_input_colored.empty()) {
      stages.begin("writing " + opt.output_input_colored);
      write_output_atomically(opt.output_input_colored, [&](const std::string& f) {
        write_mapped_mesh(colored_format, f, pb.mesh, pb.mesh.points(), data, by, Texture_domain<Mesh>());
      });
    }
    stages.end();
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: cannot write the output: " << e.what() << "\n";
    return fail(3, true);
  }
  return 0;
}

} // namespace dem_cli
