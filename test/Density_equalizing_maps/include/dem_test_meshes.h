// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Test support: mesh generators (as index arrays and as Surface_mesh), bad
// meshes for the validation tests, access to the shared data folder and a
// tiny check helper. Header-only, for the test programs only.

#ifndef DEM_TEST_MESHES_H
#define DEM_TEST_MESHES_H

#include <CGAL/Density_equalizing_maps/internal/mesh_arrays.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace dem_test {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Point_2 Point_2;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index vertex_descriptor;
typedef Mesh::Face_index face_descriptor;
using CGAL::Density_equalizing_maps::internal::Matrix;
using CGAL::Density_equalizing_maps::internal::Index_matrix;
using CGAL::Density_equalizing_maps::internal::Vector;

/// Exit code that ctest reports as "skipped".
constexpr int skip_code = 77;

// ---------------------------------------------------------------------------
// Checks: record failures, keep going, report at the end.

inline int& failure_count() { static int n = 0; return n; }

inline bool check(bool ok, const std::string& what)
{
  if(!ok) { ++failure_count(); std::cerr << "FAILED: " << what << std::endl; }
  return ok;
}

/// |a - b| <= tol (false on NaN).
inline bool check_close(double a, double b, double tol, const std::string& what)
{
  const bool ok = std::abs(a - b) <= tol;
  if(!ok) {
    std::ostringstream s;
    s.precision(17);
    s << what << ": " << a << " vs " << b << " (tolerance " << tol << ")";
    return check(false, s.str());
  }
  return true;
}

/// Returns the exit code of a test program.
inline int finish(const char* name)
{
  if(failure_count() == 0) { std::cout << name << ": all checks passed" << std::endl; return 0; }
  std::cerr << name << ": " << failure_count() << " check(s) failed" << std::endl;
  return 1;
}

/// Runs `f()` and returns the message of the exception of type E it throws,
/// or an empty string (and a failed check) if it throws nothing or something else.
template <class E, class F>
std::string expect_throw(F f, const std::string& what)
{
  try { f(); }
  catch(const E& e) { return e.what(); }
  catch(const std::exception& e) { check(false, what + ": wrong exception type: " + e.what()); return ""; }
  check(false, what + ": no exception");
  return "";
}

inline bool contains(const std::string& s, const std::string& sub) { return s.find(sub) != std::string::npos; }

struct Stopwatch
{
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
};

// ---------------------------------------------------------------------------
// Arrays <-> Surface_mesh

struct Arrays { Matrix X; Index_matrix F; };

inline Arrays make_arrays(const std::vector<Eigen::Vector3d>& V, const std::vector<Eigen::Vector3i>& T)
{
  Arrays a;
  a.X.resize(static_cast<Eigen::Index>(V.size()), 3);
  a.F.resize(static_cast<Eigen::Index>(T.size()), 3);
  for(std::size_t i = 0; i < V.size(); ++i) a.X.row(i) = V[i].transpose();
  for(std::size_t k = 0; k < T.size(); ++k) a.F.row(k) = T[k].transpose();
  return a;
}

/// Builds a Surface_mesh; vertex i of the arrays is vertex index i of the mesh.
inline Mesh to_mesh(const Arrays& a)
{
  Mesh m;
  std::vector<vertex_descriptor> v;
  for(Eigen::Index i = 0; i < a.X.rows(); ++i) v.push_back(m.add_vertex(Point(a.X(i, 0), a.X(i, 1), a.X(i, 2))));
  for(Eigen::Index k = 0; k < a.F.rows(); ++k)
    if(m.add_face(v[a.F(k, 0)], v[a.F(k, 1)], v[a.F(k, 2)]) == Mesh::null_face())
      std::cerr << "to_mesh: face " << k << " could not be added" << std::endl;
  return m;
}

