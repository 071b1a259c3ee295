// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem METHOD INPUT [options]`: map a mesh with one of the nine methods,
// print the summary, write the metrics and the mapped mesh (DESIGN.md).
//
// Exit status: 0 done; 2 usage error; 3 invalid input (message on stderr);
// 4 the algorithm could not produce a fold-over-free map (the metrics are
// still written, the output mesh is not).
//
// The input is read as a polygon soup and validated on index arrays before a
// halfedge structure is built, so that non-manifold edges or open boundaries,
// which a Surface_mesh cannot even store, are reported as invalid input.

#include "commands.h"
#include "maps.h"
#include "metrics.h"

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace dem_cli {

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
    if(s == Parse_status::HELP) { std::cout << usage_text(); return 0; }
    if(s == Parse_status::VERSION) { std::cout << version_text() << std::endl; return 0; }
    if(s == Parse_status::ERROR) {
      std::cerr << "dem: " << error << "\n(dem --help prints the usage)\n";
      return 2;
    }
  }
  Problem pb;
  Run run;
  try {
    read_mesh(opt, pb);
    read_sidecars(opt, pb);
    run = run_map(pb, opt);
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: invalid input: " << e.what() << "\n";
    return 3;
  } catch(const std::bad_alloc&) {
    std::cerr << "dem: out of memory\n";
    return 4;
  } catch(const std::exception& e) {
    std::cerr << "dem: " << method_name(opt.method) << " failed: " << e.what() << "\n";
    return 4;
  }
  for(const std::string& n : run.notes) std::cerr << "dem: " << n << "\n";

  Metrics m = map_metrics(pb, opt, run);

  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return 3;
  }
  std::cout << summary_line(m) << std::endl;

  const bool failed = run.report.fold_overs > 0 || run.report.termination == DEM::Termination::STALLED;
  if(failed) {
    std::cerr << "dem: " << method_name(opt.method) << " could not produce a fold-over-free map ("
              << run.report.fold_overs << " fold-over(s), " << DEM::to_string(run.report.termination) << ")"
              << (run.report.message.empty() ? "" : ": " + run.report.message) << "; "
              << (opt.output.empty() ? "" : "nothing written to " + opt.output + ", ")
              << (opt.metrics.empty() ? "no metrics requested" : "metrics written to " + opt.metrics) << "\n";
    return 4;
  }
  if(!opt.output.empty() && !write_output(opt.output, run.Y, pb.F)) {
    std::cerr << "dem: cannot write " << opt.output << "\n";
    return 3;
  }
  return 0;
}

} // namespace dem_cli
