// Copyright (c) 2026 Density_equalizing_maps contributors.
// This file is part of Density_equalizing_maps, a third-party CGAL package.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "metrics.h"
#include "output_files.h"

#include <CGAL/Density_equalizing_maps/internal/beltrami.h>
#include <CGAL/Density_equalizing_maps/internal/measures.h>
#include <CGAL/Density_equalizing_maps/internal/operators.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace dem_cli {

std::pair<double, double> density_variances(const DI::Matrix& Z, const DI::Index_matrix& F,
                                                   const DI::Vector& population)
{
  const DI::Vector area = DI::face_areas(Z, F);
  const DI::Densities d = DI::densities(population, area, DI::face_to_vertex(area, F, Z.rows()));
  return {DI::normalized_variance(d.vertex), DI::normalized_variance(d.face)};
}

Metrics compute_metrics(const std::string& method, const CGAL::Density_equalizing_maps::Map_report& report,
                               double seconds, const Metric_input& in)
{
  using CGAL::Density_equalizing_maps::Termination;
  // the input at unit size (a power of two, as the library does): lengths and
  // areas of coordinates near 1e+-100 overflow; every metric is scale-invariant
  const DI::Matrix X = *in.X * DI::unit_scale(*in.X);
  const DI::Index_matrix& F = *in.F;
  const DI::Matrix& Y = *in.Y;
  Metrics m;
  m.method = method;
  m.vertices = std::size_t(X.rows());
  m.faces = std::size_t(F.rows());
  m.seconds = seconds;
  if(report.termination != Termination::NOT_ITERATIVE) m.iterations = double(report.iterations);
  m.converged = report.converged();
  m.termination = CGAL::Density_equalizing_maps::to_string(report.termination);
  m.fold_overs = report.fold_overs;
  m.fallback = report.fallback;
  m.start = report.start;
  m.repairs = report.repairs;

  const DI::Mean_sd mu = DI::mean_sd(DI::beltrami_magnitude_3d(X, Y, F));
  m.mean_abs_mu = mu.mean;
  m.sd_abs_mu = mu.sd;
  const DI::Vector darea = DI::log_area_ratio(DI::face_areas(X, F), DI::face_areas(Y, F)).cwiseAbs();
  const DI::Mean_sd da = DI::mean_sd(darea);
  m.mean_abs_darea = da.mean;
  m.sd_abs_darea = da.sd;

  const auto initial = density_variances(in.initial && in.initial != in.X ? *in.initial : X, F, *in.population);
  const auto final = density_variances(Y, F, *in.population);
  m.density_var_initial = initial.first;
  m.face_density_var_initial = initial.second;
  m.density_var_final = final.first;
  m.face_density_var_final = final.second;

  if(in.landmark_index && !in.landmark_index->empty()) {
    double s = 0;
    for(std::size_t k = 0; k < in.landmark_index->size(); ++k)
      s += (Y.row((*in.landmark_index)[k]) - in.landmark_targets->row(Eigen::Index(k))).norm();
    m.landmark_error = s / double(in.landmark_index->size());
  }
  for(std::size_t c = 0; c < std::min(in.radii_count, report.radii.size()); ++c) m.radii.push_back(report.radii[c]);
  return m;
}

void Metrics::add(const std::string& key, double value) { add_json(key, json_number(value)); }

std::string json_number(double v)
{
  if(!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string json_string(const std::string& s)
{
  std::string r = "\"";
  for(char c : s) {
    if(c == '"' || c == '\\') { r += '\\'; r += c; }
    else if(static_cast<unsigned char>(c) < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); r += b; }
    else r += c;
  }
  return r + "\"";
}

std::string metrics_json(const Metrics& m)
{
  std::ostringstream o;
  o << "{\n"
    << "  \"method\": " << json_string(m.method) << ",\n"
    << "  \"vertices\": " << m.vertices << ",\n"
    << "  \"faces\": " << m.faces << ",\n"
    << "  \"seconds\": " << json_number(m.seconds) << ",\n"
    << "  \"iterations\": " << json_number(m.iterations) << ",\n"
    << "  \"converged\": " << (m.converged ? "true" : "false") << ",\n"
    << "  \"fold_overs\": " << m.fold_overs << ",\n"
    << "  \"mean_abs_mu\": " << json_number(m.mean_abs_mu) << ",\n"
    << "  \"sd_abs_mu\": " << json_number(m.sd_abs_mu) << ",\n"
    << "  \"mean_abs_darea\": " << json_number(m.mean_abs_darea) << ",\n"
    << "  \"sd_abs_darea\": " << json_number(m.sd_abs_darea) << ",\n"
    << "  \"density_var_initial\": " << json_number(m.density_var_initial) << ",\n"
    << "  \"density_var_final\": " << json_number(m.density_var_final) << ",\n"
    << "  \"face_density_var_initial\": " << json_number(m.face_density_var_initial) << ",\n"
    << "  \"face_density_var_final\": " << json_number(m.face_density_var_final) << ",\n"
    << "  \"landmark_error\": " << json_number(m.landmark_error) << ",\n"
    << "  \"fallback\": " << (m.fallback.empty() ? std::string("null") : json_string(m.fallback)) << ",\n"
    << "  \"start\": " << (m.start.empty() ? std::string("null") : json_string(m.start)) << ",\n"
    << "  \"repairs\": " << m.repairs << ",\n"
    << "  \"radii\": ";
  if(m.radii.empty()) o << "null";
  else {
    o << "[";
    for(std::size_t c = 0; c < m.radii.size(); ++c) o << (c ? ", " : "") << json_number(m.radii[c]);
    o << "]";
  }
  for(const auto& kv : m.extra) o << ",\n  " << json_string(kv.first) << ": " << kv.second;
  o << "\n}\n";
  return o.str();
}

bool write_metrics_json(const std::string& file, const Metrics& m)
{
  std::string error;
  return write_atomically(file, [&](const std::string& f) {
    std::ofstream out(f);
    if(!out) return false;
    out << metrics_json(m);
    out.close();
    return bool(out);
  }, error);
}

std::string summary_line(const Metrics& m)
{
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s: %zu vertices, %zu faces, %.3f s (%.3f s CPU), %s%s, fold-overs %zu, mean|mu| %.4g, mean|darea| %.4g, "
                "density var %.4g -> %.4g",
                m.method.c_str(), m.vertices, m.faces, m.seconds, m.cpu_seconds,
                std::isfinite(m.iterations) ? (std::to_string(std::size_t(m.iterations)) + " iterations, ").c_str() : "",
                m.termination.c_str(), m.fold_overs, m.mean_abs_mu, m.mean_abs_darea, m.density_var_initial,
                m.density_var_final);
  std::string s = buf;
  if(std::isfinite(m.landmark_error)) s += ", landmark error " + json_number(m.landmark_error).substr(0, 10);
  if(!m.radii.empty()) {
    s += ", radii";
    for(double r : m.radii) { std::snprintf(buf, sizeof buf, " %.5g", r); s += buf; }
  }
  s += ", repairs " + std::to_string(m.repairs);
  if(!m.fallback.empty()) s += ", fallback: " + m.fallback;
  return s;
}

} // namespace dem_cli