inline Arrays from_mesh(const Mesh& m)
{
  Arrays a;
  a.X.resize(m.number_of_vertices(), 3);
  a.F.resize(m.number_of_faces(), 3);
  for(auto v : m.vertices()) {
    const Point& p = m.point(v);
    a.X.row(v.idx()) = Eigen::RowVector3d(p.x(), p.y(), p.z());
  }
  Eigen::Index k = 0;
  for(auto f : m.faces()) {
    int c = 0;
    for(auto v : vertices_around_face(m.halfedge(f), m)) if(c < 3) a.F(k, c++) = int(v.idx());
    ++k;
  }
  return a;
}

/// The volume enclosed by a closed mesh (positive if oriented outward).
inline double signed_volume(const Arrays& a)
{
  double v = 0;
  for(Eigen::Index k = 0; k < a.F.rows(); ++k) {
    const Eigen::Vector3d p = a.X.row(a.F(k, 0)), q = a.X.row(a.F(k, 1)), r = a.X.row(a.F(k, 2));
    v += p.dot(q.cross(r)) / 6.;
  }
  return v;
}

inline void flip_faces(Arrays& a)
{
  for(Eigen::Index k = 0; k < a.F.rows(); ++k) std::swap(a.F(k, 1), a.F(k, 2));
}

inline void orient_outward(Arrays& a) { if(signed_volume(a) < 0) flip_faces(a); }

// ---------------------------------------------------------------------------
// Generators (closed meshes are oriented outward)

/// Regular icosahedron on the unit sphere, each triangle split in 4 `subdivisions`
/// times with the new vertices projected on the sphere: 10 * 4^s + 2 vertices.
inline Arrays icosphere_arrays(int subdivisions)
{
  const double t = (1 + std::sqrt(5.)) / 2;
  std::vector<Eigen::Vector3d> V = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::Vector3i> T = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for(auto& v : V) v.normalize();
  for(int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int i, int j) {
      const std::pair<int, int> key(std::min(i, j), std::max(i, j));
      auto it = mid.find(key);
      if(it != mid.end()) return it->second;
      V.push_back((V[i] + V[j]).normalized());
      return mid[key] = int(V.size()) - 1;
    };
    std::vector<Eigen::Vector3i> T2;
    T2.reserve(4 * T.size());
    for(const auto& f : T) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      T2.emplace_back(f[0], a, c); T2.emplace_back(f[1], b, a); T2.emplace_back(f[2], c, b); T2.emplace_back(a, b, c);
    }
    T.swap(T2);
  }
  Arrays a = make_arrays(V, T);
  orient_outward(a);
  return a;
}

inline Mesh icosphere(int subdivisions) { return to_mesh(icosphere_arrays(subdivisions)); }

/// Icosphere scaled to the ellipsoid with semi-axes a, b, c.
inline Arrays ellipsoid_arrays(double a, double b, double c, int subdivisions)
{
  Arrays m = icosphere_arrays(subdivisions);
  for(Eigen::Index i = 0; i < m.X.rows(); ++i) { m.X(i, 0) *= a; m.X(i, 1) *= b; m.X(i, 2) *= c; }
  return m;
}

inline Mesh ellipsoid(double a, double b, double c, int subdivisions)
{ return to_mesh(ellipsoid_arrays(a, b, c, subdivisions)); }

/// A star-shaped genus-0 surface with radial bumps r = 1 + amplitude * b(direction),
/// optionally stretched along z by `elongation` (a bumpy cigar for elongation > 1).
inline Arrays bumpy_arrays(int subdivisions, double amplitude = 0.25, double elongation = 1.)
{
  Arrays m = icosphere_arrays(subdivisions);
  for(Eigen::Index i = 0; i < m.X.rows(); ++i) {
    const Eigen::Vector3d u = m.X.row(i);
    const double b = std::sin(3 * u.x()) * std::cos(2 * u.y() + 0.5) * std::sin(4 * u.z() + 0.3) +
                     0.5 * std::cos(5 * u.x() * u.y());
    m.X.row(i) = (1 + amplitude * b) * u.transpose();
    m.X(i, 2) *= elongation;
  }
  orient_outward(m);
  return m;
}

inline Mesh bumpy(int subdivisions, double amplitude = 0.25) { return to_mesh(bumpy_arrays(subdivisions, amplitude)); }
inline Mesh elongated(int subdivisions) { return to_mesh(bumpy_arrays(subdivisions, 0.15, 4.)); }

