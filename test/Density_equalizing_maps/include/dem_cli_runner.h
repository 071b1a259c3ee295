// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Test support for the programs that run the dem tool: a temporary folder,
// small text-mesh writers, and a runner that captures the exit status and
// stderr, with a time limit (coreutils `timeout`). No CGAL: cheap to compile.

#ifndef DEM_CLI_RUNNER_H
#define DEM_CLI_RUNNER_H

#include <sys/wait.h> // WIFEXITED
#include <unistd.h>   // getpid

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#ifndef DEM_CLI
#error "DEM_CLI must name the dem executable"
#endif

namespace dem_cli_test {

namespace fs = std::filesystem;
typedef std::array<double, 3> P3;
typedef std::array<int, 3> Tri;

struct Soup { std::vector<P3> V; std::vector<Tri> T; };

inline int& failures() { static int n = 0; return n; }
inline bool check(bool ok, const std::string& what)
{
  if(!ok) { ++failures(); std::cerr << "FAILED: " << what << std::endl; }
  return ok;
}
inline bool contains(const std::string& s, const std::string& sub) { return s.find(sub) != std::string::npos; }

/// A fresh folder under the system temporary folder, removed at exit.
struct Temporary_folder
{
  fs::path path;
  explicit Temporary_folder(const std::string& name)
    : path(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid())))
  { fs::remove_all(path); fs::create_directories(path); }
  ~Temporary_folder() { std::error_code ec; fs::remove_all(path, ec); }
  std::string operator/(const std::string& file) const { return (path / file).string(); }
};

/// Octahedron subdivided `levels` times and pushed to the unit sphere, outward oriented.
inline Soup sphere_soup(int levels)
{
  Soup s;
  s.V = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.T = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for(int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto m = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if(it != mid.end()) return it->second;
      P3 p = {(s.V[a][0] + s.V[b][0]) / 2, (s.V[a][1] + s.V[b][1]) / 2, (s.V[a][2] + s.V[b][2]) / 2};
      const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      s.V.push_back({p[0] / n, p[1] / n, p[2] / n});
      return mid[key] = int(s.V.size()) - 1;
    };
    std::vector<Tri> T;
    for(const Tri& f : s.T) {
      const int a = m(f[0], f[1]), b = m(f[1], f[2]), c = m(f[2], f[0]);
      T.push_back({f[0], a, c}); T.push_back({f[1], b, a}); T.push_back({f[2], c, b}); T.push_back({a, b, c});
    }
    s.T = T;
  }
  for(P3& p : s.V) p[0] *= 1.5; // not round
  return s;
}

inline Soup torus_soup(double R, double r, int nu, int nv)
{
  Soup s;
  const double pi = std::acos(-1.);
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
      s.V.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for(int i = 0; i < nu; ++i)
    for(int j = 0; j < nv; ++j) {
      s.T.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.T.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

inline std::string off_text(const Soup& s)
{
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n" << s.V.size() << " " << s.T.size() << " 0\n";
  for(const P3& v : s.V) out << v[0] << " " << v[1] << " " << v[2] << "\n";
  for(const Tri& t : s.T) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return out.str();
}

inline std::string obj_text(const Soup& s)
{
  std::ostringstream out;
  out.precision(17);
  for(const P3& v : s.V) out << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
  for(const Tri& t : s.T) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return out.str();
}

inline std::string ply_ascii_text(const Soup& s)
{
  std::ostringstream out;
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex " << s.V.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << s.T.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for(const P3& v : s.V) out << v[0] << " " << v[1] << " " << v[2] << "\n";
  for(const Tri& t : s.T) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return out.str();
}

template <class T> void put_bytes(std::string& s, T v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

/// Binary little-endian PLY (float coordinates, int indices); little-endian host assumed.
inline std::string ply_binary_text(const Soup& s)
{
  std::ostringstream head;
  head << "ply\nformat binary_little_endian 1.0\nelement vertex " << s.V.size()
       << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << s.T.size()
       << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string out = head.str();
  for(const P3& v : s.V) for(double c : v) put_bytes(out, float(c));
  for(const Tri& t : s.T) { put_bytes(out, (unsigned char)3); for(int i : t) put_bytes(out, std::int32_t(i)); }
  return out;
}

/// Binary STL (the soup's faces, unwelded as STL is).
inline std::string stl_binary_text(const Soup& s)
{
  std::string out(80, ' ');
  put_bytes(out, std::uint32_t(s.T.size()));
  for(const Tri& t : s.T) {
    for(int c = 0; c < 3; ++c) put_bytes(out, 0.f);
    for(int i : t) for(double c : s.V[i]) put_bytes(out, float(c));
    put_bytes(out, std::uint16_t(0));
  }
  return out;
}

inline std::string stl_ascii_text(const Soup& s)
{
  std::ostringstream out;
  out.precision(9);
  out << "solid s\n";
  for(const Tri& t : s.T) {
    out << "facet normal 0 0 0\nouter loop\n";
    for(int i : t) out << "vertex " << s.V[i][0] << " " << s.V[i][1] << " " << s.V[i][2] << "\n";
    out << "endloop\nendfacet\n";
  }
  out << "endsolid s\n";
  return out.str();
}

inline std::string write_file(const std::string& path, const std::string& content)
{
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

inline std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Result
{
  int code = -1;     // exit status; -1 if killed by a signal
  bool timed_out = false;
  std::string out, err;
};

/// Runs `dem ARGS` in `folder` with a time limit, capturing stdout and stderr;
/// `environment` is a prefix of the command (e.g. "env -u OPENBLAS_NUM_THREADS").
inline Result run_dem(const Temporary_folder& folder, const std::string& args, int seconds = 120,
                      const std::string& environment = "")
{
  const std::string out = folder / "stdout.txt", err = folder / "stderr.txt";
  const std::string cmd = environment + (environment.empty() ? "" : " ") + "timeout -s KILL " +
                          std::to_string(seconds) + " \"" + std::string(DEM_CLI) + "\" " + args + " > \"" + out +
                          "\" 2> \"" + err + "\"";
  const int status = std::system(cmd.c_str());
  Result r;
  if(status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
  r.timed_out = r.code == 137 || (status != -1 && WIFSIGNALED(status));
  if(r.code == 137) r.code = -1; // the shell reports the KILL as 128 + 9
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline std::string quoted(const std::string& s) { return "\"" + s + "\""; }

} // namespace dem_cli_test

#endif // DEM_CLI_RUNNER_H
