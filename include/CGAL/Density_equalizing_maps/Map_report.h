// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_MAP_REPORT_H
#define CGAL_DENSITY_EQUALIZING_MAPS_MAP_REPORT_H

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {

/// \ingroup PkgDensityEqualizingMapsRef
/// Exception thrown by every function of the package when its input is invalid:
/// the mesh (not a triangle mesh, boundary, non-manifold, wrong genus, degenerate
/// or non-finite face, too few vertices), the population, landmarks, radii or
/// other parameters. `what()` names the problem and, where it applies, the
/// offending face, vertex or line. Nothing is written to the output maps when
/// it is thrown.
class Invalid_input : public std::invalid_argument
{
public:
  explicit Invalid_input(const std::string& what_arg) : std::invalid_argument(what_arg) {}
};

/// \ingroup PkgDensityEqualizingMapsRef
/// Exception thrown when the input is valid but the method itself could not
/// produce its result: a step that cannot fail in exact arithmetic failed in
/// floating point (a linear solve or factorization, a computed starting map
/// that is not bijective or not finite). `what()` says which step failed and,
/// for a starting map, its exact fold-over count. It is not a subclass of
/// `Invalid_input`: the caller did nothing wrong, and a tool reports it with a
/// different status (the `dem` tool exits with status 4, not 3). Nothing is
/// written to the output maps when it is thrown.
///
/// A run that starts but cannot improve further (a density-equalizing flow
/// that stalls) does not throw: it returns a bijective map (the last one, or,
/// for SDEM, EDEM and TDEM, the most uniform one of the run) with
/// `Map_report::termination` set to `Termination::STALLED`.
class Algorithm_failure : public std::runtime_error
{
public:
  explicit Algorithm_failure(const std::string& what_arg) : std::runtime_error(what_arg) {}
};

/// \ingroup PkgDensityEqualizingMapsRef
/// How an iterative method ended.
enum class Termination
{
  CONVERGED,          ///< the stopping criterion was met
  MAXIMUM_ITERATIONS, ///< the iteration limit was reached first (the density-only flows, SDEM, EDEM and TDEM,
                      ///< return the most uniform of the run's maps, see `Map_report::message`)
  STALLED,            ///< no fold-over-free step could be found; the last bijective map is returned, or, by
                      ///< the density-only flows (SDEM, EDEM, TDEM), the most uniform of the run's maps (see `Map_report::message`)
  CANCELLED,          ///< the progress callback asked to stop; the last bijective map is returned
  NOT_ITERATIVE       ///< a direct (non-iterative) method
};

/// \ingroup PkgDensityEqualizingMapsRef
/// Returns a lower-case name for a termination value (`"converged"`, ...).
/// \param t the termination value
/// \returns a static, null-terminated string
inline const char* to_string(Termination t)
{
  switch(t) {
    case Termination::CONVERGED: return "converged";
    case Termination::MAXIMUM_ITERATIONS: return "maximum iterations reached";
    case Termination::STALLED: return "stalled: no fold-over-free step";
    case Termination::CANCELLED: return "cancelled";
    default: return "direct method";
  }
}

/// \ingroup PkgDensityEqualizingMapsRef
/// What a mapping function did. Every method fills `fold_overs` with the
/// exact-predicate count on its output; the other fields are filled where they
/// apply and are otherwise left at their default (negative = not applicable).
struct Map_report
{
  Termination termination = Termination::NOT_ITERATIVE;
  /// number of outer iterations of an iterative method
  std::size_t iterations = 0;
  /// faces whose image is inverted, counted with exact predicates
  std::size_t fold_overs = 0;
  /// final value of the stopping quantity (sd/mean of the density for the
  /// density-equalizing maps, update norm for LSDEM); negative if not applicable
  double final_error = -1;
  /// initial value of the stopping quantity
  double initial_error = -1;
  /// number of fold-over repairs of a step (local untangling and Linear
  /// Beltrami Solver repairs; those of the flow, and those that moved a
  /// fallback start towards the conformal map)
  std::size_t repairs = 0;
  /// number of times the time step was halved during repairs
  std::size_t step_halvings = 0;
  /// mean distance between mapped landmarks and their targets (landmark methods)
  double landmark_error = -1;
  /// ellipsoid radii (a,b,c) or torus radii (R,r,0) used or found; empty otherwise
  std::vector<double> radii;
  /// true when the Tutte fallback replaced the cotangent harmonic map
  bool used_tutte_fallback = false;
  /// Which fallback replaced a step of the method, empty if none: e.g.
  /// "tutte embedding (the harmonic map failed)" or "tutte embedding repaired
  /// towards the harmonic map (the harmonic map folded)". Several fallbacks
  /// are separated by "; ". A non-empty value means the output is valid
  /// (`fold_overs` says whether it is bijective) but may be of lower quality
  /// than the method's usual result.
  std::string fallback;
  /// `true` when a landmark method returned a fold-free map only by giving up
  /// its landmark constraints (the quasi-conformal map kept folds and the
  /// fold-free fallback that replaced it does not follow the landmarks): the
  /// output is bijective but it is not the landmark-aligned map asked for, and
  /// callers must treat the run as failed
  bool landmarks_given_up = false;
  /// The starting map an iterative method chose, empty for the direct methods
  /// and where there is no choice: `"initial_map"` (given by the caller),
  /// `"input"` (the input already lies on the ellipsoid), `"conformal"` (the
  /// conformal map with the Moebius area correction, or the ellipsoidal
  /// conformal map), `"conformal_population_moebius"` (the conformal map
  /// Moebius-corrected towards the population), `"scaled_sphere"` and
  /// `"scaled_sphere_population_moebius"` (EDEM: the spherical ones scaled by
  /// the radii), `"axial"` and `"ellipsoidal"` (the
  /// starts of elongated surfaces). A density flow takes the start closest to
  /// uniform density, so this says which one a run took.
  std::string start;
  /// a human-readable note on anything unusual (e.g. why a run stalled)
  std::string message;

  /// appends a fallback description to `fallback`
  /// \param what the fallback taken (ignored when empty)
  void add_fallback(const std::string& what)
  {
    if(what.empty()) return;
    fallback += (fallback.empty() ? "" : "; ") + what;
  }

  /// \returns `true` when the output is a bijective map (no fold-over)
  bool is_bijective() const { return fold_overs == 0; }
  /// \returns `true` when the method met its stopping criterion (or is direct)
  bool converged() const
  { return termination == Termination::CONVERGED || termination == Termination::NOT_ITERATIVE; }
};

} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_MAP_REPORT_H