/// Icosphere whose vertices are moved on the sphere by the Moebius dilation
/// z -> k z of the stereographic chart from the north pole: still a unit
/// sphere, but with triangles k^2 times larger near the south pole than near
/// the north one. Its conformal maps onto the sphere are exactly the Moebius
/// maps, among which only the inverse dilation (up to rotation) makes the map
/// area-preserving: FLASH's normalization does not pick it.
inline Arrays mobius_dilated_icosphere_arrays(int subdivisions, double k)
{
  Arrays a = icosphere_arrays(subdivisions);
  for(Eigen::Index i = 0; i < a.X.rows(); ++i) {
    const double z = a.X(i, 2);
    if(z > 1 - 1e-12) continue; // the north pole stays
    const double u = k * a.X(i, 0) / (1 - z), v = k * a.X(i, 1) / (1 - z), r2 = u * u + v * v;
    a.X.row(i) << 2 * u / (1 + r2), 2 * v / (1 + r2), (r2 - 1) / (r2 + 1);
  }
  return a;
}

/// Closed torus with radii R > r, nu x nv vertices, (nu x nv x 2) triangles.
inline Arrays torus_arrays(double R, double r, int nu, int nv)
{
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> T;
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      V.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [nu, nv](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      T.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      T.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  Arrays a = make_arrays(V, T);
  // the volume of a torus about the origin is well defined: use it to orient outward
  orient_outward(a);
  return a;
}

inline Mesh torus(double R, double r, int nu, int nv) { return to_mesh(torus_arrays(R, r, nu, nv)); }

/// A closed genus-2 surface: two tori, one face removed from each, joined by a
/// triangular tube (combinatorial connected sum; geometry is only roughly embedded).
inline Arrays double_torus_arrays(int nu = 16, int nv = 8)
{
  Arrays A = torus_arrays(2, 0.7, nu, nv), B = torus_arrays(2, 0.7, nu, nv);
  const Eigen::Index na = A.X.rows();
  B.X.col(0).array() += 6.; // side by side along x
  // remove from A a face on its +x side and from B one on its -x side
  auto pick = [](const Arrays& M, double sign) {
    Eigen::Index best = 0;
    double bx = -std::numeric_limits<double>::infinity();
    for(Eigen::Index k = 0; k < M.F.rows(); ++k) {
      const double x = sign * (M.X(M.F(k, 0), 0) + M.X(M.F(k, 1), 0) + M.X(M.F(k, 2), 0));
      if(x > bx) { bx = x; best = k; }
    }
    return best;
  };
  const Eigen::Index fa = pick(A, 1), fb = pick(B, -1);
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> T;
  for(Eigen::Index i = 0; i < A.X.rows(); ++i) V.push_back(A.X.row(i).transpose());
  for(Eigen::Index i = 0; i < B.X.rows(); ++i) V.push_back(B.X.row(i).transpose());
  for(Eigen::Index k = 0; k < A.F.rows(); ++k) if(k != fa) T.push_back(A.F.row(k).transpose());
  for(Eigen::Index k = 0; k < B.F.rows(); ++k)
    if(k != fb) T.emplace_back(B.F(k, 0) + na, B.F(k, 1) + na, B.F(k, 2) + na);
  // the tube needs the halfedges a->b, b->c, c->a (A's hole) and d->e, e->f, f->d (B's hole);
  // pairing a-e, b-d, c-f gives the quads (a,b,d,e), (b,c,f,d), (c,a,e,f)
  const int a = A.F(fa, 0), b = A.F(fa, 1), c = A.F(fa, 2);
  const int d = int(B.F(fb, 0) + na), e = int(B.F(fb, 1) + na), f = int(B.F(fb, 2) + na);
  T.emplace_back(a, b, d); T.emplace_back(a, d, e);
  T.emplace_back(b, c, f); T.emplace_back(b, f, d);
  T.emplace_back(c, a, e); T.emplace_back(c, e, f);
  return make_arrays(V, T);
}

inline Arrays tetrahedron_arrays(const Eigen::Vector3d& shift = Eigen::Vector3d::Zero())
{
  std::vector<Eigen::Vector3d> V = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for(auto& v : V) v += shift;
  Arrays a = make_arrays(V, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}});
  orient_outward(a);
  return a;
}

