#include "io/export_checks.hpp"

#include <cmath>
#include <unordered_set>

#include "io/export_error.hpp"

namespace syncap::io {
namespace {

// Why `label` cannot name a marker in both formats, or an empty string when it can.
std::string label_problem(const std::string& label) {
  if (label.empty()) return "is empty";
  if (label.size() > kMaxLabelLength) {
    return "is longer than " + std::to_string(kMaxLabelLength) + " characters";
  }
  for (char c : label) {
    // Tabs and line breaks would split TRC columns; C3D labels are ASCII.
    if (c < 0x20 || c > 0x7e) return "holds a character that is not printable ASCII";
  }
  if (label.front() == ' ' || label.back() == ' ') return "starts or ends with a space";
  return "";
}

void check_labels(const std::vector<std::string>& labels, const std::string& path) {
  if (labels.empty()) throw ExportError(path, "nothing to export: no marker");
  std::unordered_set<std::string> seen;
  for (std::size_t m = 0; m < labels.size(); ++m) {
    const std::string problem = label_problem(labels[m]);
    if (!problem.empty()) {
      throw ExportError(path, "label " + std::to_string(m) + " \"" + labels[m] + "\" " + problem);
    }
    if (!seen.insert(labels[m]).second) {
      throw ExportError(path, "label \"" + labels[m] + "\" names two markers");
    }
  }
}

void check_sample(const tracking::MarkerSample& sample, std::size_t frame, std::size_t marker,
                  const std::string& path) {
  const std::string where =
      "frame " + std::to_string(frame) + ", marker " + std::to_string(marker) + ": ";
  if (!sample.position_mm.allFinite()) throw ExportError(path, where + "position is not finite");
  if (!std::isfinite(sample.residual_mm) || sample.residual_mm < 0) {
    throw ExportError(path, where + "residual is negative or not finite");
  }
}

}  // namespace

void check_exportable(const tracking::MarkerTrajectories& trajectories, const std::string& path) {
  check_labels(trajectories.labels, path);
  if (!(std::isfinite(trajectories.rate_hz) && trajectories.rate_hz > 0)) {
    throw ExportError(path, "frame rate " + std::to_string(trajectories.rate_hz) +
                                " Hz is not a positive number");
  }
  if (trajectories.samples.empty()) throw ExportError(path, "nothing to export: no frame");
  const std::size_t width = trajectories.labels.size();
  for (std::size_t f = 0; f < trajectories.samples.size(); ++f) {
    const auto& row = trajectories.samples[f];
    if (row.size() != width) {
      throw ExportError(path, "frame " + std::to_string(f) + " has " + std::to_string(row.size()) +
                                  " samples for " + std::to_string(width) + " labels");
    }
    for (std::size_t m = 0; m < width; ++m) {
      if (row[m]) check_sample(*row[m], f, m, path);
    }
  }
}

}  // namespace syncap::io
