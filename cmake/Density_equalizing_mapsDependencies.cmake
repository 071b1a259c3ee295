# The optional dependency of Density_equalizing_maps, found the same way by the
# build (CMakeLists.txt) and by the installed package configuration
# (Density_equalizing_mapsConfig.cmake), so that a consumer finds it on its own
# machine: nothing of the build machine's paths is recorded in the package.
#
#   dem_find_cholmod()
# defines the imported target Density_equalizing_maps::CHOLMOD and sets
# DEM_CHOLMOD_FOUND when SuiteSparse CHOLMOD (header and library) is found. The
# target carries the compile definition CGAL_DEM_USE_CHOLMOD, which makes the
# supernodal Cholesky factorization the package's default SPD solver, and, when
# the OpenMP runtime library is found, links it and defines
# CGAL_DEM_HAS_OPENMP_RUNTIME: CHOLMOD's supernodal factorization runs a fixed
# 4 OpenMP threads, and the package lets the runtime lower that to the free cores
# during its factorizations (omp_set_dynamic), which needs the runtime itself
# (only the library: the consumer's code is not compiled with -fopenmp).
# Cache entries CHOLMOD_INCLUDE_DIR and CHOLMOD_LIBRARY point to another copy.
function(dem_find_cholmod)
  if(TARGET Density_equalizing_maps::CHOLMOD)
    set(DEM_CHOLMOD_FOUND TRUE PARENT_SCOPE)
    return()
  endif()
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(CHOLMOD_LIBRARY cholmod)
  if(NOT CHOLMOD_INCLUDE_DIR OR NOT CHOLMOD_LIBRARY)
    set(DEM_CHOLMOD_FOUND FALSE PARENT_SCOPE)
    return()
  endif()
  # GLOBAL: the library target may be linked from any directory of a project that
  # adds this package with add_subdirectory().
  add_library(Density_equalizing_maps::CHOLMOD UNKNOWN IMPORTED GLOBAL)
  set_target_properties(Density_equalizing_maps::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS CGAL_DEM_USE_CHOLMOD)
  # dlsym: whether the BLAS under CHOLMOD may be called from two threads
  # (internal/bisection_cholesky.h); in libc itself from glibc 2.34 on
  if(CMAKE_DL_LIBS)
    set_property(TARGET Density_equalizing_maps::CHOLMOD APPEND PROPERTY INTERFACE_LINK_LIBRARIES ${CMAKE_DL_LIBS})
  endif()
  find_package(OpenMP COMPONENTS CXX QUIET)
  if(OpenMP_CXX_FOUND AND OpenMP_CXX_LIBRARIES)
    set_property(TARGET Density_equalizing_maps::CHOLMOD APPEND PROPERTY
      INTERFACE_LINK_LIBRARIES ${OpenMP_CXX_LIBRARIES})
    set_property(TARGET Density_equalizing_maps::CHOLMOD APPEND PROPERTY
      INTERFACE_COMPILE_DEFINITIONS CGAL_DEM_HAS_OPENMP_RUNTIME)
  endif()
  set(DEM_CHOLMOD_FOUND TRUE PARENT_SCOPE)
  message(STATUS "Density_equalizing_maps: using CHOLMOD from ${CHOLMOD_LIBRARY}")
endfunction()
