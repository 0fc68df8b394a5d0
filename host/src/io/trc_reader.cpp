#include "io/trc_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>

#include "io/c3d_reader.hpp"
#include "io/import_error.hpp"
#include "io/unit_scale.hpp"

namespace syncap::io {
namespace {

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = line.find('\t', start);
    std::string f = line.substr(start, tab == std::string::npos ? std::string::npos : tab - start);
    while (!f.empty() && std::isspace(static_cast<unsigned char>(f.back()))) f.pop_back();
    out.push_back(f);
    if (tab == std::string::npos) return out;
    start = tab + 1;
  }
}

bool parse_number(const std::string& s, double* value) {
  if (s.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && std::isfinite(*value);
}

}  // namespace

TrcFile read_trc(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ImportError(path, "cannot open the file");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  auto fail = [&](std::size_t line, const std::string& problem) {
    throw ImportError(path, "line " + std::to_string(line + 1) + ": " + problem);
  };
  if (lines.size() < 5 || lines[0].rfind("PathFileType", 0) != 0)
    fail(0, "not a TRC file (it starts with PathFileType and has 5 header lines)");
  const std::vector<std::string> keys = fields(lines[1]), values = fields(lines[2]);
  std::map<std::string, std::string> header;
  for (std::size_t i = 0; i < keys.size() && i < values.size(); ++i) header[keys[i]] = values[i];
  TrcFile out;
  tracking::MarkerTrajectories& t = out.trajectories;
  double rate = 0, markers = 0;
  if (!parse_number(header["DataRate"], &rate) || !(rate > 0))
    fail(2, "DataRate '" + header["DataRate"] + "' is not a positive number");
  if (!parse_number(header["NumMarkers"], &markers) || markers < 1)
    fail(2, "NumMarkers '" + header["NumMarkers"] + "' is not a count");
  t.rate_hz = rate;
  out.units = header.count("Units") ? header["Units"] : "mm";
  const std::optional<double> to_mm = millimetres_per(out.units);
  if (!to_mm) fail(2, "unknown Units '" + out.units + "' (mm, cm, m)");
  const std::vector<std::string> names = fields(lines[3]);
  for (std::size_t i = 2; i < names.size(); i += 3) {
    if (!names[i].empty()) t.labels.push_back(names[i]);
  }
  const std::size_t count = static_cast<std::size_t>(markers);
  if (t.labels.size() != count) {
    fail(3,
         std::to_string(t.labels.size()) + " marker names for NumMarkers " + std::to_string(count));
  }
  bool first = true;
  for (std::size_t l = 5; l < lines.size(); ++l) {
    const std::vector<std::string> f = fields(lines[l]);
    if (f.size() == 1 && f[0].empty()) continue;  // blank lines (one after the header)
    double frame = 0;
    if (!parse_number(f[0], &frame)) fail(l, "frame number '" + f[0] + "' is not a number");
    if (first) t.first_frame = static_cast<int64_t>(frame);
    first = false;
    std::vector<std::optional<tracking::MarkerSample>> row(count);
    for (std::size_t m = 0; m < count; ++m) {
      Eigen::Vector3d p;
      bool have = true;
      for (int k = 0; k < 3; ++k) {
        const std::size_t at = 2 + 3 * m + static_cast<std::size_t>(k);
        const std::string text = at < f.size() ? f[at] : "";
        if (text.empty()) {
          have = false;
          continue;
        }
        if (!parse_number(text, &p[k]))
          fail(l, "marker " + t.labels[m] + ": '" + text + "' is not a number");
      }
      if (!have || p.isZero(0.0)) continue;  // a gap: empty, or written as 0, 0, 0
      tracking::MarkerSample s;
      s.position_mm = *to_mm * p;
      row[m] = s;
    }
    t.samples.push_back(std::move(row));
  }
  if (t.samples.empty()) fail(lines.size() - 1, "no frames");
  return out;
}

tracking::MarkerTrajectories read_marker_trajectories(const std::string& path) {
  std::string ext = path.substr(
      path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".c3d") return read_c3d(path).trajectories;
  if (ext == ".trc") return read_trc(path).trajectories;
  throw ImportError(path, "not a marker file: the name ends in .c3d or .trc");
}

}  // namespace syncap::io
