// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Built by the parent project beside it: the library target gives the include
// path and the compile definitions (a light header keeps this build short).
#include <CGAL/Density_equalizing_maps/Map_report.h>
#include <CGAL/Density_equalizing_maps/version.h>
#include <iostream>

int main()
{
  CGAL::Density_equalizing_maps::Map_report report;
  std::cout << "Density_equalizing_maps " << CGAL_DEM_VERSION_STR
#ifdef CGAL_DEM_USE_CHOLMOD
            << " (CHOLMOD)"
#endif
            << ", fold-overs of an empty report: " << report.fold_overs << std::endl;
  return 0;
}
