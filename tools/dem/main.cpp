// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// dem: the command-line front end of the package (contract in DESIGN.md).
//
//   dem METHOD INPUT [options]       map a mesh (map_command.cpp)
//   dem APPLICATION ... [options]    an application built on the maps
//
// This file only dispatches on the first argument.

#include "cli.h"
#include "commands.h"

#include <CGAL/Density_equalizing_maps/internal/openblas.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace dem_cli {

const std::vector<Application>& applications()
{
  // Applications register here, one file each (remesh.cpp, ...).
  static const std::vector<Application> a = {remesh_application, register_application,
#ifdef DEM_HAVE_CARTOGRAM
                                             cartogram_application,
#endif
  };
  return a;
}

} // namespace dem_cli

int main(int argc, char** argv)
{
  using namespace dem_cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if(args.empty()) { std::cerr << usage_text(); return 2; }
  // --threads N, for every subcommand: at most N threads, those of the
  // parallel loops (the maps are the same on any number) and those of the
  // sparse factorizations (OpenBLAS's, CHOLMOD's OpenMP regions); by default
  // every core. The factorizations' pools are sized when their libraries are
  // loaded, so dem sets their variables and starts again.
  unsigned threads = 0;
  if(!take_threads_option(args, threads)) return 2;
  namespace DEMI = CGAL::Density_equalizing_maps::internal;
  const bool limited = DEMI::set_thread_limit_environment(threads);
  // OpenBLAS chose its kernels when it was loaded: an older build runs SSE3
  // kernels on a recent CPU it does not know (internal/openblas.h), and the
  // factorizations take about 1.5x as long. Unless OPENBLAS_CORETYPE is set,
  // dem then sets it to this CPU's kernels and starts again.
  DEMI::restart_with_openblas_kernels_of_this_cpu(argv, limited);
  DEMI::cap_sparse_solver_threads(threads); // holds if the new start failed
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> thread_limit;
  if(threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
#endif
  for(const Application& a : applications())
    if(args[0] == a.name) return a.run(std::vector<std::string>(args.begin() + 1, args.end()));
  return map_command(args);
}
