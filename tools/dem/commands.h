// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The subcommands of `dem`. Each family lives in its own file and takes the
// arguments after the program name; it returns the exit status (DESIGN.md:
// 0 done, 2 usage error, 3 invalid input, 4 no fold-over-free map).

#ifndef DEM_TOOL_COMMANDS_H
#define DEM_TOOL_COMMANDS_H

#include <string>
#include <vector>

namespace dem_cli {

/// `dem METHOD INPUT [options]` (map_command.cpp).
int map_command(const std::vector<std::string>& args);

/// An application subcommand: `dem NAME ...` (one file each).
struct Application
{
  const char* name;
  const char* synopsis;  // one line for `dem --help`
  int (*run)(const std::vector<std::string>& args); // args after NAME
};

/// `dem remesh ...` (remesh.cpp).
extern const Application remesh_application;

#ifdef DEM_HAVE_CARTOGRAM
/// `dem cartogram ...` (cartogram_command.cpp; needs nlohmann-json).
extern const Application cartogram_application;
#endif
/// `dem register ...` (register_command.cpp).
extern const Application register_application;

/// The applications built into this `dem` (main.cpp).
const std::vector<Application>& applications();

} // namespace dem_cli

#endif // DEM_TOOL_COMMANDS_H
