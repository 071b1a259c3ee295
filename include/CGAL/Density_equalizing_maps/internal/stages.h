// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_STAGES_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_STAGES_H

// The names of the stages of a map, told to the caller as each one starts
// (named parameter `stage_callback`), so that a progress display can say what
// a long direct stage is doing: a 2M-face harmonic solve lasts a minute with
// no iteration to count.

#include <CGAL/Density_equalizing_maps/parameters.h>

#include <functional>
#include <string>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Tells the caller which stage starts; empty (does nothing) without a callback.
typedef std::function<void(const std::string&)> Stage_notifier;

inline void begin_stage(const Stage_notifier& notify, const char* name)
{
  if(notify) notify(name);
}

template <class NamedParameters>
Stage_notifier stage_notifier_from_parameters(const NamedParameters& np)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::stage_callback_t>::value) {
    auto callback = get_parameter(np, internal_np::stage_callback);
    return [callback](const std::string& name) { callback(name); };
  } else {
    return Stage_notifier();
  }
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_STAGES_H
