// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELONGATED_STARTS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELONGATED_STARTS_H

// Starting maps for elongated surfaces (issue 14, paper 000 section 1): the
// conformal map onto the sphere shrinks a protrusion exponentially with its
// length (a 100:1 capsule needs scale ratios near e^-200, below double
// precision: the FLASH map folds), and the density flow stalls on the density
// ratios it leaves. The density-equalizing maps start instead from a map that
// does not crowd, whichever is closest to the target density. Also here, as
// the other choice of a start by its density: the Moebius correction towards
// the population (population_mobius_start()).

#include <CGAL/Density_equalizing_maps/internal/ellipsoidal_conformal.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

/// Surfaces whose bounding box in the principal frame is this many times
/// longer than wide are elongated: their conformal image crowds.
constexpr double elongation_of_crowding = 3.;

/// Mean over the faces of |log(image density / mean)|, the density being
/// population / image area; a face crowded to zero area counts as a density
/// of 1e300 (mean_abs_log_area_ratio() would skip it).
inline double mean_abs_log_density(const Vector& population, const Vector& image_area)
{
  const double sp = population.sum(), si = image_area.sum();
  double sum = 0;
  for(Eigen::Index k = 0; k < population.size(); ++k)
    sum += std::abs(std::log(std::max(image_area[k] / si, 1e-300) / (population[k] / sp)));
  return sum / double(population.size());
}

/// sd/mean of the re-coupled vertex density (the density flows' own measure).
inline double vertex_density_spread(const Vector& population, const Matrix& S, const Index_matrix& F)
{
  const Vector area = face_areas(S, F);
  return relative_sd(densities(population, area, face_to_vertex(area, F, S.rows())).vertex);
}

/// The start of a density flow on the sphere from the conformal map S: the
/// Moebius correction towards the population (mobius_correction()) where it
/// brings the density closer to uniform by both measures, mean |log density|
/// and sd/mean of the vertex density, than the area correction of paper 001;
/// else the area correction. Both are needed: on a smooth bump of ratio 1e4
/// the population correction lowers both (sd/mean 7.6 -> 0.82) and the flow
/// converges in 24 iterations instead of 149, but on a step of ratio 1e4 it
/// lowers mean |log density| while raising sd/mean (1.30 -> 2.1), and the flow
/// from it stalls sooner, less uniform (benchmark/RESULTS.md, "Moebius
/// correction towards the population"). With the face area as population the
/// two are the same map.
/// `by_population` says which one was taken.
inline Matrix population_mobius_start(const Matrix& X, const Index_matrix& F, const Matrix& S, const Vector& population,
                                      bool& by_population_taken)
{
  by_population_taken = false;
  const Vector area = face_areas(X, F);
  Matrix by_area = mobius_correction(area, F, S);
  if(population == area) return by_area;
  Matrix by_population = mobius_correction(population, F, S);
  const bool closer = mean_abs_log_density(population, face_areas(by_population, F)) <
                        mean_abs_log_density(population, face_areas(by_area, F)) &&
                      vertex_density_spread(population, by_population, F) < vertex_density_spread(population, by_area, F);
  by_population_taken = closer;
  return closer ? by_population : by_area;
}

/// Area of the surface below each height h_i, each face's area spread
/// uniformly over its range of heights: a continuous, non-decreasing function
/// of the height, so vertices at equal heights get equal values (a ring of a
/// tube stays a ring). One sweep over the sorted face ranges and queries.
inline Vector area_below_heights(const Vector& h, const Index_matrix& F, const Vector& face_area)
{
  struct Event { double at; Eigen::Index face; bool end; };
  std::vector<Event> events;
  events.reserve(static_cast<std::size_t>(2 * F.rows()));
  Vector lo(F.rows()), hi(F.rows());
  for(Eigen::Index k = 0; k < F.rows(); ++k) {
    lo[k] = std::min({h[F(k, 0)], h[F(k, 1)], h[F(k, 2)]});
    hi[k] = std::max({h[F(k, 0)], h[F(k, 1)], h[F(k, 2)]});
    events.push_back({lo[k], k, false});
    events.push_back({hi[k], k, true});
  }
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.at < b.at; });
  std::vector<Eigen::Index> queries(static_cast<std::size_t>(h.size()));
  std::iota(queries.begin(), queries.end(), Eigen::Index(0));
  std::sort(queries.begin(), queries.end(), [&h](Eigen::Index i, Eigen::Index j) { return h[i] < h[j]; });
  Vector below(h.size());
  double full = 0, slope = 0, offset = 0; // the faces passing the height h contribute slope h - offset
  std::size_t e = 0;
  for(Eigen::Index i : queries) {
    for(; e < events.size() && events[e].at <= h[i]; ++e) {
      const Eigen::Index k = events[e].face;
      const double range = hi[k] - lo[k], rate = range > 0 ? face_area[k] / range : 0;
      if(events[e].end) { full += face_area[k]; slope -= rate; offset -= rate * lo[k]; }
      else { slope += rate; offset += rate * lo[k]; }
    }
    below[i] = full + std::max(0., slope * h[i] - offset);
  }
  return below;
}

