# The test `version_consistency`: every place that states the package version
# states the one of include/CGAL/Density_equalizing_maps/version.h.
#   cmake -DDEM_SOURCE_DIR=<repository> [-DDEM_CMAKE_VERSION=<project version>] -P cmake/check_version.cmake
include(${CMAKE_CURRENT_LIST_DIR}/Density_equalizing_maps_version.cmake)
dem_read_version("${DEM_SOURCE_DIR}/include/CGAL/Density_equalizing_maps/version.h" header_version)

function(expect what found)
  if(NOT found STREQUAL header_version)
    message(SEND_ERROR "${what} states version '${found}', version.h states '${header_version}'")
  else()
    message(STATUS "${what}: ${found}")
  endif()
endfunction()

if(DEFINED DEM_CMAKE_VERSION)
  expect("project(VERSION) of the build" "${DEM_CMAKE_VERSION}")
endif()

file(STRINGS "${DEM_SOURCE_DIR}/package_info/Density_equalizing_maps/version" info_version LIMIT_COUNT 1)
string(STRIP "${info_version}" info_version)
expect("package_info/Density_equalizing_maps/version" "${info_version}")

file(STRINGS "${DEM_SOURCE_DIR}/doc/Density_equalizing_maps/Doxyfile" number_line
     REGEX "^PROJECT_NUMBER *=")
string(REGEX REPLACE "^PROJECT_NUMBER *= *\"?([^\" ]*)\"? *$" "\\1" doc_version "${number_line}")
expect("PROJECT_NUMBER of doc/Density_equalizing_maps/Doxyfile" "${doc_version}")