/// Planar jittered grid on [0,1]^2 (n x n vertices, z = 0 column if dim == 3),
/// counter-clockwise faces; interior vertices moved randomly by up to jitter * h.
inline Arrays planar_grid_arrays(int n, double jitter = 0.3, unsigned seed = 1, int dim = 2)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 1. / (n - 1);
  Arrays a;
  a.X = Matrix::Zero(n * n, dim);
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      double x = i * h, y = j * h;
      if(i > 0 && i < n - 1 && j > 0 && j < n - 1) { x += jitter * h * U(gen); y += jitter * h * U(gen); }
      a.X(i * n + j, 0) = x;
      a.X(i * n + j, 1) = y;
    }
  a.F.resize(2 * (n - 1) * (n - 1), 3);
  Eigen::Index k = 0;
  for(int i = 0; i + 1 < n; ++i)
    for(int j = 0; j + 1 < n; ++j) {
      const int v00 = i * n + j, v10 = (i + 1) * n + j, v11 = (i + 1) * n + j + 1, v01 = i * n + j + 1;
      if((i + j) % 2) { a.F.row(k++) << v00, v10, v11; a.F.row(k++) << v00, v11, v01; }
      else { a.F.row(k++) << v00, v10, v01; a.F.row(k++) << v10, v11, v01; }
    }
  return a;
}

/// Vertices on the boundary of the unit square grid.
inline std::vector<char> planar_grid_boundary(int n)
{
  std::vector<char> b(static_cast<std::size_t>(n * n), 0);
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) b[i * n + j] = (i == 0 || j == 0 || i == n - 1 || j == n - 1);
  return b;
}

// ---------------------------------------------------------------------------
// Bad meshes for the validation tests

/// Icosphere with one face removed (a hole).
inline Mesh open_icosphere(int subdivisions = 2)
{
  Mesh m = icosphere(subdivisions);
  CGAL::Euler::remove_face(m.halfedge(*m.faces().begin()), m);
  m.collect_garbage();
  return m;
}

/// Two tetrahedra sharing one vertex (vertex 0). Surface_mesh cannot build it
/// through add_face (the second fan would close around a non-border vertex),
/// so the second tetrahedron is built around a temporary last vertex whose
/// halfedges are then re-targeted to vertex 0.
inline Mesh pinched_tetrahedra()
{
  Arrays A = tetrahedron_arrays(), B = tetrahedron_arrays();
  for(Eigen::Index i = 0; i < 4; ++i) B.X.row(i) = 2. * A.X.row(0) - A.X.row(i); // point reflection through A's vertex 0
  orient_outward(B);
  Mesh m;
  std::vector<vertex_descriptor> v;
  for(int i = 0; i < 4; ++i) v.push_back(m.add_vertex(Point(A.X(i, 0), A.X(i, 1), A.X(i, 2))));
  for(int i = 1; i < 4; ++i) v.push_back(m.add_vertex(Point(B.X(i, 0), B.X(i, 1), B.X(i, 2))));
  const vertex_descriptor tmp = m.add_vertex(Point(B.X(0, 0), B.X(0, 1), B.X(0, 2)));
  auto vb = [&](int i) { return i == 0 ? tmp : v[3 + i]; };
  for(Eigen::Index k = 0; k < 4; ++k) m.add_face(v[A.F(k, 0)], v[A.F(k, 1)], v[A.F(k, 2)]);
  for(Eigen::Index k = 0; k < 4; ++k) m.add_face(vb(B.F(k, 0)), vb(B.F(k, 1)), vb(B.F(k, 2)));
  for(auto h : m.halfedges())
    if(m.target(h) == tmp) m.set_target(h, v[0]);
  m.remove_vertex(tmp); // the last vertex: the others keep the indices 0..6
  m.collect_garbage();
  return m;
}

