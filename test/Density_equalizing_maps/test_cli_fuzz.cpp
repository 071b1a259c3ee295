// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Fuzzing of the dem tool's readers (issue 15): random and mutated OFF, OBJ,
// PLY (ascii and binary) and STL (ascii and binary) meshes, population,
// landmark and cut-edge files. Every run must end by itself (time limit),
// without a crash, with exit 0 (the mutation happened to be valid), 3 (with
// a "dem: invalid input" message) or 4 (a valid input the method could not
// map, with a message). Bounded by time: DEM_FUZZ_SECONDS (default 60).
// Seeded: DEM_FUZZ_SEED (default 15) reproduces a run; failing inputs are
// kept in the printed folder.

#include "dem_cli_runner.h"

#include <chrono>
#include <random>

using namespace dem_cli_test;

namespace {

typedef std::mt19937 Rng;

int pick(Rng& rng, int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }

/// Tokens that break readers: non-finite and huge numbers, bad indices, junk.
const char* nasty[] = {"nan", "-nan", "inf", "-inf", "1e999", "-1e999", "1e-999", "-1", "0", "999999999",
                       "18446744073709551616", "4294967295", "2147483648", "0x10", "1.5", "", "#", "3", "-0",
                       "abc", "\t", "1e308", "4.9e-324", "00000000000000000000001", "v", "f", "//", "1//1"};

/// One random edit of a text or binary file.
std::string mutate(std::string s, Rng& rng)
{
  if(s.empty()) return "x";
  const int n = int(s.size());
  const int at = pick(rng, n);
  switch(pick(rng, 9)) {
    case 0: s[at] = char(pick(rng, 256)); break;                                     // flip a byte
    case 1: s.erase(at, 1 + pick(rng, std::min(64, n - at))); break;                 // delete a run
    case 2: s.insert(at, s.substr(pick(rng, n), 1 + pick(rng, 32))); break;          // duplicate a run
    case 3: s.resize(at); break;                                                     // truncate
    case 4: {                                                                        // replace a token
      std::size_t b = s.find_first_of(" \n", at);
      if(b == std::string::npos) b = s.size();
      std::size_t a = s.find_last_of(" \n", at == 0 ? 0 : at - 1);
      a = (a == std::string::npos) ? 0 : a + 1;
      if(a <= b) s.replace(a, b - a, nasty[pick(rng, int(sizeof nasty / sizeof *nasty))]);
      break;
    }
    case 5: s.insert(at, std::string(" ") + nasty[pick(rng, int(sizeof nasty / sizeof *nasty))] + " "); break;
    case 6: {                                                                        // swap two lines
      const std::size_t a = s.find('\n', at), b = s.find('\n', pick(rng, n));
      if(a != std::string::npos && b != std::string::npos && a != b) std::swap(s[a], s[b]);
      break;
    }
    case 7: s += std::string(1 + pick(rng, 16), char(pick(rng, 256))); break;       // garbage at the end
    default: {                                                                       // a digit changed
      const std::size_t d = s.find_first_of("0123456789", at);
      if(d != std::string::npos) s[d] = char('0' + pick(rng, 10));
    }
  }
  return s;
}

std::string random_bytes(Rng& rng, const std::string& prefix)
{
  std::string s = prefix;
  const int n = pick(rng, 400);
  for(int i = 0; i < n; ++i) s += char(pick(rng, 3) ? " 0123456789.-\nenaif"[pick(rng, 19)] : char(pick(rng, 256)));
  return s;
}

struct Case { std::string method, extension, content, sidecar_option, sidecar_content, extra; };

struct Seeds
{
  std::vector<std::pair<std::string, std::string> > meshes; // extension, content
  std::string sphere_off, torus_off, population, landmarks, cut_edges;
};

Seeds make_seeds()
{
  Seeds s;
  const Soup sphere = sphere_soup(1); // 18 vertices, 32 faces
  s.meshes = {{".off", off_text(sphere)}, {".obj", obj_text(sphere)}, {".ply", ply_ascii_text(sphere)},
              {".ply", ply_binary_text(sphere)}, {".stl", stl_ascii_text(sphere)}, {".stl", stl_binary_text(sphere)}};
  s.sphere_off = off_text(sphere);
  const int nu = 12, nv = 6;
  s.torus_off = off_text(torus_soup(3, 1, nu, nv));
  for(std::size_t k = 0; k < sphere.T.size(); ++k) s.population += std::to_string(1 + (k % 3)) + "\n";
  s.landmarks = "# vertex x y z\n0 1 0 0\n1 -1 0 0\n4 0 0 1\n";
  for(int i = 0; i < nu; ++i) s.cut_edges += std::to_string(i * nv) + " " + std::to_string(((i + 1) % nu) * nv) + "\n";
  for(int j = 0; j < nv; ++j) s.cut_edges += std::to_string(j) + " " + std::to_string((j + 1) % nv) + "\n";
  return s;
}

Case next_case(const Seeds& seeds, Rng& rng)
{
  Case c;
  const int kind = pick(rng, 10);
  if(kind < 6) { // a mesh reader
    const auto& m = seeds.meshes[std::size_t(pick(rng, int(seeds.meshes.size())))];
    c.method = "spherical-conformal";
    c.extension = m.first;
    c.content = m.second;
    const int edits = 1 + pick(rng, 4);
    for(int e = 0; e < edits; ++e) c.content = mutate(c.content, rng);
  } else if(kind == 6) { // random bytes behind a plausible header
    const char* heads[] = {"OFF\n", "ply\nformat ascii 1.0\n", "solid x\n", "v ", ""};
    const char* exts[] = {".off", ".ply", ".stl", ".obj", ".off"};
    const int h = pick(rng, 5);
    c.method = "spherical-conformal";
    c.extension = exts[h];
    c.content = random_bytes(rng, heads[h]);
  } else { // a sidecar file with a valid mesh
    c.extension = ".off";
    const int which = kind - 7;
    c.content = which == 2 ? seeds.torus_off : seeds.sphere_off;
    c.method = which == 0 ? "sdem" : which == 1 ? "lsdem" : "toroidal-parameterization";
    c.sidecar_option = which == 0 ? "--population" : which == 1 ? "--landmarks" : "--cut-edges";
    c.sidecar_content = which == 0 ? seeds.population : which == 1 ? seeds.landmarks : seeds.cut_edges;
    const int edits = 1 + pick(rng, 3);
    for(int e = 0; e < edits; ++e) c.sidecar_content = mutate(c.sidecar_content, rng);
    c.extra = which == 2 ? " --torus 3 1 --max-iterations 3" : " --max-iterations 3";
  }
  return c;
}

} // namespace

