// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MESH_ARRAYS_H
#define CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MESH_ARRAYS_H

// The numerical core works on index arrays (positions n x 3, triangles m x 3),
// extracted once from the user's FaceListGraph. This keeps the algorithms
// free of graph templates (one instantiation, fast builds) and gives every
// operator contiguous data.

#include <CGAL/Density_equalizing_maps/Map_report.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Density_equalizing_maps {
namespace internal {

using Matrix = Eigen::MatrixXd;
using Index_matrix = Eigen::Matrix<int, Eigen::Dynamic, 3>;
using Vector = Eigen::VectorXd;
using Complex_vector = Eigen::VectorXcd;

/// A triangle mesh as arrays. `vertices[i]` / `faces[k]` are the descriptors
/// of row i of `X` / row k of `F`, in the iteration order of the graph.
template <class TriangleMesh>
struct Mesh_arrays
{
  typedef typename boost::graph_traits<TriangleMesh>::vertex_descriptor vertex_descriptor;
  typedef typename boost::graph_traits<TriangleMesh>::face_descriptor face_descriptor;
  Matrix X;
  Index_matrix F;
  std::vector<vertex_descriptor> vertices;
  std::vector<face_descriptor> faces;
  /// X = scale * (the input positions), a power of two (normalize_scale())
  double scale = 1;
  /// the positions in the units of the input (where an output lives in them)
  Matrix input_positions() const { return X / scale; }
};

/// The power of two 2^-e that brings the largest side of the bounding box of
/// the finite rows of X into [1/2, 1); 1 if there is none (no finite row, or
/// all points equal: validation reports them).
inline double unit_scale(const Matrix& X)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for(Eigen::Index i = 0; i < X.rows(); ++i)
    if(X.row(i).allFinite()) {
      lo = lo.cwiseMin(X.row(i).transpose());
      hi = hi.cwiseMax(X.row(i).transpose());
    }
  // half sides: hi - lo may overflow where hi / 2 - lo / 2 does not
  double half_side = 0;
  for(int c = 0; c < 3; ++c)
    if(hi[c] >= lo[c]) half_side = std::max(half_side, 0.5 * hi[c] - 0.5 * lo[c]);
  if(!(half_side > 0) || !std::isfinite(half_side)) return 1;
  int e = 0;
  std::frexp(half_side, &e); // half_side = m 2^e with m in [1/2, 1)
  return std::ldexp(1., -(e + 1));
}

/// Scales the positions by unit_scale(): the numerics work on a mesh of size
/// about 1 whatever the units of the input (coordinates near 1e+-100 have
/// squared lengths and areas that overflow or underflow). A power of two
/// changes only the exponents, so the scaled computation rounds exactly as the
/// unscaled one would: the results are the same up to the scale, bit for bit.
template <class TriangleMesh>
void normalize_scale(Mesh_arrays<TriangleMesh>& a)
{
  a.scale = unit_scale(a.X);
  if(a.scale != 1) a.X *= a.scale;
}