/// The heights t in [-1, 1] on the unit sphere, about `axis`, that the map
/// s -> radii (*) s onto the ellipsoid sends to the heights below which the
/// ellipsoid holds the given shares of its area: the inverse of the ellipsoid's
/// area CDF in the sphere's height. The band of the sphere at height t has
/// ellipsoid area density g(t) = integral over the longitude of
/// abc |diag(radii)^-1 s| (a linear map scales the area of a surface with unit
/// normal n by |det D| |D^-T n|); for the unit sphere g is constant and t = 2
/// share - 1 (Archimedes). g is tabulated and integrated by the midpoint rule.
inline Vector sphere_heights_of_area_shares(const Vector& shares, const Eigen::Vector3d& radii, int axis)
{
  const int samples = 2048, longitudes = 64;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::vector<double> cdf(samples + 1, 0.);
  for(int k = 0; k < samples; ++k) {
    const double t = -1 + (k + 0.5) * 2. / samples, r = std::sqrt(1 - t * t);
    double g = 0;
    for(int j = 0; j < longitudes; ++j) {
      const double phi = 2 * M_PI * (j + 0.5) / longitudes;
      Eigen::Vector3d s;
      s[u] = r * std::cos(phi);
      s[v] = r * std::sin(phi);
      s[axis] = t;
      g += s.cwiseQuotient(radii).norm();
    }
    cdf[k + 1] = cdf[k] + g;
  }
  Vector t(shares.size());
  for(Eigen::Index i = 0; i < shares.size(); ++i) {
    const double target = std::max(0., std::min(1., shares[i])) * cdf[samples];
    const int k = int(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin()) - 1;
    if(k >= samples) { t[i] = 1; continue; }
    const double f = cdf[k + 1] > cdf[k] ? (target - cdf[k]) / (cdf[k + 1] - cdf[k]) : 0;
    t[i] = -1 + (k + f) * 2. / samples;
  }
  return t;
}

/// A start along the axis of an elongated surface, with no conformal map
/// involved (nothing crowds): with the principal coordinate `axis` of `frame`
/// as height, a vertex goes to the height on the unit sphere whose polar cap,
/// once mapped onto the ellipsoid `radii` (the sphere itself for (1, 1, 1)),
/// holds the share of the domain's area that the part of the surface below
/// the vertex holds of the surface's, so that bands keep their area shares;
/// at its own longitude about the axis. Bijective when every cross-section is
/// star-shaped about the axis (capsules, stretched blobs); empty otherwise
/// (exact fold count). The result lies on the unit sphere (scale it by the
/// radii for the ellipsoid).
inline Matrix axial_start(const Matrix& X, const Index_matrix& F, const Principal_frame& frame, int axis = 2,
                          const Eigen::Vector3d& radii = Eigen::Vector3d::Ones())
{
  const Matrix Q = (X.rowwise() - frame.center.transpose()) * frame.axes; // principal coordinates
  const Vector area = face_areas(X, F);
  const Vector heights = sphere_heights_of_area_shares(area_below_heights(Q.col(axis), F, area) / area.sum(), radii, axis);
  const int u = (axis + 1) % 3, v = (axis + 2) % 3; // longitude plane, cyclic after the axis
  Matrix S(X.rows(), 3);
  for(Eigen::Index i = 0; i < X.rows(); ++i) {
    const double height = heights[i];
    const double longitude = std::atan2(Q(i, v), Q(i, u)), r = std::sqrt(std::max(0., 1 - height * height));
    S(i, u) = r * std::cos(longitude);
    S(i, v) = r * std::sin(longitude);
    S(i, axis) = height;
  }
  // the principal frame may be left-handed relative to the faces' orientation: mirror then
  if(2 * count_inverted_faces_about_center(S, F) > std::size_t(F.rows())) S.col(v) = -S.col(v);
  return count_inverted_faces_about_center(S, F) == 0 ? S : Matrix();
}

/// The start of an elongated surface: a conformal map onto the unit sphere
/// shrinks a protrusion exponentially with its length (a 30:1 capsule: density
/// ratios near e^20, which the flow has to undo and on which it stalls), while
/// the conformal map onto the surface's bounding-box ellipsoid (FECM, from the
/// same FLASH map) does not crowd. The linear map diag(1/a, 1/b, 1/c) carries
/// it onto the unit sphere keeping every face's orientation about the centre
/// (a positive diagonal map), so a fold-free FECM map gives a fold-free start.
/// It inherits the precision of the FLASH map, which a 30:1 capsule already
/// exhausts (measured: mean |log density| 4.1 there, 0.26 at 10:1; the axial
/// start serves the longer ones). Empty when the result folds (exact count).
inline Matrix ellipsoidal_start(const Matrix& X, const Index_matrix& F, const Principal_frame& frame,
                                const Flash_result& flash, const Spd_solver& solver)
{
  const Eigen::Vector3d radii = frame.extent / frame.extent.mean();
  const Ellipsoidal_mapper mapper(X, F, default_pole_vertices(X, frame), solver, flash);
  Matrix S = evaluate_ellipsoidal_conformal(mapper, radii, face_areas(X, F), true).f;
  for(Eigen::Index i = 0; i < S.rows(); ++i) S.row(i) = S.row(i).cwiseQuotient(radii.transpose()).normalized();
  if(!S.allFinite() || count_inverted_faces_about_center(S, F) > 0) return Matrix();
  return S;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_ELONGATED_STARTS_H
