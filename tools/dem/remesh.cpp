// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// `dem remesh INPUT --via METHOD --vertices N [METHOD's options] --output FILE --metrics FILE`
// (DESIGN.md): map INPUT with METHOD exactly as `dem METHOD` does, then pull a
// uniform mesh of the domain with N vertices back to INPUT
// (remesh_through_map). The metrics are the map's plus delta_size,
// delta_shape, remesh_vertices, remesh_faces and remesh_seconds (the
// remeshing alone, after the map); --output receives the remeshed surface.

#include "commands.h"
#include "maps.h"
#include "metrics.h"
#include "output_files.h"

#include <CGAL/Density_equalizing_maps/remeshing.h>

#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace dem_cli {

namespace {

/// Takes `--via M` and `--vertices N` out of the arguments; the rest is a map
/// command line `M INPUT [options]`.
bool split_remesh_arguments(const std::vector<std::string>& args, std::vector<std::string>& map_args,
                            std::size_t& vertices, std::string& torus_mesh, std::string& error)
{
  std::string via, count;
  std::vector<std::string> rest;
  for(std::size_t i = 0; i < args.size(); ++i) {
    if(args[i] == "--via" || args[i] == "--vertices" || args[i] == "--torus-mesh") {
      if(i + 1 >= args.size()) { error = "option " + args[i] + " needs a value"; return false; }
      std::string& target = args[i] == "--via" ? via : args[i] == "--vertices" ? count : torus_mesh;
      target = args[i + 1];
      ++i;
    } else {
      rest.push_back(args[i]);
    }
  }
  if(via.empty()) { error = "remesh needs --via METHOD"; return false; }
  if(count.empty()) { error = "remesh needs --vertices N"; return false; }
  try {
    std::size_t used = 0;
    const long long n = std::stoll(count, &used);
    if(used != count.size() || n <= 0) throw std::invalid_argument(count);
    vertices = std::size_t(n);
  } catch(const std::exception&) {
    error = "option --vertices: \"" + count + "\" is not a positive integer";
    return false;
  }
  if(!torus_mesh.empty() && torus_mesh != "lattice" && torus_mesh != "relaxed") {
    error = "option --torus-mesh: \"" + torus_mesh + "\" is neither lattice nor relaxed";
    return false;
  }
  map_args.assign(1, via);
  map_args.insert(map_args.end(), rest.begin(), rest.end());
  return true;
}

/// The domain of the map that `run` produced, with the radii it reports.
template <class F>
DEM::Remeshing_report remesh_on_domain(const Options& opt, const Run& run, F remesh)
{
  switch(domain_of(opt.method)) {
    case Domain::SPHERE: return remesh(DEM::Unit_sphere_domain());
    case Domain::ELLIPSOID: {
      const std::vector<double>& r = run.report.radii;
      if(r.size() != 3) throw std::logic_error("the ellipsoidal map reported no radii");
      return remesh(DEM::Ellipsoid_domain{r[0], r[1], r[2]});
    }
    case Domain::TORUS: return remesh(DEM::Torus_domain{(*opt.torus)[0], (*opt.torus)[1]});
  }
  throw std::logic_error("unknown domain");
}

DI::Index_matrix face_matrix(const Mesh& m)
{
  DI::Index_matrix F(Eigen::Index(m.number_of_faces()), 3);
  Eigen::Index k = 0;
  for(Face f : m.faces()) {
    int c = 0;
    for(Vertex v : vertices_around_face(m.halfedge(f), m)) F(k, c++) = int(v.idx());
    ++k;
  }
  return F;
}

const char* remesh_usage()
{
  return "usage: dem remesh INPUT --via METHOD --vertices N [METHOD's options] --output FILE --metrics FILE\n"
         "  map INPUT with METHOD (as `dem METHOD` does), triangulate its domain uniformly with about N\n"
         "  vertices and pull that triangulation back onto INPUT: a remeshed surface of the same genus,\n"
         "  every vertex on INPUT, triangles uniform in size where the map preserves area\n"
         "  --via METHOD     any map method: spherical-conformal, sdem, lsdem (genus 0, sphere);\n"
         "                   ellipsoidal-conformal, ellipsoidal-quasiconformal, edem, edeq (genus 0, ellipsoid);\n"
         "                   toroidal-parameterization, tdem (genus 1, torus; needs --torus R r)\n"
         "  --vertices N     vertex count of the domain mesh (N >= 12; within 1 % for N >= 100)\n"
         "  --population FILE  with sdem/lsdem/edem/edeq/tdem: denser triangles where the population is higher\n"
         "  --torus-mesh lattice|relaxed  torus methods only: the domain mesh; lattice (default): every vertex\n"
         "                   of valence 6, delta_shape about 0.07 at R/r = 3; relaxed: DistMesh with vertices of\n"
         "                   valence 5 and 7, delta_shape <= 0.05 and delta_size <= 0.7 (measured)\n"
         "  the METHOD's own options (dem METHOD --help), --output FILE (the remeshed surface, any mesh\n"
         "  format of --output), --metrics FILE (the map's keys plus delta_size, delta_shape,\n"
         "  remesh_vertices, remesh_faces, remesh_seconds), --quiet\n"
         "examples:\n"
         "  dem remesh bunny.off --via sdem --vertices 8500 --output bunny_uniform.off --metrics m.json\n"
         "  dem remesh ring.off --via toroidal-parameterization --torus 3 1 --vertices 4000 --output ring_grid.ply\n";
}

int remesh_command(const std::vector<std::string>& args)
{
  for(const std::string& a : args)
    if(a == "--help" || a == "-h") { std::cout << remesh_usage(); return 0; }
  Options opt;
  std::size_t vertices = 0;
  std::string torus_mesh;
  {
    std::vector<std::string> map_args;
    std::string error;
    if(!split_remesh_arguments(args, map_args, vertices, torus_mesh, error) ||
       parse_command_line(map_args, opt, error) == Parse_status::ERROR) {
      std::cerr << "dem remesh: " << error << "\n(dem --help prints the usage)\n";
      return 2;
    }
    if(!torus_mesh.empty() && domain_of(opt.method) != Domain::TORUS) {
      std::cerr << "dem remesh: option --torus-mesh applies to the torus methods only (not "
                << method_name(opt.method) << ")\n(dem --help prints the usage)\n";
      return 2;
    }
  }
  const bool torus_lattice = torus_mesh != "relaxed";
  if(vertices < 12) { // before the map: a refused request costs nothing
    std::cerr << "dem: invalid input: at least 12 vertices must be requested for a remeshed surface (got "
              << vertices << ")\n";
    return 3;
  }
  // the outputs are checked before the work (a mistyped folder costs nothing)
  const std::vector<std::string> inputs = {opt.input, opt.landmarks, opt.cut_edges, opt.population, opt.vertex_population};
  for(const Output_problem& p : {output_path_problem("--output", opt.output, true, inputs),
                                 output_path_problem("--metrics", opt.metrics, false, inputs)})
    if(p) {
      std::cerr << "dem: " << p.message << "\n";
      return p.status;
    }
  Stage_progress stages(opt.quiet);
  set_stage_progress(&stages);
  struct Unset { ~Unset() { set_stage_progress(nullptr); } } unset;
  Problem pb;
  Run run;
  Mesh remeshed;
  DEM::Remeshing_report remesh;
  double remesh_seconds = 0, remesh_cpu = 0;
  try {
    stages.begin("reading and validating " + opt.input);
    read_mesh(opt, pb);
    read_sidecars(opt, pb);
    stages.begin(std::string("mapping (") + method_name(opt.method) + ")",
                 opt.tolerance.value_or(method_defaults(opt.method).tolerance));
    run = run_map(pb, opt);
    for(const std::string& n : run.notes) std::cerr << "dem: " << n << "\n";
    if(run.report.fold_overs == 0 && run.report.termination != DEM::Termination::STALLED) {
      Point_map mapped = fresh_point_map(pb.mesh, "v:dem_remesh_map");
      for(Vertex v : pb.mesh.vertices())
        put(mapped, v, Point_3(run.Y(v.idx(), 0), run.Y(v.idx(), 1), run.Y(v.idx(), 2)));
      stages.begin("remeshing (uniform domain mesh pulled back through the map)");
      const Stopwatch watch;
      remesh = remesh_on_domain(opt, run, [&](const auto& domain) {
        return DEM::remesh_through_map(pb.mesh, mapped, domain, vertices, remeshed,
                                       DEM::parameters::combine(DEM::parameters::torus_lattice(torus_lattice),
                                                                DEM::parameters::concurrency_tag(CGAL::Parallel_if_available_tag())));
      });
      watch.stop(remesh_seconds, remesh_cpu);
    }
    stages.end();
  } catch(const DEM::Invalid_input& e) {
    std::cerr << "dem: invalid input: " << e.what() << "\n";
    return 3;
  } catch(const std::bad_alloc&) {
    std::cerr << "dem: out of memory\n";
    return 4;
  } catch(const std::exception& e) {
    std::cerr << "dem: remesh via " << method_name(opt.method) << " failed: " << e.what() << "\n";
    return 4;
  }

  Metrics m = map_metrics(pb, opt, run);
  const bool failed = run.report.fold_overs > 0 || run.report.termination == DEM::Termination::STALLED;
  m.add("delta_size", failed ? Metrics::NA : remesh.delta_size);
  m.add("delta_shape", failed ? Metrics::NA : remesh.delta_shape);
  m.add("remesh_vertices", failed ? Metrics::NA : double(remesh.vertices));
  m.add("remesh_faces", failed ? Metrics::NA : double(remesh.faces));
  m.add("remesh_seconds", failed ? Metrics::NA : remesh_seconds);
  m.add("domain_delta_size", failed ? Metrics::NA : remesh.domain_delta_size);
  m.add("domain_delta_shape", failed ? Metrics::NA : remesh.domain_delta_shape);
  if(!opt.metrics.empty() && !write_metrics_json(opt.metrics, m)) {
    std::cerr << "dem: cannot write " << opt.metrics << "\n";
    return 3;
  }
  std::cout << summary_line(m);
  if(!failed)
    std::cout << " | remeshed: " << remesh.vertices << " vertices, delta_size " << remesh.delta_size
              << ", delta_shape " << remesh.delta_shape << ", " << remesh_seconds << " s";
  std::cout << std::endl;
  if(failed) {
    std::cerr << "dem: " << method_name(opt.method) << " could not produce a fold-over-free map ("
              << run.report.fold_overs << " fold-over(s)); nothing remeshed"
              << (opt.output.empty() ? "" : ", nothing written to " + opt.output) << "\n";
    return 4;
  }
  if(!opt.output.empty()) stages.begin("writing " + opt.output);
  if(!opt.output.empty() && !write_output(opt.output, to_matrix(remeshed, remeshed.points()), face_matrix(remeshed))) {
    std::cerr << "dem: cannot write " << opt.output << "\n";
    return 3;
  }
  return 0;
}

} // namespace

const Application remesh_application = {
  "remesh",
  "remesh INPUT --via METHOD --vertices N [METHOD's options] --output FILE --metrics FILE",
  remesh_command};

} // namespace dem_cli
