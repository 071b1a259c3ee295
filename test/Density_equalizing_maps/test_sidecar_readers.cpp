// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The sidecar file readers (IO/sidecar_files.h): accepted syntax (comments,
// blank lines, CRLF, blanks around '='), every rejection with the line number
// in the message, the file-name overloads on files the test writes; with
// `--shared` (ctest test_sidecar_readers_shared) the shared data files.

#include <CGAL/Density_equalizing_maps/IO/sidecar_files.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace IO = CGAL::Density_equalizing_maps::IO;
using CGAL::Density_equalizing_maps::Invalid_input;

namespace {

int failures = 0;
bool check(bool ok, const std::string& what)
{
  if(!ok) { ++failures; std::cerr << "FAILED: " << what << std::endl; }
  return ok;
}

/// Runs f, expects Invalid_input whose message contains `needle`.
template <class F>
void expect_error(F f, const std::string& needle, const std::string& what)
{
  try {
    f();
    check(false, what + ": no exception");
  } catch(const Invalid_input& e) {
    check(std::string(e.what()).find(needle) != std::string::npos,
          what + ": message \"" + e.what() + "\" should contain \"" + needle + "\"");
  }
}

} // namespace

int shared_part();

int main(int argc, char** argv)
{
  if(argc > 1 && std::string(argv[1]) == "--shared") return shared_part();
  // --- face values
  {
    std::istringstream in("# population\n1.5\n\n  2 # two\r\n3e-2\n");
    const auto v = IO::read_face_values(in, 3);
    check(v.size() == 3 && v[0] == 1.5 && v[1] == 2 && v[2] == 3e-2, "face values with comments, blanks, CRLF");
    expect_error([] { std::istringstream s("1\n2\nabc\n"); IO::read_face_values(s, 3, "pop.txt"); },
                 "pop.txt line 3", "malformed value");
    expect_error([] { std::istringstream s("1\n2 3\n"); IO::read_face_values(s, 2); }, "line 2", "two values on a line");
    expect_error([] { std::istringstream s("1\n0\n"); IO::read_face_values(s, 2); }, "line 2", "zero value");
    expect_error([] { std::istringstream s("1\n-4\n"); IO::read_face_values(s, 2); }, "line 2", "negative value");
    expect_error([] { std::istringstream s("nan\n1\n"); IO::read_face_values(s, 2); }, "line 1", "NaN value");
    expect_error([] { std::istringstream s("inf\n1\n"); IO::read_face_values(s, 2); }, "line 1", "infinite value");
    expect_error([] { std::istringstream s("1.0x\n1\n"); IO::read_face_values(s, 2); }, "line 1", "trailing garbage");
    expect_error([] { std::istringstream s("1\n2\n"); IO::read_face_values(s, 3); }, "2 values for 3 faces",
                 "too few values");
    expect_error([] { std::istringstream s("1\n2\n3\n4\n"); IO::read_face_values(s, 3); }, "4 values for 3 faces",
                 "too many values");
    expect_error([] { IO::read_face_values(std::string("/nonexistent/dem.pop"), 3); }, "cannot open", "missing file");
  }

  // --- landmarks
  {
    std::istringstream in("# vertex x y z\n\n3 0 0 1\n  7 1 0 0   # equator\n0 -0.6 0.8 0\n");
    const auto l = IO::read_landmarks(in, 10);
    check(l.size() == 3, "three landmarks");
    check(l.size() == 3 && l[0].vertex == 3 && l[0].target[2] == 1 && l[1].vertex == 7 && l[1].line == 4 &&
              l[2].target[0] == -0.6,
          "landmark values");
    expect_error([] { std::istringstream s("1 0 0 1\n2 0 1\n"); IO::read_landmarks(s, 10, "lm.txt"); },
                 "lm.txt line 2", "three fields");
    expect_error([] { std::istringstream s("1 0 0 1\n-2 0 1 0\n"); IO::read_landmarks(s, 10); }, "line 2",
                 "negative index");
    expect_error([] { std::istringstream s("1.5 0 0 1\n"); IO::read_landmarks(s, 10); }, "line 1", "fractional index");
    expect_error([] { std::istringstream s("1 0 0 1\n\n10 0 1 0\n"); IO::read_landmarks(s, 10); }, "line 3",
                 "index out of range (line)");
    expect_error([] { std::istringstream s("10 0 1 0\n"); IO::read_landmarks(s, 10); }, "out of range",
                 "index out of range (message)");
    expect_error([] { std::istringstream s("1 0 0 1\n1 0 1 0\n"); IO::read_landmarks(s, 10); }, "already has",
                 "repeated vertex");
    expect_error([] { std::istringstream s("1 0 nan 1\n"); IO::read_landmarks(s, 10); }, "line 1", "NaN target");
    expect_error([] { std::istringstream s("# nothing\n\n"); IO::read_landmarks(s, 10); }, "no landmark", "empty");
  }

  // --- vertex pairs
  {
    std::istringstream in("# cut\n0 5\n5 9 # end\n");
    const auto p = IO::read_vertex_pairs(in, 10);
    check(p.size() == 2 && p[0].first == 0 && p[0].second == 5 && p[1].second == 9, "vertex pairs");
    expect_error([] { std::istringstream s("0 5\n5\n"); IO::read_vertex_pairs(s, 10); }, "line 2", "one index");
    expect_error([] { std::istringstream s("0 5\n5 12\n"); IO::read_vertex_pairs(s, 10); }, "line 2", "out of range");
    expect_error([] { std::istringstream s("3 3\n"); IO::read_vertex_pairs(s, 10); }, "line 1", "loop edge");
  }

  // --- key=value parameters
  {
    std::istringstream in("# radii\na=1\nb = 0.59999999999999998\n\nc=2 # long axis\nR=3\n");
    const auto p = IO::read_numeric_parameters(in);
    check(p.size() == 4 && p.at("a") == 1 && std::abs(p.at("b") - 0.6) < 1e-15 && p.at("c") == 2 && p.at("R") == 3,
          "parameters");
    expect_error([] { std::istringstream s("a=1\nb 2\n"); IO::read_numeric_parameters(s); }, "line 2", "no '='");
    expect_error([] { std::istringstream s("a=x\n"); IO::read_numeric_parameters(s); }, "line 1", "non-numeric");
    expect_error([] { std::istringstream s("a=1\na=2\n"); IO::read_numeric_parameters(s); }, "given twice",
                 "repeated key");
  }

  // --- the file-name overloads, on files written here (the test runs in its build folder)
  {
    auto write = [](const std::string& name, const std::string& text) { std::ofstream(name) << text; };
    write("dem_test_sidecar.population.txt", "# two faces\n1\n2.5\n");
    write("dem_test_sidecar.landmarks.txt", "3 0 0 1\n");
    write("dem_test_sidecar.cut_edges.txt", "0 1\n1 2\n");
    write("dem_test_sidecar.params.txt", "R=3\nr = 1\n");
    const std::vector<double> v = IO::read_face_values("dem_test_sidecar.population.txt", 2);
    check(v.size() == 2 && v[1] == 2.5, "read_face_values(file)");
    const auto l = IO::read_landmarks("dem_test_sidecar.landmarks.txt", 4);
    check(l.size() == 1 && l[0].vertex == 3 && l[0].target[2] == 1, "read_landmarks(file)");
    const auto e = IO::read_vertex_pairs("dem_test_sidecar.cut_edges.txt", 3);
    check(e.size() == 2 && e[1].first == 1 && e[1].second == 2, "read_vertex_pairs(file)");
    const auto p = IO::read_numeric_parameters("dem_test_sidecar.params.txt");
    check(p.size() == 2 && p.at("R") == 3 && p.at("r") == 1, "read_numeric_parameters(file)");
    // the file name is the source named in the messages
    expect_error([] { IO::read_face_values("dem_test_sidecar.population.txt", 3); }, "dem_test_sidecar.population.txt",
                 "face count from a file");
    expect_error([] { IO::read_landmarks("dem_test_sidecar.landmarks.txt", 3); }, "dem_test_sidecar.landmarks.txt",
                 "landmark index from a file");
    for(const char* missing : {"dem_test_no_such_file.txt"}) {
      expect_error([&] { IO::read_face_values(missing, 0); }, "cannot open dem_test_no_such_file.txt", "missing file");
      expect_error([&] { IO::read_landmarks(missing, 0); }, "cannot open", "missing landmark file");
      expect_error([&] { IO::read_vertex_pairs(missing, 0); }, "cannot open", "missing cut-edge file");
      expect_error([&] { IO::read_numeric_parameters(missing); }, "cannot open", "missing parameter file");
    }
  }

  if(failures) { std::cerr << failures << " failure(s)\n"; return 1; }
  std::cout << "test_sidecar_readers: all checks passed\n";
  return 0;
}

// --shared (ctest test_sidecar_readers_shared, label shared_data): the shared files parse.
int shared_part()
{
  const char* env = std::getenv("DEM_TEST_DATA_DIR"); // as dem_test::data_dir()
  const std::string dir = env ? env : DEM_DATA_DIR;
  if(!std::ifstream(dir + "/brain_landmarks.landmarks.txt")) {
    std::cout << "shared data not found in '" << dir << "': skipped\n";
    return 77;
  }
  check(IO::read_landmarks(dir + "/brain_landmarks.landmarks.txt", 12502).size() == 22, "brain landmarks");
  check(IO::read_face_values(dir + "/brain_landmarks.population.txt", 25000).size() == 25000, "brain population");
  check(IO::read_vertex_pairs(dir + "/bob_genus1.cut_edges.txt", 5344).size() > 10, "bob cut edges");
  const auto p = IO::read_numeric_parameters(dir + "/edeq_ellipsoid2.params.txt");
  check(p.count("a0") && p.count("b0") && p.count("c0"), "edeq parameters");
  if(failures) { std::cerr << failures << " failure(s)\n"; return 1; }
  std::cout << "test_sidecar_readers: all checks passed\n";
  return 0;
}
