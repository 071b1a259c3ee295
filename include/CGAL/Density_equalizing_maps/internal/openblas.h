// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H

// What the package needs to know of the BLAS under CHOLMOD's supernodal
// factorizations, where their dense work runs: whether it may be called from
// two threads at once, and whether OpenBLAS runs the kernels of this CPU.
//
// OpenBLAS built for several CPUs (DYNAMIC_ARCH, as Debian's) chooses its
// kernels once, when it is loaded, by the CPU's model, and falls back to its
// SSE3 kernels ("Prescott") for a model it does not know: OpenBLAS 0.3.21
// (Debian 12) does not know Intel's Sapphire and Emerald Rapids Xeons, whose
// AVX-512 units then sit idle (a numeric factorization of 1M faces takes about
// 1.5 times as long; benchmark/RESULTS.md). The environment variable
// OPENBLAS_CORETYPE names the kernels instead; it must be set before the
// library is loaded, so a program sets it and starts itself again
// (restart_with_openblas_kernels_of_this_cpu()).

#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
#include <dlfcn.h>
#include <unistd.h>
#endif

#include <cstdlib>
#include <cstring>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
/// A function of the OpenBLAS loaded in this process, null when the BLAS is another.
template <class Function>
Function openblas_function(const char* name)
{
  return reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, name));
}
#endif

/// The kernels the loaded OpenBLAS runs ("SkylakeX", "Haswell", "Prescott",
/// ...); empty when the BLAS is not OpenBLAS.
inline std::string openblas_core_name()
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
  typedef char* (*Name)();
  if(Name name = openblas_function<Name>("openblas_get_corename"))
    if(const char* text = name()) return text;
#endif
  return std::string();
}

/// Whether OpenBLAS's kernels `core` are of a CPU without AVX (those it
/// falls back to for a model it does not know).
inline bool openblas_core_without_avx(const std::string& core)
{
  for(const char* name : {"Prescott", "Core2", "Penryn", "Dunnington", "Nehalem", "Atom"})
    if(core == name) return true;
  return false;
}

/// The OpenBLAS kernels this CPU can run when the loaded OpenBLAS runs
/// kernels without AVX (it fell back for an unknown model) and the CPU has
/// AVX-512 ("SkylakeX") or AVX2 with FMA ("Haswell"); null otherwise.
inline const char* better_openblas_core_for_this_cpu()
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__) && (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
  if(!openblas_core_without_avx(openblas_core_name())) return nullptr;
  __builtin_cpu_init();
  if(__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
     __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd"))
    return "SkylakeX";
  if(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return nullptr;
}

/// For a program's main(): when the loaded OpenBLAS runs kernels older than
/// this CPU's and OPENBLAS_CORETYPE is not set, sets it and starts the program
/// again (execv of /proc/self/exe with the same arguments); returns only when
/// nothing was to be done or the new start failed. The computed results are
/// the same up to rounding (other kernels sum in another order).
inline void restart_with_openblas_kernels_of_this_cpu(char** argv)
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__linux__)
  if(std::getenv("OPENBLAS_CORETYPE")) return; // the user's choice, or already restarted
  const char* core = better_openblas_core_for_this_cpu();
  if(!core || setenv("OPENBLAS_CORETYPE", core, 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OPENBLAS_CORETYPE"); // the restart failed: go on with the kernels loaded
#else
  (void)argv;
#endif
}

/// Whether the BLAS may be called from two threads at once. OpenBLAS built
/// single-threaded without locking (Debian's libopenblas0-serial reports
/// "SINGLE_THREADED") shares its work buffers between calls: concurrent
/// CHOLMOD factorizations on it were seen to fail (benchmark/RESULTS.md). A
/// multithreaded OpenBLAS that already runs its kernels on several threads
/// would be oversubscribed. Other BLAS libraries keep no shared state.
inline bool blas_allows_two_concurrent_calls()
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
  static const bool allowed = [] {
    typedef char* (*Config)();
    typedef int (*Threads)();
    Config config = openblas_function<Config>("openblas_get_config");
    if(!config) return true;
    const char* text = config();
    if(!text || std::strstr(text, "SINGLE_THREADED")) return false;
    Threads threads = openblas_function<Threads>("openblas_get_num_threads");
    return threads && threads() == 1;
  }();
  return allowed;
#else
  return false;
#endif
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H
