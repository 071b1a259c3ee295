// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Output files of the dem tool, handled so that a user can trust what is on
// disk after a run:
//  - every output path is checked before the computation (supported mesh
//    format, existing writable directory, not one of the input files);
//  - each file is written to a temporary file in the same directory and
//    renamed over the target, so a reader never sees a half-written file and
//    a failed write leaves no partial file;
//  - on a failed run (exit 3 or 4), an output file left by an earlier run is
//    deleted, so that no stale result looks like the result of this run.

#ifndef DEM_TOOL_OUTPUT_FILES_H
#define DEM_TOOL_OUTPUT_FILES_H

#include <CGAL/Density_equalizing_maps/Map_report.h> // Invalid_input

#include <stdlib.h> // mkstemps
#include <sys/stat.h> // fchmod, umask
#include <unistd.h> // close

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace dem_cli {

namespace fs = std::filesystem;

/// The extension of `path` without the dot, lower-cased ("" if none).
inline std::string lower_extension(const std::string& path)
{
  std::string e = fs::path(path).extension().string();
  if(!e.empty()) e.erase(0, 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

/// Mesh formats `CGAL::IO::write_polygon_soup` writes in this build.
inline std::vector<std::string> writable_mesh_extensions()
{
  std::vector<std::string> e = {"off", "obj", "ply", "stl", "ts"};
#ifdef CGAL_USE_VTK
  e.push_back("vtp");
#endif
  return e;
}

/// True when both paths exist and name the same file (hard links and
/// symbolic links included).
inline bool same_file(const std::string& a, const std::string& b)
{
  std::error_code ec;
  return !a.empty() && !b.empty() && fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

/// The directory a file named `path` would be created in.
inline fs::path directory_of(const std::string& path)
{
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

/// Creates an empty temporary file in the directory of `path`, with the same
/// extension (writers choose the format by the extension). Returns its name,
/// or "" with `error` set.
inline std::string make_temporary_beside(const std::string& path, std::string& error)
{
  const fs::path target(path);
  const std::string ext = target.extension().string();
  std::string name = (directory_of(path) / ("." + target.stem().string() + ".dem-XXXXXX" + ext)).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = mkstemps(buffer.data(), int(ext.size()));
  if(fd < 0) { error = std::strerror(errno); return ""; }
  // mkstemps creates the file readable by its owner only; the output must get
  // the permissions any other new file gets (0666 less the umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  return std::string(buffer.data());
}

/// A problem with an output path, and the exit status it deserves: 2 for a
/// command-line mistake (unsupported format, an output that is an input), 3
/// for a place that cannot be written (DESIGN.md: unwritable file = exit 3).
struct Output_problem
{
  std::string message; // empty: no problem
  int status = 0;
  explicit operator bool() const { return !message.empty(); }
};

/// Everything that can be known about an output path before the computation.
/// `inputs` are the files the run reads: an output must be none of them.
inline Output_problem output_path_problem(const std::string& option, const std::string& path, bool mesh,
                                          const std::vector<std::string>& inputs)
{
  auto usage = [](const std::string& m) { return Output_problem{m, 2}; };
  auto unwritable = [](const std::string& m) { return Output_problem{m, 3}; };
  if(path.empty()) return Output_problem();
  for(const std::string& in : inputs)
    if(same_file(path, in))
      return usage(option + " " + path + " is the input file " + in + ": refusing to overwrite an input");
  if(mesh) {
    const std::vector<std::string> ok = writable_mesh_extensions();
    const std::string e = lower_extension(path);
    if(std::find(ok.begin(), ok.end(), e) == ok.end()) {
      std::string list;
      for(const std::string& s : ok) list += (list.empty() ? "." : ", .") + s;
      return usage(option + " " + path + ": " + (e.empty() ? "no extension" : "unsupported format ." + e) +
                   " (supported: " + list + ")");
    }
  }
  std::error_code ec;
  if(fs::is_directory(path, ec)) return usage(option + " " + path + " is a directory");
  const fs::path dir = directory_of(path);
  if(!fs::is_directory(dir, ec))
    return unwritable(option + " " + path + ": directory " + dir.string() + " does not exist");
  if(fs::exists(path, ec) && !fs::is_regular_file(path, ec)) return Output_problem(); // a device or pipe
  std::string error;
  const std::string probe = make_temporary_beside(path, error);
  if(probe.empty())
    return unwritable(option + " " + path + ": cannot create a file in " + dir.string() + " (" + error + ")");
  fs::remove(probe, ec);
  return Output_problem();
}

/// Writes `path` through `write(temporary_name)`: the temporary file (same
/// directory, same extension) is renamed over `path` only if `write`
/// succeeded; otherwise it is removed and `path` is left alone. Paths that
/// exist and are not regular files (/dev/stdout, a pipe) are written in place.
template <class Writer>
bool write_atomically(const std::string& path, const Writer& write, std::string& error)
{
  std::error_code ec;
  if(fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    if(write(path)) return true;
    error = "write failed";
    return false;
  }
  const std::string tmp = make_temporary_beside(path, error);
  if(tmp.empty()) return false;
  if(!write(tmp)) {
    fs::remove(tmp, ec);
    error = "write failed";
    return false;
  }
  fs::rename(tmp, path, ec);
  if(ec) {
    error = ec.message();
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

/// write_atomically() for a writer that reports failure by throwing
/// (`Invalid_input` and the like): the temporary file is removed and an
/// `Invalid_input` naming `path` is thrown.
template <class ThrowingWriter>
void write_output_atomically(const std::string& path, const ThrowingWriter& write)
{
  std::string what;
  std::string error;
  const bool ok = write_atomically(path, [&](const std::string& f) {
    try { write(f); return true; } catch(const std::exception& e) { what = e.what(); return false; }
  }, error);
  if(!ok)
    throw CGAL::Density_equalizing_maps::Invalid_input("cannot write " + path + ": " + (what.empty() ? error : what));
}

/// After a failed run: deletes `path` if a regular file by that name exists
/// (left by an earlier run), unless it is one of the inputs. Returns true if
/// a file was deleted.
inline bool remove_stale_output(const std::string& path, const std::vector<std::string>& inputs)
{
  if(path.empty()) return false;
  for(const std::string& in : inputs)
    if(same_file(path, in)) return false;
  std::error_code ec;
  if(!fs::is_regular_file(path, ec)) return false;
  return fs::remove(path, ec) && !ec;
}

} // namespace dem_cli

#endif // DEM_TOOL_OUTPUT_FILES_H
