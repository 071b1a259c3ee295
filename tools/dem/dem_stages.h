// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Progress of the `dem` tool on stderr: the name of the running stage
// (reading, validation, the map, metrics, writing) once it has lasted more
// than a second, refreshed every second, with the iteration, the error against
// the tolerance and an estimate of the iterations left for iterative stages.
// A watcher thread prints, so a long direct solve inside a library call is not
// silent. On a terminal the line is rewritten in place; otherwise one line per
// second. `--quiet` turns it off.

#ifndef DEM_TOOL_DEM_STAGES_H
#define DEM_TOOL_DEM_STAGES_H

#include <unistd.h> // isatty

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace dem_cli {

class Stage_progress
{
public:
  explicit Stage_progress(bool quiet) : m_quiet(quiet)
  {
    if(!m_quiet) m_watcher = std::thread([this] { watch(); });
  }
  ~Stage_progress()
  {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_stop = true;
    }
    m_wake.notify_all();
    if(m_watcher.joinable()) m_watcher.join();
    finish_line();
  }
  Stage_progress(const Stage_progress&) = delete;
  Stage_progress& operator=(const Stage_progress&) = delete;

  /// Starts a stage (and ends the previous one).
  void begin(const std::string& name, double tolerance = 0)
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    end_locked();
    m_top = name;
    m_top_tolerance = tolerance;
    m_stage = name;
    m_start = std::chrono::steady_clock::now();
    m_tolerance = tolerance;
    m_iteration = 0;
    m_error = m_previous_error = -1;
  }
  /// Starts a part of the current stage, named by the library (its
  /// `stage_callback`): shown as "stage: part", timed on its own.
  void substage(const std::string& part)
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    end_locked();
    m_stage = m_top.empty() ? part : m_top + ": " + part;
    m_start = std::chrono::steady_clock::now();
    m_tolerance = m_top_tolerance;
    m_iteration = 0;
    m_error = m_previous_error = -1;
  }
  void end()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    end_locked();
  }
  /// Called by the library after each iteration; never cancels.
  bool iteration(std::size_t k, double error)
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_previous_error = m_error;
    m_iteration = k;
    m_error = error;
    return true;
  }

private:
  static double since(std::chrono::steady_clock::time_point t)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }

  /// "iteration k, error e (tolerance t), ~n more" for an iterative stage, "" otherwise.
  std::string detail() const
  {
    if(m_iteration == 0) return "";
    char b[160];
    int n = std::snprintf(b, sizeof b, ", iteration %zu, error %.3e", m_iteration, m_error);
    if(m_tolerance > 0) {
      n += std::snprintf(b + n, sizeof b - std::size_t(n), " (tolerance %.1e)", m_tolerance);
      // the last step's reduction factor, assumed to hold: log(error/tol) / -log(rate) steps left
      const double rate = m_previous_error > 0 ? m_error / m_previous_error : 0;
      if(rate > 0 && rate < 1 && m_error > m_tolerance)
        std::snprintf(b + n, sizeof b - std::size_t(n), ", ~%.0f more",
                      std::ceil(std::log(m_error / m_tolerance) / -std::log(rate)));
    }
    return b;
  }

  void print_locked()
  {
    const double t = since(m_start);
    std::fprintf(stderr, m_tty ? "\rdem: %s: %.0f s%s   " : "dem: %s: %.0f s%s\n", m_stage.c_str(), t, detail().c_str());
    std::fflush(stderr);
    m_printed = true;
  }

  void end_locked()
  {
    if(m_stage.empty()) return;
    if(m_printed) {
      std::fprintf(stderr, m_tty ? "\rdem: %s: done in %.1f s%s\n" : "dem: %s: done in %.1f s%s\n", m_stage.c_str(),
                   since(m_start), detail().c_str());
      m_printed = false;
    }
    m_stage.clear();
  }

  void finish_line()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    end_locked();
  }

  void watch()
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    double last = 0;
    std::string last_stage;
    while(!m_stop) {
      m_wake.wait_for(lock, std::chrono::milliseconds(200));
      if(m_stop || m_stage.empty()) continue;
      if(m_stage != last_stage) { last_stage = m_stage; last = 0; }
      const double t = since(m_start);
      if(t > 1.0 && t - last >= 1.0) {
        print_locked();
        last = t;
      }
    }
  }

  bool m_quiet;
  bool m_tty = isatty(2) != 0;
  bool m_printed = false, m_stop = false;
  std::string m_stage, m_top;
  double m_top_tolerance = 0;
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
  double m_tolerance = 0, m_error = -1, m_previous_error = -1;
  std::size_t m_iteration = 0;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  std::thread m_watcher;
};

} // namespace dem_cli

#endif // DEM_TOOL_DEM_STAGES_H
