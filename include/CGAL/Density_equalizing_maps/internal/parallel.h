// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PARALLEL_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PARALLEL_H

// Loops over faces and vertices that may run on several threads: with TBB
// (CGAL_LINKED_WITH_TBB) and when the caller of a map asked for it with the
// named parameter `concurrency_tag(CGAL::Parallel_tag())`.
//
// Their results do not depend on the number of threads, so that a map is the
// same to the last bit on one thread or on many:
// - parallel_for() gives every index to exactly one call of the body, which
//   writes only what belongs to its indices;
// - parallel_sum() adds fixed blocks of `parallel_block` consecutive terms in
//   index order and then the blocks' sums in block order, and the serial loop
//   does the very same, so the rounding is the same whoever adds what
//   (parallel_sums() does so for several sums in one pass).
//
// The choice is carried by a flag of the calling thread, set for the duration
// of a map by Concurrency_scope (the public functions open one from their
// named parameters), rather than by an argument through every operator: the
// operators are shared by all methods, and their results do not depend on it.

#include <CGAL/Density_equalizing_maps/parameters.h>

#include <Eigen/Core>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>
#endif

#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Terms per block of parallel_sum(), and the least number of indices per task.
constexpr Eigen::Index parallel_block = 4096;

/// Whether TBB was linked in (the concurrency tag has no effect without it).
constexpr bool parallel_loops_available()
{
#ifdef CGAL_LINKED_WITH_TBB
  return true;
#else
  return false;
#endif
}

inline bool& parallel_loops_requested()
{
  thread_local bool requested = false;
  return requested;
}

/// While alive, the loops started by this thread run in parallel (or not).
class Concurrency_scope
{
public:
  explicit Concurrency_scope(bool parallel) : m_previous(parallel_loops_requested())
  {
    parallel_loops_requested() = parallel && parallel_loops_available();
  }
  ~Concurrency_scope() { parallel_loops_requested() = m_previous; }
  Concurrency_scope(const Concurrency_scope&) = delete;
  Concurrency_scope& operator=(const Concurrency_scope&) = delete;

private:
  bool m_previous;
};

/// true for CGAL::Parallel_tag and CGAL::Parallel_if_available_tag.
template <class Tag>
constexpr bool is_parallel_tag()
{
  return std::is_convertible<Tag, CGAL::Parallel_tag>::value ||
         std::is_same<Tag, CGAL::Parallel_if_available_tag>::value;
}

/// The scope of a map called with the named parameters `np`: parallel loops
/// for `concurrency_tag(CGAL::Parallel_tag())` or
/// `concurrency_tag(CGAL::Parallel_if_available_tag())`, serial ones for
/// `CGAL::Sequential_tag`. Without the parameter the loops stay as they are:
/// serial, or as the map asked that calls this one (a registration's two maps,
/// a cartogram's passes).
template <class NamedParameters>
Concurrency_scope concurrency_scope_from_parameters(const NamedParameters&)
{
  using CGAL::parameters::is_default_parameter;
  if constexpr(is_default_parameter<NamedParameters, internal_np::concurrency_tag_t>::value) {
    return Concurrency_scope(parallel_loops_requested());
  } else {
    typedef typename internal_np::Lookup_named_param_def<internal_np::concurrency_tag_t, NamedParameters,
                                                         CGAL::Sequential_tag>::type Tag;
    return Concurrency_scope(is_parallel_tag<Tag>());
  }
}

/// body(begin, end) for consecutive ranges covering [0, n), each index once,
/// in parallel when requested and n > grain (at least grain indices a task).
template <class Body>
void parallel_for(Eigen::Index n, const Body& body, Eigen::Index grain = parallel_block)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel_loops_requested() && n > grain) {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, grain),
                      [&](const tbb::blocked_range<Eigen::Index>& r) { body(r.begin(), r.end()); });
    return;
  }
#endif
  if(n > 0) body(Eigen::Index(0), n);
}

/// Runs `first` and `second`, in parallel when parallel loops were asked for.
/// Each runs with its caller's choice of loops, whichever thread takes it.
template <class First, class Second>
void parallel_invoke(const First& first, const Second& second)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel_loops_requested()) {
    tbb::parallel_invoke([&] { const Concurrency_scope loops(true); first(); },
                         [&] { const Concurrency_scope loops(true); second(); });
    return;
  }
#endif
  first();
  second();
}

/// Runs `foreground` on the calling thread and, side by side when parallel
/// loops were asked for, `other` as a task any thread may take. Memory that
/// `other` allocates on another thread stays in that thread's malloc arena,
/// where the caller's later allocations cannot reuse it (FLASH at 100K
/// faces: +5 % peak memory when its Laplacian was allocated that way), so
/// `other` should fill storage the caller allocated.
template <class Other, class Foreground>
void run_beside(const Other& other, const Foreground& foreground)
{
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel_loops_requested()) {
    tbb::task_group group;
    group.run([&] { const Concurrency_scope loops(true); other(); });
    foreground();
    group.wait();
    return;
  }
#endif
  other();
  foreground();
}

/// body(b, begin, end) for the fixed blocks b = [begin, end) of
/// parallel_block indices of [0, n), each block whole to one call.
template <class Body>
void for_each_fixed_block(Eigen::Index n, const Body& body)
{
  const Eigen::Index blocks = (n + parallel_block - 1) / parallel_block;
  parallel_for(blocks, [&](Eigen::Index first_block, Eigen::Index last_block) {
    for(Eigen::Index b = first_block; b < last_block; ++b)
      body(b, b * parallel_block, std::min(n, (b + 1) * parallel_block));
  }, 1);
}

/// The K sums accumulated by add(i, sums) over [0, n) (add does sums[j] +=
/// ... for the terms of index i), rounded the same way on any number of
/// threads: blocks of parallel_block indices, then the blocks in order.
template <int K, class Add>
std::array<double, K> parallel_sums(Eigen::Index n, const Add& add)
{
  std::vector<std::array<double, K> > block_sums(static_cast<std::size_t>((n + parallel_block - 1) / parallel_block));
  for_each_fixed_block(n, [&](Eigen::Index b, Eigen::Index begin, Eigen::Index end) {
    std::array<double, K> s{}; // zeros
    for(Eigen::Index i = begin; i < end; ++i) add(i, s);
    block_sums[static_cast<std::size_t>(b)] = s;
  });
  std::array<double, K> total{};
  for(const std::array<double, K>& s : block_sums)
    for(int j = 0; j < K; ++j) total[j] += s[j];
  return total;
}

/// The sum of term(i) over [0, n), as parallel_sums().
template <class Term>
double parallel_sum(Eigen::Index n, const Term& term)
{
  return parallel_sums<1>(n, [&](Eigen::Index i, std::array<double, 1>& s) { s[0] += term(i); })[0];
}

/// The least i in [0, n) with pred(i), or n if there is none: the first
/// offending face of a check, whichever thread finds which.
template <class Pred>
Eigen::Index first_index_where(Eigen::Index n, const Pred& pred)
{
  std::vector<Eigen::Index> block_first(static_cast<std::size_t>((n + parallel_block - 1) / parallel_block), n);
  for_each_fixed_block(n, [&](Eigen::Index b, Eigen::Index begin, Eigen::Index end) {
    for(Eigen::Index i = begin; i < end; ++i)
      if(pred(i)) { block_first[static_cast<std::size_t>(b)] = i; break; }
  });
  for(Eigen::Index i : block_first)
    if(i < n) return i;
  return n;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_PARALLEL_H
