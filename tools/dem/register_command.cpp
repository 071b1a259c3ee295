// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem register SOURCE TARGET --landmark-pairs FILE [--via lsdem|ellipsoidal-quasiconformal]
//  [--alpha A --beta B --gamma G | --lambda L] [--time-step, --tolerance, --max-iterations]
//  --output FILE --metrics FILE` (issue 18): register_surfaces(). --output receives the
// source connectivity with every vertex at its corresponding target point. The metrics are
// the contract's keys for the registration map (source surface -> registered points:
// mean_abs_mu, mean_abs_darea, fold_overs = both maps' exact counts), landmark_error_3d
// {mean, max, relative_mean, relative_max} (relative = divided by the target's bounding-box
// diagonal), both underlying maps' full metrics under source_map and target_map, and on the
// sphere route landmark_correction (the landmark warps of the starting and the final maps:
// largest sphere distance to the common positions before and after, exact or not).

#include "commands.h"
#include "maps.h"
#include "metrics.h"

#include <CGAL/Density_equalizing_maps/IO/landmark_pairs.h>
#include <CGAL/Density_equalizing_maps/surface_registration.h>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace dem_cli {

namespace {

struct Register_arguments
{
  std::string source, target, pairs;
  Method via = Method::LSDEM;
  Options opt; // the map options (weights, steps, --output, --metrics, --quiet)
};

bool parse_register_arguments(const std::vector<std::string>& args, Register_arguments& r, std::string& error)
{
  std::vector<std::string> positional, rest;
  std::string via = "lsdem";
  for(std::size_t i = 0; i < args.size(); ++i) {
    if(args[i] == "--via" || args[i] == "--landmark-pairs") {
      if(i + 1 >= args.size()) { error = "option " + args[i] + " needs a value"; return false; }
      (args[i] == "--via" ? via : r.pairs) = args[i + 1];
      ++i;
    } else if(args[i].size() > 1 && args[i][0] == '-') {
      rest.push_back(args[i]);
      if(i + 1 < args.size() && args[i] != "--quiet" && args[i] != "-q") rest.push_back(args[++i]);
    } else {
      positional.push_back(args[i]);
    }
  }
  if(positional.size() != 2) { error = "register needs SOURCE and TARGET meshes"; return false; }
  r.source = positional[0];
  r.target = positional[1];
  if(r.pairs.empty()) { error = "register needs --landmark-pairs FILE"; return false; }
  if(via == "lsdem") r.via = Method::LSDEM;
  else if(via == "ellipsoidal-quasiconformal") r.via = Method::ELLIPSOIDAL_QUASICONFORMAL;
  else { error = "--via must be lsdem or ellipsoidal-quasiconformal (got \"" + via + "\")"; return false; }
  // the map options are those of the method; its --landmarks is satisfied by the pairs file
  // (not read as landmarks: the targets are computed)
  std::vector<std::string> map_args = {method_name(r.via), r.source, "--landmarks", r.pairs};
  map_args.insert(map_args.end(), rest.begin(), rest.end());
  if(parse_command_line(map_args, r.opt, error) == Parse_status::ERROR) return false;
  r.opt.landmarks.clear();
  return true;
}

void read_named(const std::string& role, const std::string& file, Options opt, Problem& pb)
{
  opt.input = file;
  try {
    read_mesh(opt, pb);
  } catch(const DEM::Invalid_input& e) {
    throw DEM::Invalid_input(role + " " + file + ": " + e.what());
  }
  pb.population = DI::face_areas(pb.X * DI::unit_scale(pb.X), pb.F);
}

DI::Matrix rows(const std::vector<std::array<double, 3>>& p)
{
  DI::Matrix Y(Eigen::Index(p.size()), 3);
  for(std::size_t i = 0; i < p.size(); ++i) Y.row(Eigen::Index(i)) << p[i][0], p[i][1], p[i][2];
  return Y;
}

/// The metrics of one underlying map, as `dem METHOD` reports them.
std::string underlying_map_json(Problem& pb, const Options& opt, const DEM::Map_report& report,
                                const std::vector<std::array<double, 3>>& image, const std::vector<Vertex>& landmarks,
                                const std::vector<std::array<double, 3>>& targets)
{
  Run run;
  run.report = report;
  run.Y = rows(image);
  run.seconds = Metrics::NA;
  pb.landmarks.clear();
  for(std::size_t k = 0; k < landmarks.size(); ++k)
    pb.landmarks.emplace_back(landmarks[k], Point_3(targets[k][0], targets[k][1], targets[k][2]));
  return metrics_json(map_metrics(pb, opt, run));
}

const char* register_usage()
{
  return "usage: dem register SOURCE TARGET --landmark-pairs FILE [--via lsdem|ellipsoidal-quasiconformal]\n"
         "                    [options] --output FILE --metrics FILE\n"
         "  a dense bijective correspondence SOURCE -> TARGET (two closed genus-0 meshes): both are mapped\n"
         "  onto the domain with their corresponding landmarks sent to common positions, then every source\n"
         "  vertex is carried to the target through the target's map (lsdem: a smooth warp of the sphere, kept\n"
         "  only if fold-free, puts the landmarks exactly at their common positions before and after LSDEM)\n"
         "  --landmark-pairs FILE  lines \"source_vertex target_vertex\" (0-based, '#' comments; at least 3)\n"
         "  --via M                lsdem (default, unit sphere) | ellipsoidal-quasiconformal (ellipsoid)\n"
         "  options of the map: --alpha --beta --gamma (lsdem; gamma default 20 here), --lambda (ellipsoidal-\n"
         "  quasiconformal), --time-step --tolerance --max-iterations, --quiet\n"
         "  --output FILE          the source connectivity with every vertex at its corresponding target point\n"
         "  --metrics FILE         landmark_error_3d, mean_abs_mu, mean_abs_darea, fold_overs, both maps' keys and\n"
         "                         (lsdem) landmark_correction: each warp's largest landmark distance before/after, exact\n"
         "exit status: 0 done, 2 usage, 3 invalid input (bad pairs, genus mismatch), 4 a map folded\n"
         "example:\n"
         "  dem register face_a.off face_b.off --landmark-pairs pairs.txt --output a_on_b.off --metrics m.json\n";
}

int register_command(const std::vector<std::string>& args)
{
  for(const std::string& a : args)
    if(a == "--help" || a == "-h") { std::cout << register_usage(); return 0; }
  Register_arguments ra;
  {
    std::string error;
    if(!parse_register_arguments(args, ra, error)) {
      std::cerr << "dem register: " << error << "\n(dem --help prints the usage)\n";
      return 2;
    }
  }
  const Options& opt = ra.opt;
  Problem src, tgt;
  DEM::Registration_report rep;
  DI::Matrix registered;
  std::vector<Vertex> ls, lt;
  double seconds = 0, cpu = 0;
  try {
    // both surfaces are read before any error is reported, so that a genus mismatch is named as such
    std::string source_error, target_error;
    try { read_named("source", ra.source, opt, src); } catch(const DEM::Invalid_input& e) { source_error = e.what(); }
    try { read_named("target", ra.target, opt, tgt); } catch(const DEM::Invalid_input& e) { target_error = e.what(); }
    const auto wrong_genus = [](const std::string& m) { return m.find("wrong topology") != std::string::npos; };
    if(source_error.empty() != target_error.empty() && wrong_genus(source_error + target_error))
      throw DEM::Invalid_input("genus mismatch: the " + std::string(source_error.empty() ? "source" : "target") +
                               " surface has genus 0 but " + source_error + target_error);
    if(!source_error.empty()) throw DEM::Invalid_input(source_error);
    if(!target_error.empty()) throw DEM::Invalid_input(target_error);
    const auto pairs = DEM::IO::read_landmark_pairs(ra.pairs, src.mesh.number_of_vertices(), tgt.mesh.number_of_vertices());
    std::vector<std::pair<Vertex, Vertex>> vp;
    for(const auto& p : pairs) {
      vp.emplace_back(Vertex(Mesh::size_type(p.first)), Vertex(Mesh::size_type(p.second)));
      ls.push_back(vp.back().first);
      lt.push_back(vp.back().second);
    }
    Point_map out = fresh_point_map(src.mesh, "v:dem_registered");
    const Method_defaults d = method_defaults(ra.via);
    const bool sphere = ra.via == Method::LSDEM;
    const Stopwatch watch;
    rep = DEM::register_surfaces(
      src.mesh, tgt.mesh, vp, out,
      DEM::parameters::combine(
        DEM::parameters::registration_domain(sphere ? DEM::Registration_domain::SPHERE : DEM::Registration_domain::ELLIPSOID),
        DEM::parameters::density_weight(opt.alpha.value_or(1.)), DEM::parameters::harmonic_weight(opt.beta.value_or(2.)),
        DEM::parameters::landmark_weight(sphere ? opt.gamma.value_or(20.) : opt.lambda.value_or(20.)),
        DEM::parameters::time_step(opt.time_step.value_or(d.time_step)),
        DEM::parameters::stopping_tolerance(opt.tolerance.value_or(d.tolerance)),
        CGAL::parameters::number_of_iterations(unsigned(opt.max_iterations.value_or(d.max_iterations))),
        DEM::parameters::concurrency_tag(CGAL::Parallel_if_available_tag())));
    watch.stop(seconds, cpu);
    registered = to_matrix(src.mesh, out);
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: invalid input: " << e.what() << "\nnothing written\n";
    return 3;
  } catch(const std::bad_alloc&) {
    std::cerr << "dem: out of memory\n";
    return 4;
  } catch(const std::exception& e) {
    std::cerr << "dem: register via " << method_name(ra.via) << " failed: " << e.what() << "\nnothing written\n";
    return 4;
  }

  Metric_input mi;
  mi.X = &src.X; mi.F = &src.F; mi.Y = &registered; mi.initial = &src.X; mi.population = &src.population;
  DEM::Map_report combined;
  combined.fold_overs = rep.source_map.fold_overs + rep.target_map.fold_overs;
  combined.termination = rep.source_map.converged() && rep.target_map.converged() ? DEM::Termination::CONVERGED
                                                                                  : DEM::Termination::MAXIMUM_ITERATIONS;
  Metrics m = compute_metrics("register", combined, seconds, mi);
  m.cpu_seconds = cpu;
  m.iterations = Metrics::NA;
  m.density_var_initial = m.density_var_final = m.face_density_var_initial = m.face_density_var_final = Metrics::NA;
  const double diag = rep.target_diagonal;
  m.add_json("via", json_string(method_name(ra.via)));
  m.add_json("landmark_error_3d", "{\"mean\": " + json_number(rep.landmark_error_mean) +
                                    ", \"max\": " + json_number(rep.landmark_error_max) +
                                    ", \"relative_mean\": " + json_number(rep.landmark_error_mean / diag) +
                                    ", \"relative_max\": " + json_number(rep.landmark_error_max / diag) + "}");
  m.add("target_bbox_diagonal", diag);
  if(ra.via == Method::LSDEM) {
    const auto correction = [](const DEM::Landmark_correction& c) {
      return "{\"error_before\": " + json_number(c.error_before) + ", \"error_after\": " + json_number(c.error_after) +
             ", \"exact\": " + (c.exact ? "true" : "false") + "}";
    };
    m.add_json("landmark_correction",
               "{\"source_start\": " + correction(rep.source_start_correction) + ", \"target_start\": " +
                 correction(rep.target_start_correction) + ", \"source_final\": " + correction(rep.source_correction) +
                 ", \"target_final\": " + correction(rep.target_correction) + "}");
  }
  Options map_opt = opt;
  map_opt.method = ra.via;
  m.add_json("source_map", underlying_map_json(src, map_opt, rep.source_map, rep.source_domain_points, ls, rep.landmark_positions));
  m.add_json("target_map", underlying_map_json(tgt, map_opt, rep.target_map, rep.target_domain_points, lt, rep.landmark_positions));
  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return 3;
  }
  std::cout << summary_line(m) << " | landmark error " << rep.landmark_error_max / diag
            << " of the target diagonal (max)" << std::endl;
  if(!opt.output.empty() && !write_output(opt.output, registered, src.F)) {
    std::cerr << "dem: cannot write " << opt.output << "\n";
    return 3;
  }
  return 0;
}

} // namespace

const Application register_application = {
  "register",
  "register SOURCE TARGET --landmark-pairs FILE [--via lsdem|ellipsoidal-quasiconformal] [options] --output FILE --metrics FILE",
  register_command};

} // namespace dem_cli
