// The TRC export, read as OpenSim's TRCFileAdapter reads it: tab-separated fields, empty fields
// kept inside a line, the empty field after a line's last tab dropped.
#include "io/trc_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "export_test_paths.hpp"
#include "synthetic_trajectories.hpp"

namespace syncap::io {
namespace {

using testing::fresh_path;
using testing::synthetic_trajectories;

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> opensim_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1) {
    fields.push_back(line.substr(start, tab - start));
  }
  if (start < line.size()) fields.push_back(line.substr(start));
  return fields;
}

TEST(TrcWriter, HeaderLinesAreTheOnesOpenSimExpects) {
  const auto path = fresh_path(".trc");
  auto t = synthetic_trajectories(3, 2, 120.0, 1500);
  t.labels = {"M001", "Wrist"};
  write_trc(path, t);
  const auto lines = read_lines(path);
  ASSERT_GE(lines.size(), 9u);
  const std::string name = std::filesystem::path(path).filename().string();
  EXPECT_EQ(lines[0], "PathFileType\t4\t(X/Y/Z)\t" + name);
  EXPECT_EQ(lines[1],
            "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\t"
            "OrigDataStartFrame\tOrigNumFrames");
  EXPECT_EQ(lines[2], "120\t120\t3\t2\tmm\t120\t1500\t3");
  EXPECT_EQ(lines[3], "Frame#\tTime\tM001\t\t\tWrist\t\t");
  EXPECT_EQ(lines[4], "\t\tX1\tY1\tZ1\tX2\tY2\tZ2");
  EXPECT_EQ(lines[5], "");
  EXPECT_EQ(lines.size(), 6u + 3u);
}

TEST(TrcWriter, RowsHoldFrameTimeAndMillimetresWithGapsLeftEmpty) {
  const auto path = fresh_path(".trc");
  const long frames = 40, markers = 3;
  const auto t = synthetic_trajectories(frames, markers, 100.0, 0);
  write_trc(path, t);
  const auto lines = read_lines(path);
  ASSERT_EQ(lines.size(), 6u + frames);
  for (long f = 0; f < frames; ++f) {
    const auto fields = opensim_fields(lines[6 + static_cast<std::size_t>(f)]);
    ASSERT_EQ(fields.size(), 2u + 3u * markers) << "frame " << f;
    EXPECT_EQ(std::stol(fields[0]), f + 1);
    EXPECT_NEAR(std::stod(fields[1]), f / 100.0, 1e-12);
    for (long m = 0; m < markers; ++m) {
      const std::size_t at = 2 + 3 * static_cast<std::size_t>(m);
      const auto& sample = t.samples[static_cast<std::size_t>(f)][static_cast<std::size_t>(m)];
      if (!sample) {
        EXPECT_EQ(fields[at] + fields[at + 1] + fields[at + 2], "") << "gap " << f << "," << m;
        continue;
      }
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(std::stod(fields[at + static_cast<std::size_t>(axis)]),
                    sample->position_mm[axis], 5e-5);
      }
    }
  }
}

TEST(TrcWriter, GapInTheLastMarkerStillCountsItsThreeFields) {
  const auto path = fresh_path(".trc");
  tracking::MarkerTrajectories t;
  t.labels = {"A", "B"};
  t.rate_hz = 10;
  t.samples = {{tracking::MarkerSample{{1, 2, 3}, 0.5, 1}, std::nullopt}};
  write_trc(path, t);
  const auto lines = read_lines(path);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[6], "1\t0\t1.0000\t2.0000\t3.0000\t\t\t\t");
  EXPECT_EQ(opensim_fields(lines[6]).size(), 8u);
}

}  // namespace
}  // namespace syncap::io
