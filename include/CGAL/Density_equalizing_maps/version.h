// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The version of the package. This header is the one place where the number is
// written: CMake reads it for project(VERSION), and the test `version_consistency`
// checks that package_info and the manual's Doxyfile state the same number.

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_VERSION_H
#define CGAL_DENSITY_EQUALIZING_MAPS_VERSION_H

/// \ingroup PkgDensityEqualizingMapsRef
/// Major version of the package; a change means an incompatible interface change.
#define CGAL_DEM_VERSION_MAJOR 1
/// \ingroup PkgDensityEqualizingMapsRef
/// Minor version of the package: compatible additions.
#define CGAL_DEM_VERSION_MINOR 0
/// \ingroup PkgDensityEqualizingMapsRef
/// Patch version of the package: fixes only.
#define CGAL_DEM_VERSION_PATCH 0

/// \cond SKIP_IN_MANUAL
#define CGAL_DEM_STRINGIZE_(x) #x
#define CGAL_DEM_STRINGIZE(x) CGAL_DEM_STRINGIZE_(x)
/// \endcond

/// \ingroup PkgDensityEqualizingMapsRef
/// The version as the string "MAJOR.MINOR.PATCH", spelled from the three numbers above.
#define CGAL_DEM_VERSION_STR                                                  \
  CGAL_DEM_STRINGIZE(CGAL_DEM_VERSION_MAJOR) "." CGAL_DEM_STRINGIZE(CGAL_DEM_VERSION_MINOR) \
  "." CGAL_DEM_STRINGIZE(CGAL_DEM_VERSION_PATCH)

/// \ingroup PkgDensityEqualizingMapsRef
/// The version as one comparable number, `MAJOR * 10000 + MINOR * 100 + PATCH`.
#define CGAL_DEM_VERSION_NR \
  (CGAL_DEM_VERSION_MAJOR * 10000 + CGAL_DEM_VERSION_MINOR * 100 + CGAL_DEM_VERSION_PATCH)

#endif // CGAL_DENSITY_EQUALIZING_MAPS_VERSION_H