/// An octahedron whose top vertex lies exactly on the segment between two
/// others: the face they span has exactly collinear corners (zero area).
inline Mesh octahedron_with_collinear_face()
{
  std::vector<Eigen::Vector3d> V = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  Arrays a = make_arrays(V, {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {1, 0, 5}, {2, 1, 5}, {3, 2, 5}, {0, 3, 5}});
  orient_outward(a);
  a.X.row(4) = Eigen::RowVector3d(0.5, 0.5, 0); // exactly the midpoint of (1,0,0) and (0,1,0)
  return to_mesh(a);
}

/// Icosphere with one coordinate set to NaN.
inline Mesh icosphere_with_nan(int subdivisions = 2)
{
  Arrays a = icosphere_arrays(subdivisions);
  a.X(3, 1) = std::numeric_limits<double>::quiet_NaN();
  return to_mesh(a);
}

/// A cube made of quadrilaterals.
inline Mesh quad_cube()
{
  Mesh m;
  std::vector<vertex_descriptor> v;
  for(int i = 0; i < 8; ++i) v.push_back(m.add_vertex(Point(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  const int Q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for(const auto& q : Q)
    if(m.add_face(v[q[0]], v[q[1]], v[q[2]], v[q[3]]) == Mesh::null_face())
      std::cerr << "quad_cube: face could not be added" << std::endl;
  return m;
}

/// Two triangles glued back to back: closed, but only 3 vertices.
inline Mesh two_sided_triangle()
{
  Mesh m;
  const auto a = m.add_vertex(Point(0, 0, 0)), b = m.add_vertex(Point(1, 0, 0)), c = m.add_vertex(Point(0, 1, 0));
  m.add_face(a, b, c);
  m.add_face(a, c, b);
  return m;
}

/// Two disjoint tetrahedra.
inline Mesh two_tetrahedra()
{
  Arrays A = tetrahedron_arrays(), B = tetrahedron_arrays(Eigen::Vector3d(5, 0, 0));
  Arrays C;
  C.X.resize(8, 3);
  C.X << A.X, B.X;
  C.F.resize(8, 3);
  C.F << A.F, (B.F.array() + 4).matrix();
  return to_mesh(C);
}

/// Icosphere plus one vertex that belongs to no face.
inline Mesh icosphere_with_isolated_vertex(int subdivisions = 1)
{
  Mesh m = icosphere(subdivisions);
  m.add_vertex(Point(3, 0, 0));
  return m;
}

/// Two tetrahedra sharing an edge: edge (0,1) has four incident faces
/// (cannot be stored in a halfedge data structure, hence arrays).
inline Arrays non_manifold_edge_arrays()
{
  Arrays A = tetrahedron_arrays();
  std::vector<Eigen::Vector3d> V;
  for(Eigen::Index i = 0; i < 4; ++i) V.push_back(A.X.row(i).transpose());
  V.emplace_back(3, 0, 0);
  V.emplace_back(2, 2, 1);
  std::vector<Eigen::Vector3i> T;
  for(Eigen::Index k = 0; k < 4; ++k) T.push_back(A.F.row(k).transpose());
  // a second tetrahedron (0,1,4,5) with the same orientation rule
  Arrays B = make_arrays({V[0], V[1], V[4], V[5]}, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}});
  orient_outward(B);
  const int map[4] = {0, 1, 4, 5};
  for(Eigen::Index k = 0; k < 4; ++k) T.emplace_back(map[B.F(k, 0)], map[B.F(k, 1)], map[B.F(k, 2)]);
  return make_arrays(V, T);
}

// ---------------------------------------------------------------------------
// Shared data (../shared/data, DEM_DATA_DIR)

/// The shared data folder: the environment variable DEM_TEST_DATA_DIR if set
/// (e.g. `DEM_TEST_DATA_DIR=/nonexistent ctest` checks the suite without the
/// data, no rebuild needed), else DEM_DATA_DIR (CMake's DEM_SHARED_DATA_DIR).
inline std::string data_dir()
{
  if(const char* dir = std::getenv("DEM_TEST_DATA_DIR")) return dir;
#ifdef DEM_DATA_DIR
  return DEM_DATA_DIR;
#else
  return "";
#endif
}

inline std::string data_path(const std::string& file) { return data_dir() + "/" + file; }

inline bool data_available(const std::string& file)
{
  std::ifstream in(data_path(file));
  return bool(in);
}

/// True when a program with a shared-mesh part is asked to run that part only
/// (`<program> --shared`, registered as the ctest test `<program>_shared` with
/// the label `shared_data`, see CMakeLists.txt). Without the argument such a
/// program runs on generated meshes only.
inline bool shared_part_requested(int argc, char** argv)
{
  return argc > 1 && std::string(argv[1]) == "--shared";
}

/// The exit code of a shared-mesh part: skipped (77) when `probe` is absent
/// from the data folder, else what `run()` returns.
template <class Run>
int run_shared_part(const std::string& probe, Run run)
{
  if(!data_available(probe)) {
    std::cout << "shared data not found in '" << data_dir() << "' (" << probe << "): skipped" << std::endl;
    return skip_code;
  }
  return run();
}

/// Reads `<DEM_DATA_DIR>/<name>.off`; false if absent or unreadable.
inline bool load_shared_mesh(const std::string& name, Mesh& m)
{
  m.clear();
  const std::string path = data_path(name + ".off");
  if(!data_available(name + ".off")) return false;
  if(!CGAL::IO::read_polygon_mesh(path, m) || m.is_empty()) {
    std::cerr << "could not read " << path << std::endl;
    return false;
  }
  return true;
}

/// One value per line (`#` comments); empty if absent.
inline std::vector<double> read_values(const std::string& path)
{
  std::vector<double> v;
  std::ifstream in(path);
  std::string line;
  while(std::getline(in, line)) {
    const auto hash = line.find('#');
    if(hash != std::string::npos) line.erase(hash);
    std::istringstream s(line);
    double x;
    while(s >> x) v.push_back(x);
  }
  return v;
}

/// The population of a shared mesh (`<name>.population.txt`), one value per face; empty if absent.
inline std::vector<double> read_population(const std::string& name)
{
  return read_values(data_path(name + ".population.txt"));
}

// ---------------------------------------------------------------------------
// Output checks shared by the method tests.

/// A vertex point map filled with a sentinel: `untouched()` then tells that a
/// function that threw wrote nothing (no partial output).
inline const Point& output_sentinel() { static const Point p(7, 7, 7); return p; }

inline Mesh::Property_map<vertex_descriptor, Point> output_map(Mesh& m, const std::string& name)
{
  auto out = m.add_property_map<vertex_descriptor, Point>(name, output_sentinel()).first;
  for(vertex_descriptor v : vertices(m)) put(out, v, output_sentinel());
  return out;
}

inline bool untouched(const Mesh& m, const Mesh::Property_map<vertex_descriptor, Point>& out)
{
  for(vertex_descriptor v : vertices(m))
    if(get(out, v) != output_sentinel()) return false;
  return true;
}

/// max | |p| - 1 | over the mapped vertices
inline double max_sphere_deviation(const Mesh& m, const Mesh::Property_map<vertex_descriptor, Point>& out)
{
  double d = 0;
  for(vertex_descriptor v : vertices(m)) {
    const Point& p = get(out, v);
    d = std::max(d, std::abs(std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z()) - 1));
  }
  return d;
}

/// max |x^2/a^2 + y^2/b^2 + z^2/c^2 - 1| over the mapped vertices
inline double max_level_deviation(const Mesh& m, const Mesh::Property_map<vertex_descriptor, Point>& out,
                                  const std::array<double, 3>& r)
{
  double d = 0;
  for(vertex_descriptor v : vertices(m)) {
    const Point& p = get(out, v);
    d = std::max(d, std::abs(p.x() * p.x() / (r[0] * r[0]) + p.y() * p.y() / (r[1] * r[1]) +
                             p.z() * p.z() / (r[2] * r[2]) - 1));
  }
  return d;
}

} // namespace dem_test

#endif // DEM_TEST_MESHES_H
