// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Registration cases with a known true correspondence (tests and benchmark):
// a smooth star-shaped surface S(u) = shape(u) u over the directions u of the
// unit sphere, meshed twice independently (two spherical Fibonacci lattices of
// different sizes, relaxed: uniform_domain_mesh), the second copy deformed by
// a smooth map D and moved rigidly. The true partner of the source vertex with
// direction u is M(D(S(u))) (M the rigid motion): the analytic parameter u is
// the ground truth. The landmark directions are vertices of both meshes (the
// target's nearest vertex is moved onto each), so landmark pairs correspond
// exactly.
//
// The deformation D, chosen mild but not special (neither conformal nor
// area-preserving): an anisotropic scaling by (1.10, 0.95, 1.00) and a bend
// z += 0.08 x^2, i.e. lengths change by up to about 10 % and angles by a few degrees.

#ifndef DEM_REGISTRATION_CASES_H
#define DEM_REGISTRATION_CASES_H

#include <CGAL/Density_equalizing_maps/remeshing.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dem_registration {

typedef CGAL::Exact_predicates_inexact_constructions_kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index Vertex;

/// The radial profile of the generated surface: an ellipsoid-like body with
/// a bump and a saddle-like wave, so that no symmetry makes correspondence ambiguous.
inline Eigen::Vector3d surface_point(const Eigen::Vector3d& u)
{
  const Eigen::Vector3d bump_centre = Eigen::Vector3d(0.5, 0.6, 0.62).normalized();
  const double r = 1 + 0.2 * std::exp(-(u - bump_centre).squaredNorm() / 0.15) + 0.12 * u.x() * u.y();
  return r * Eigen::Vector3d(1.0 * u.x(), 0.8 * u.y(), 1.3 * u.z());
}

inline Eigen::Vector3d deformation(const Eigen::Vector3d& p)
{
  return Eigen::Vector3d(1.10 * p.x(), 0.95 * p.y(), p.z() + 0.08 * p.x() * p.x());
}

/// A rigid motion of the target (registration must not depend on pose).
inline Eigen::Vector3d rigid_motion(const Eigen::Vector3d& p)
{
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  return R * p + Eigen::Vector3d(0.3, -1.2, 2.0);
}

inline Eigen::Vector3d true_target_point(const Eigen::Vector3d& u) { return rigid_motion(deformation(surface_point(u))); }

inline Eigen::Vector3d to_eigen(const Point& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); }

/// The landmark directions: the 8 corners of a cube, turned so that none is on a symmetry axis.
inline std::vector<Eigen::Vector3d> landmark_directions(std::size_t count = 8)
{
  std::vector<Eigen::Vector3d> d;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  for(int i = 0; i < 8; ++i)
    d.push_back(R * Eigen::Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1).normalized());
  d.push_back(R * Eigen::Vector3d(0, 0, 1));
  d.push_back(R * Eigen::Vector3d(1, 0, 0));
  d.push_back(R * Eigen::Vector3d(0, -1, 0));
  d.push_back(R * Eigen::Vector3d(0, 0, -1));
  d.resize(count);
  return d;
}

struct Case
{
  Mesh source, target;
  std::vector<Eigen::Vector3d> source_directions; // the parameter u of every source vertex
  std::vector<std::pair<Vertex, Vertex> > pairs;
};

/// A sphere mesh with about n vertices whose nearest vertex to each direction is moved onto it.
inline Mesh sphere_with_landmarks(std::size_t n, const std::vector<Eigen::Vector3d>& dirs, const Eigen::Matrix3d& turn,
                                  std::vector<Vertex>& landmark_vertices)
{
  Mesh m;
  CGAL::Density_equalizing_maps::uniform_domain_mesh(CGAL::Density_equalizing_maps::Unit_sphere_domain(), n, m);
  for(Vertex v : m.vertices()) { const Eigen::Vector3d p = turn * to_eigen(m.point(v)); m.point(v) = Point(p.x(), p.y(), p.z()); }
  landmark_vertices.clear();
  for(const Eigen::Vector3d& d : dirs) {
    Vertex best;
    double bd = std::numeric_limits<double>::infinity();
    for(Vertex v : m.vertices()) {
      const double e = (to_eigen(m.point(v)) - d).squaredNorm();
      if(e < bd) { bd = e; best = v; }
    }
    m.point(best) = Point(d.x(), d.y(), d.z());
    landmark_vertices.push_back(best);
  }
  // the moved vertices must leave every face positively oriented about the centre
  for(auto f : m.faces()) {
    std::vector<Eigen::Vector3d> c;
    for(Vertex v : vertices_around_face(m.halfedge(f), m)) c.push_back(to_eigen(m.point(v)));
    if(!(c[0].dot(c[1].cross(c[2])) > 0)) throw std::logic_error("moving the landmark vertices folded the sphere mesh");
  }
  return m;
}

/// The source (about n_source vertices) and the target (an independent mesh of about
/// n_target vertices, deformed and moved), with `landmarks` exact landmark pairs.
inline Case make_case(std::size_t n_source, std::size_t n_target, std::size_t landmarks = 8)
{
  Case c;
  const std::vector<Eigen::Vector3d> dirs = landmark_directions(landmarks);
  std::vector<Vertex> ls, lt;
  c.source = sphere_with_landmarks(n_source, dirs, Eigen::Matrix3d::Identity(), ls);
  // a turned lattice, so that no vertex of the target sits at a source vertex by construction
  c.target = sphere_with_landmarks(n_target, dirs,
                                   Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix(), lt);
  for(Vertex v : c.source.vertices()) {
    const Eigen::Vector3d u = to_eigen(c.source.point(v));
    c.source_directions.push_back(u);
    const Eigen::Vector3d p = surface_point(u);
    c.source.point(v) = Point(p.x(), p.y(), p.z());
  }
  for(Vertex v : c.target.vertices()) {
    const Eigen::Vector3d p = true_target_point(to_eigen(c.target.point(v)));
    c.target.point(v) = Point(p.x(), p.y(), p.z());
  }
  for(std::size_t k = 0; k < dirs.size(); ++k) c.pairs.emplace_back(ls[k], lt[k]);
  return c;
}

inline double bounding_box_diagonal(const Mesh& m)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for(Vertex v : m.vertices()) { lo = lo.cwiseMin(to_eigen(m.point(v))); hi = hi.cwiseMax(to_eigen(m.point(v))); }
  return (hi - lo).norm();
}

struct Accuracy
{
  double mean = 0, max = 0; // distance to the true partner / target bounding-box diagonal
};

/// Distance of every registered source vertex to its true partner, relative to the target's diagonal.
template <class PointMap>
Accuracy accuracy(const Case& c, const PointMap& registered)
{
  Accuracy a;
  const double diag = bounding_box_diagonal(c.target);
  for(Vertex v : c.source.vertices()) {
    const double e = (to_eigen(get(registered, v)) - true_target_point(c.source_directions[v.idx()])).norm() / diag;
    a.mean += e / double(c.source.number_of_vertices());
    a.max = (std::max)(a.max, e);
  }
  return a;
}

} // namespace dem_registration

#endif // DEM_REGISTRATION_CASES_H
