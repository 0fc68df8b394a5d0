// The layout OpenSim's TRCFileAdapter reads: 5 header lines, a blank line, one row per frame.
#include "io/trc_writer.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "io/atomic_file.hpp"
#include "io/export_checks.hpp"

namespace syncap::io {
namespace {

// Shortest text that reads back as the same double (times, rates).
std::string exact(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

void write_header(std::ostream& out, const std::string& path,
                  const tracking::MarkerTrajectories& t) {
  const std::string rate = exact(t.rate_hz);
  const std::size_t frames = t.samples.size();
  const std::size_t markers = t.labels.size();
  out << "PathFileType\t4\t(X/Y/Z)\t" << std::filesystem::path(path).filename().string() << "\n";
  out << "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame"
         "\tOrigNumFrames\n";
  out << rate << "\t" << rate << "\t" << frames << "\t" << markers << "\tmm\t" << rate << "\t"
      << t.first_frame << "\t" << frames << "\n";
  out << "Frame#\tTime";
  for (const auto& label : t.labels) out << "\t" << label << "\t\t";
  out << "\n\t";
  for (std::size_t m = 1; m <= markers; ++m) out << "\tX" << m << "\tY" << m << "\tZ" << m;
  out << "\n\n";
}

// One frame; a gap leaves its three fields empty. Each row ends with a tab so that a gap in the
// last marker still counts three fields for OpenSim, which drops a line's empty last field.
void write_row(std::ostream& out, std::size_t row_index, double time_s,
               const std::vector<std::optional<tracking::MarkerSample>>& row) {
  char number[48];
  out << row_index + 1 << "\t" << exact(time_s);
  for (const auto& sample : row) {
    if (!sample) {
      out << "\t\t\t";
      continue;
    }
    const Eigen::Vector3d& p = sample->position_mm;
    std::snprintf(number, sizeof number, "\t%.4f\t%.4f\t%.4f", p.x(), p.y(), p.z());
    out << number;
  }
  out << "\t\n";
}

}  // namespace

void write_trc(const std::string& path, const tracking::MarkerTrajectories& trajectories) {
  check_exportable(trajectories, path);
  write_file_atomically(path, [&](std::ostream& out) {
    write_header(out, path, trajectories);
    for (std::size_t f = 0; f < trajectories.samples.size(); ++f) {
      write_row(out, f, static_cast<double>(f) / trajectories.rate_hz, trajectories.samples[f]);
    }
  });
}

}  // namespace syncap::io