/// Extracts positions and triangles. Throws `Invalid_input` if a face is not a
/// triangle; all other checks are in validation.h.
template <class TriangleMesh, class VertexPointMap, class VertexIndexMap>
Mesh_arrays<TriangleMesh> to_arrays(const TriangleMesh& tm, VertexPointMap vpm, VertexIndexMap vim)
{
  Mesh_arrays<TriangleMesh> a;
  const std::size_t nv = static_cast<std::size_t>(num_vertices(tm));
  const std::size_t nf = static_cast<std::size_t>(num_faces(tm));
  a.X.resize(nv, 3);
  a.F.resize(nf, 3);
  a.vertices.resize(nv);
  // The index map must number the vertices 0..n-1, and num_vertices() /
  // num_faces() must count the iterated elements. Neither holds for a
  // Surface_mesh with removed elements before collect_garbage() (the counts
  // include the removed slots): rows would stay uninitialized. CGAL only
  // asserts the index map in debug builds, so check here.
  const std::string garbage_hint = "; for a Surface_mesh with removed elements call collect_garbage() first";
  std::vector<char> seen(nv, 0);
  std::size_t iterated = 0;
  for(auto v : vertices(tm)) {
    const std::size_t i = static_cast<std::size_t>(get(vim, v));
    if(i >= nv || seen[i])
      throw Invalid_input("the vertex index map does not number the vertices 0.." + std::to_string(nv) +
                          " - 1 (index " + std::to_string(i) + ")" + garbage_hint);
    seen[i] = 1;
    ++iterated;
    const auto& p = get(vpm, v);
    a.X(i, 0) = CGAL::to_double(p.x());
    a.X(i, 1) = CGAL::to_double(p.y());
    a.X(i, 2) = CGAL::to_double(p.z());
    a.vertices[i] = v;
  }
  if(iterated != nv)
    throw Invalid_input("the mesh has " + std::to_string(iterated) + " vertices but num_vertices() is " +
                        std::to_string(nv) + garbage_hint);
  a.faces.reserve(nf);
  std::size_t k = 0;
  for(auto f : faces(tm)) {
    if(k == nf) break; // reported below
    int c = 0;
    for(auto v : vertices_around_face(halfedge(f, tm), tm)) {
      if(c == 3) break;
      a.F(k, c++) = static_cast<int>(get(vim, v));
    }
    if(c != 3 || degree(f, tm) != 3)
      throw Invalid_input("not a pure triangle mesh: face " + std::to_string(k) + " has " +
                          std::to_string(degree(f, tm)) + " vertices");
    a.faces.push_back(f);
    ++k;
  }
  if(k != nf || std::size_t(std::distance(faces(tm).begin(), faces(tm).end())) != nf)
    throw Invalid_input("the number of faces does not match num_faces() = " + std::to_string(nf) + garbage_hint);
  return a;
}

/// Writes the rows of `Y` (n x 3) to a vertex property map of points.
template <class TriangleMesh, class VertexPointOutMap>
void write_points(const Mesh_arrays<TriangleMesh>& a, const Matrix& Y, VertexPointOutMap out)
{
  typedef typename boost::property_traits<VertexPointOutMap>::value_type Point;
  for(std::size_t i = 0; i < a.vertices.size(); ++i)
    put(out, a.vertices[i], Point(Y(i, 0), Y(i, 1), Y(i, 2)));
}

/// Reads a vertex property map of points into an n x 3 matrix.
template <class TriangleMesh, class VertexPointMap>
Matrix read_points(const Mesh_arrays<TriangleMesh>& a, VertexPointMap pm)
{
  Matrix Y(a.vertices.size(), 3);
  for(std::size_t i = 0; i < a.vertices.size(); ++i) {
    const auto& p = get(pm, a.vertices[i]);
    Y(i, 0) = CGAL::to_double(p.x());
    Y(i, 1) = CGAL::to_double(p.y());
    Y(i, 2) = CGAL::to_double(p.z());
  }
  return Y;
}

/// Reads a face property map of scalars into a vector (face order of `a`).
template <class TriangleMesh, class FaceScalarMap>
Vector read_face_values(const Mesh_arrays<TriangleMesh>& a, FaceScalarMap fm)
{
  Vector v(a.faces.size());
  for(std::size_t k = 0; k < a.faces.size(); ++k) v[k] = CGAL::to_double(get(fm, a.faces[k]));
  return v;
}

/// Reads a vertex property map of scalars into a vector.
template <class TriangleMesh, class VertexScalarMap>
Vector read_vertex_values(const Mesh_arrays<TriangleMesh>& a, VertexScalarMap vm)
{
  Vector v(a.vertices.size());
  for(std::size_t i = 0; i < a.vertices.size(); ++i) v[i] = CGAL::to_double(get(vm, a.vertices[i]));
  return v;
}

} // namespace internal
} // namespace Density_equalizing_maps
} // namespace CGAL

#endif // CGAL_DENSITY_EQUALIZING_MAPS_INTERNAL_MESH_ARRAYS_H
