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
// The input is read as a polygon soup and validated on index arrays before a
// halfedge structure is built, so that non-manifold edges or open boundaries,
// which a Surface_mesh cannot even store, are reported as invalid input.

#include "commands.h"
#include "maps.h"
#include "metrics.h"
#include "output_files.h"

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace dem_cli {

namespace {

/// What went wrong in a run that returned a map, as it is: fold-overs left
/// (exact count), or a stall with a fold-over-free but unconverged map.
std::string failure_description(const DEM::Map_report& r)
{
  if(r.fold_overs > 0)
    return "the map has " + std::to_string(r.fold_overs) + " fold-over(s) (exact count; " +
           DEM::to_string(r.termination) + ", " + std::to_string(r.iterations) + " iteration(s))";
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "stalled after %zu iteration(s): no fold-over-free step could be found; the last map has no "
                "fold-over but did not converge (final error %.3g)",
                r.iterations, r.final_error);
  return buffer;
}

} // namespace

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
  // The files this run reads: no output may be one of them, and a stale
  // output is never deleted if it is one of them.
  std::vector<std::string> inputs = {opt.input, opt.landmarks, opt.cut_edges};
  if(opt.population != "area") inputs.push_back(opt.population);
  if(!opt.output.empty() && (opt.output == opt.metrics || same_file(opt.output, opt.metrics))) {
    std::cerr << "dem: --output and --metrics name the same file " << opt.output << "\n";
    return 2;
  }
  for(const Output_problem& p : {output_path_problem("--output", opt.output, true, inputs),
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
    if(!metrics_written && remove_stale_output(opt.metrics, inputs)) deleted += " " + opt.metrics;
    if(!deleted.empty()) std::cerr << "dem: deleted the output of an earlier run:" << deleted << "\n";
    return status;
  };

  Problem pb;
  Run run;
  try {
    read_mesh(opt, pb);
    read_sidecars(opt, pb);
    run = run_map(pb, opt);
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

  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return fail(3, false);
  }
  std::cout << summary_line(m) << std::endl;

  const bool failed = run.report.fold_overs > 0 || run.report.termination == DEM::Termination::STALLED;
  // a result the user must not take for the method's usual one says so on stderr
  if(!run.report.fallback.empty())
    std::cerr << "dem: warning: " << method_name(opt.method) << " used a fallback: " << run.report.fallback
              << " (" << run.report.repairs << " repairs)\n";
  if(!failed && !run.report.converged())
    std::cerr << "dem: warning: " << method_name(opt.method) << " did not converge ("
              << DEM::to_string(run.report.termination) << ", stopping quantity " << run.report.initial_error << " -> "
              << run.report.final_error << ")" << (run.report.message.empty() ? "" : ": " + run.report.message)
              << "; the output is the last bijective map\n";
  if(failed) {
    std::cerr << "dem: " << method_name(opt.method) << " failed: " << failure_description(run.report)
              << (run.report.message.empty() ? "" : " (" + run.report.message + ")") << "; "
              << (opt.output.empty() ? "" : "nothing written to " + opt.output + ", ")
              << (opt.metrics.empty() ? "no metrics requested" : "metrics written to " + opt.metrics) << "\n";
    return fail(4, true);
  }
  if(!opt.output.empty() && !write_output(opt.output, run.Y, pb.F)) {
    std::cerr << "dem: cannot write " << opt.output << "\n";
    return fail(3, true);
  }
  return 0;
}

} // namespace dem_cli
