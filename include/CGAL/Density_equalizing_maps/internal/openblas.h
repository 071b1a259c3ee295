// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H

// What the package needs to know of the BLAS under CHOLMOD's supernodal
// factorizations, where their dense work runs: whether it may be called from
// two threads at once, whether OpenBLAS runs the kernels of this CPU, and how
// many threads the factorizations run besides the caller's.
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

#ifdef CGAL_DEM_HAS_OPENMP_RUNTIME
#include <omp.h>
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
/// again (execv of /proc/self/exe with the same arguments); also starts again
/// when `environment_changed` (the caller changed variables the libraries
/// read when they are loaded, set_thread_limit_environment()). Returns only
/// when nothing was to be done or the new start failed. The computed results
/// are the same up to rounding (other kernels sum in another order).
inline void restart_with_openblas_kernels_of_this_cpu(char** argv, bool environment_changed = false)
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__linux__)
  bool core_set = false;
  if(!std::getenv("OPENBLAS_CORETYPE")) { // else the user's choice, or already restarted
    const char* core = better_openblas_core_for_this_cpu();
    core_set = core && setenv("OPENBLAS_CORETYPE", core, 1) == 0;
  }
  if(!core_set && !environment_changed) return;
  execv("/proc/self/exe", argv);
  if(core_set) unsetenv("OPENBLAS_CORETYPE"); // the restart failed: go on with the kernels loaded
#else
  (void)argv;
  (void)environment_changed;
#endif
}

/// For a program's main() with a thread limit (`dem --threads N`), before
/// restart_with_openblas_kernels_of_this_cpu(): holds the two thread pools
/// of the sparse factorizations to at most `threads` (fewer than the cores)
/// from the moment their libraries are loaded: OPENBLAS_NUM_THREADS (a
/// multithreaded OpenBLAS starts one thread per core when it is loaded, and
/// they spin for about a tenth of a second before they sleep) and
/// OMP_THREAD_LIMIT (CHOLMOD's OpenMP regions). A smaller value the user set
/// is kept. Returns whether a variable changed: the program must then start
/// again for the limit to hold (cap_sparse_solver_threads() holds it in the
/// running process, but OpenBLAS's threads are already there).
inline bool set_thread_limit_environment(unsigned threads)
{
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
  if(threads == 0) return false;
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  if(long(threads) >= cores) return false; // every core: the pools' own sizes (OpenBLAS: one per core)
  const long limit = long(threads);
  bool changed = false;
  for(const char* name : {"OPENBLAS_NUM_THREADS", "OMP_THREAD_LIMIT"}) {
    const char* now = std::getenv(name);
    const long current = now ? std::strtol(now, nullptr, 10) : 0;
    if(current >= 1 && current <= limit) continue;
    changed = setenv(name, std::to_string(limit).c_str(), 1) == 0 || changed;
  }
  return changed;
#else
  (void)threads;
  return false;
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

/// For a program's thread limit (`dem --threads N`), in the running process:
/// at most `threads` threads in the sparse factorizations too. The package's
/// own loops take their number from TBB; the factorizations run on two other
/// pools: the threads of a multithreaded OpenBLAS (one per core unless
/// OPENBLAS_NUM_THREADS says otherwise), capped here at `threads`, and the
/// OpenMP regions of CHOLMOD's supernodal factorization (which ask for four
/// threads; Dynamic_openmp_threads lets the runtime give fewer), which with
/// `threads` = 1 run on the calling thread alone (no region is active).
/// Call it before any factorization: OpenBLAS's count is process-wide, and
/// blas_allows_two_concurrent_calls() reads it once. OpenBLAS's threads
/// started when it was loaded remain (set_thread_limit_environment() and a
/// new start avoid them). OpenBLAS splits the larger dense blocks between its
/// threads and adds their parts in another order, so the factors, and the
/// maps, differ in the last bits with its number of threads (not with the
/// number of the loops' threads).
inline void cap_sparse_solver_threads(unsigned threads)
{
  if(threads == 0) return;
#if defined(CGAL_DEM_USE_CHOLMOD) && defined(__unix__)
  typedef int (*Get)();
  typedef void (*Set)(int);
  Get get = openblas_function<Get>("openblas_get_num_threads");
  Set set = openblas_function<Set>("openblas_set_num_threads");
  if(get && set && get() > int(threads)) set(int(threads));
#endif
#ifdef CGAL_DEM_HAS_OPENMP_RUNTIME
  if(threads == 1) omp_set_max_active_levels(0);
#endif
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_OPENBLAS_H