int main()
{
  const double budget = std::getenv("DEM_FUZZ_SECONDS") ? std::atof(std::getenv("DEM_FUZZ_SECONDS")) : 60.;
  const unsigned seed = std::getenv("DEM_FUZZ_SEED") ? unsigned(std::atoi(std::getenv("DEM_FUZZ_SEED"))) : 15u;
  const Temporary_folder dir("dem_test_cli_fuzz");
  const fs::path kept = fs::temp_directory_path() / ("dem_fuzz_failures_" + std::to_string(::getpid()));
  Rng rng(seed);
  const Seeds seeds = make_seeds();
  const auto start = std::chrono::steady_clock::now();
  std::size_t runs = 0, valid = 0, refused = 0, unmapped = 0;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  while(elapsed() < budget) {
    const Case c = next_case(seeds, rng);
    const std::string mesh = write_file(dir / ("input" + c.extension), c.content);
    std::string args = c.method + " " + quoted(mesh) + c.extra + " --quiet";
    if(!c.sidecar_option.empty())
      args += " " + c.sidecar_option + " " + quoted(write_file(dir / "sidecar.txt", c.sidecar_content));
    const Result r = run_dem(dir, args, 30);
    ++runs;
    const bool message = contains(r.err, "dem: ");
    const bool ok = !r.timed_out && ((r.code == 0) || ((r.code == 3 || r.code == 4) && message));
    if(r.code == 0) ++valid;
    else if(r.code == 3) ++refused;
    else if(r.code == 4) ++unmapped;
    if(!ok) {
      fs::create_directories(kept);
      const std::string stem = (kept / ("case" + std::to_string(runs))).string();
      write_file(stem + c.extension, c.content);
      if(!c.sidecar_option.empty()) write_file(stem + ".sidecar.txt", c.sidecar_content);
      check(false, "run " + std::to_string(runs) + ": dem " + args + " -> " +
                     (r.timed_out ? std::string("killed or timed out") : "exit " + std::to_string(r.code)) +
                     ", stderr: " + r.err.substr(0, 300) + " (input kept as " + stem + c.extension + ")");
    }
  }
  std::cout << "test_cli_fuzz: seed " << seed << ", " << runs << " runs in " << elapsed() << " s: " << valid
            << " valid (exit 0), " << refused << " refused (exit 3), " << unmapped << " not mapped (exit 4)"
            << std::endl;
  check(runs >= 20, "the fuzzer ran at least 20 cases");
  if(failures() == 0) { std::cout << "test_cli_fuzz: all checks passed" << std::endl; return 0; }
  std::cerr << "test_cli_fuzz: " << failures() << " check(s) failed" << std::endl;
  return 1;
}
