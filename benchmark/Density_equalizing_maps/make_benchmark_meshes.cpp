// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Writes the large synthetic benchmark meshes (OFF) used by
// benchmark/run_benchmarks.py:
//
//   bumpy_sphere_100k.off  genus 0: geodesic icosphere of frequency 71
//                          (20 * 71^2 = 100,820 faces, 50,412 vertices), every
//                          vertex moved radially onto a bumpy ellipsoid
//                          (a star-shaped surface, hence an embedding)
//   bumpy_torus_100k.off   genus 1: a 316 x 158 grid on a torus R = 3, r = 1
//                          with radial bumps on the tube (99,856 faces)
//   torus_100k.off         the same grid on the torus itself (no bumps): TDEM's
//                          input lies on the torus
//   bumpy_torus_100k.population.txt
//                          one value per face of either torus, exp(cos u cos v)
//                          at the face's grid centre (u around the axis, v
//                          around the tube): a smooth population of ratio e^2
//                          for TDEM
//
// usage: make_benchmark_meshes OUTPUT_DIR [frequency=71]
//
// Another frequency scales both meshes (the names stay): the sphere has
// 20 f^2 faces, the torus grid is (316 f / 71) x (158 f / 71), so that 224
// gives about 1M faces each and 448 about 4M.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

typedef std::array<double, 3> P3;
typedef std::array<int, 3> Tri;

P3 normalized(const P3& p)
{
  const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return {p[0] / n, p[1] / n, p[2] / n};
}

/// Geodesic icosphere: each icosahedron face split into n^2 triangles, points
/// projected on the unit sphere; vertices on shared edges are shared.
void geodesic_icosphere(int n, std::vector<P3>& V, std::vector<Tri>& T)
{
  const double t = (1 + std::sqrt(5.)) / 2;
  const std::vector<P3> ico = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const std::vector<Tri> faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  // A lattice point of face (a,b,c) is a + (i/n)(b-a) + (j/n)(c-a). Points on
  // an icosahedron edge or corner are keyed by their barycentric coordinates
  // over the global corner ids so that neighbouring faces share them.
  std::map<std::array<long, 6>, int> index;
  V.clear();
  T.clear();
  for(const Tri& f : faces) {
    std::vector<std::vector<int>> id(std::size_t(n + 1));
    for(int i = 0; i <= n; ++i) {
      id[std::size_t(i)].resize(std::size_t(n + 1 - i));
      for(int j = 0; j + i <= n; ++j) {
        const int w[3] = {n - i - j, i, j};
        // key: the (corner, weight) pairs of the non-zero weights, sorted by corner id, padded
        std::vector<std::pair<int, int>> cw;
        for(int c = 0; c < 3; ++c)
          if(w[c] != 0) cw.emplace_back(f[std::size_t(c)], w[c]);
        std::sort(cw.begin(), cw.end());
        std::array<long, 6> key{{-1, 0, -1, 0, -1, 0}};
        for(std::size_t c = 0; c < cw.size(); ++c) { key[2 * c] = cw[c].first; key[2 * c + 1] = cw[c].second; }
        auto it = index.find(key);
        if(it == index.end()) {
          P3 p{0, 0, 0};
          for(int c = 0; c < 3; ++c)
            for(int d = 0; d < 3; ++d) p[std::size_t(d)] += w[c] * ico[std::size_t(f[std::size_t(c)])][std::size_t(d)];
          V.push_back(normalized(p));
          it = index.emplace(key, int(V.size()) - 1).first;
        }
        id[std::size_t(i)][std::size_t(j)] = it->second;
      }
    }
    for(int i = 0; i < n; ++i)
      for(int j = 0; j + i < n; ++j) {
        T.push_back({id[i][j], id[i + 1][j], id[i][j + 1]});
        if(i + j + 1 < n) T.push_back({id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]});
      }
  }
}

bool write_off(const std::string& file, const std::vector<P3>& V, const std::vector<Tri>& T)
{
  std::ofstream out(file);
  if(!out) return false;
  out.precision(17);
  out << "OFF\n" << V.size() << " " << T.size() << " 0\n";
  for(const P3& p : V) out << p[0] << " " << p[1] << " " << p[2] << "\n";
  for(const Tri& t : T) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return bool(out);
}

} // namespace

int main(int argc, char** argv)
{
  if(argc < 2) {
    std::cerr << "usage: make_benchmark_meshes OUTPUT_DIR [frequency=71]\n";
    return 2;
  }
  const std::string dir = argv[1];
  const int n = argc > 2 ? std::atoi(argv[2]) : 71;
  if(n < 1) { std::cerr << "frequency must be positive\n"; return 2; }

  // genus 0: bumpy ellipsoid, radius r(d) * (1.5 d_x, 1.0 d_y, 0.7 d_z)
  {
    std::vector<P3> V;
    std::vector<Tri> T;
    geodesic_icosphere(n, V, T);
    for(P3& d : V) {
      const double theta = std::acos(std::max(-1., std::min(1., d[2]))), phi = std::atan2(d[1], d[0]);
      const double r = 1 + 0.12 * std::sin(5 * theta) * std::cos(4 * phi) + 0.05 * std::cos(9 * theta);
      d = {1.5 * r * d[0], 1.0 * r * d[1], 0.7 * r * d[2]};
    }
    const std::string f = dir + "/bumpy_sphere_100k.off";
    if(!write_off(f, V, T)) { std::cerr << "cannot write " << f << "\n"; return 3; }
    std::cout << f << ": " << V.size() << " vertices, " << T.size() << " faces\n";
  }
  // genus 1: bumpy torus
  {
    const int nv = std::max(3, int(std::lround(158. * n / 71))), nu = 2 * nv;
    const double R = 3, pi = std::acos(-1.);
    std::vector<Tri> T;
    auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
    for(int i = 0; i < nu; ++i)
      for(int j = 0; j < nv; ++j) {
        T.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        T.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    for(const double bump : {0.15, 0.}) {
      std::vector<P3> V;
      for(int i = 0; i < nu; ++i)
        for(int j = 0; j < nv; ++j) {
          const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
          const double r = 1 + bump * std::sin(3 * u) * std::cos(2 * v);
          V.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
        }
      const std::string f = dir + (bump > 0 ? "/bumpy_torus_100k.off" : "/torus_100k.off");
      if(!write_off(f, V, T)) { std::cerr << "cannot write " << f << "\n"; return 3; }
      std::cout << f << ": " << V.size() << " vertices, " << T.size() << " faces\n";
    }
    const std::string fp = dir + "/bumpy_torus_100k.population.txt";
    std::ofstream pop(fp);
    pop.precision(17);
    for(int i = 0; i < nu; ++i)
      for(int j = 0; j < nv; ++j) {
        // the two triangles of grid cell (i, j), centred at (i + 1/2, j + 1/2)
        const double u = 2 * pi * (i + 0.5) / nu, v = 2 * pi * (j + 0.5) / nv;
        const double value = std::exp(std::cos(u) * std::cos(v));
        pop << value << "\n" << value << "\n";
      }
    if(!pop) { std::cerr << "cannot write " << fp << "\n"; return 3; }
    std::cout << fp << ": one value per face, exp(cos u cos v)\n";
  }
  return 0;
}
