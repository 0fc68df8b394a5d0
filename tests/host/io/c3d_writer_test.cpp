// The C3D export's bytes, read back by the minimal reader of c3d_test_reader.hpp.
#include "io/c3d_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "c3d_test_reader.hpp"
#include "export_test_paths.hpp"
#include "io/export_error.hpp"
#include "synthetic_trajectories.hpp"

namespace syncap::io {
namespace {

using testing::C3dTestReader;
using testing::fresh_path;
using testing::synthetic_trajectories;

// The 4th word the guide defines for a seen point: (camera mask << 8 | residual units) as a float.
float expected_fourth_word(const tracking::MarkerSample& s, float scale) {
  long units = std::lround(s.residual_mm / std::fabs(scale));
  if (s.residual_mm != 0) units = std::clamp(units, 1L, 255L);
  return static_cast<float>((s.cameras & 0x7f) << 8 | static_cast<uint32_t>(units));
}

float largest_coordinate(const tracking::MarkerTrajectories& t) {
  double largest = 0;
  for (const auto& row : t.samples) {
    for (const auto& s : row) {
      if (s) largest = std::max(largest, s->position_mm.cwiseAbs().maxCoeff());
    }
  }
  return static_cast<float>(largest);
}

void expect_points_match(const C3dTestReader& c3d, const tracking::MarkerTrajectories& t,
                         std::size_t f) {
  const float scale = c3d.header_float(7);
  for (std::size_t m = 0; m < t.labels.size(); ++m) {
    const auto point = c3d.point(f, m, t.labels.size());
    const auto& sample = t.samples[f][m];
    if (!sample) {
      EXPECT_EQ(point.x, 0.0f);
      EXPECT_EQ(point.y, 0.0f);
      EXPECT_EQ(point.z, 0.0f);
      EXPECT_EQ(point.fourth, -1.0f) << "frame " << f << " marker " << m;
      continue;
    }
    EXPECT_EQ(point.x, static_cast<float>(sample->position_mm.x()));
    EXPECT_EQ(point.y, static_cast<float>(sample->position_mm.y()));
    EXPECT_EQ(point.z, static_cast<float>(sample->position_mm.z()));
    EXPECT_EQ(point.fourth, expected_fourth_word(*sample, scale))
        << "frame " << f << " marker " << m;
  }
}

// Exports `t` to a fresh file and opens it with the minimal reader.
C3dTestReader written(const tracking::MarkerTrajectories& t) {
  const auto path = fresh_path(".c3d");
  write_c3d(path, t);
  return C3dTestReader(path);
}

TEST(C3dWriter, HeaderWordsDescribeTheRecording) {
  const auto t = synthetic_trajectories(50, 3, 100.0, 1234);
  const C3dTestReader c3d = written(t);
  EXPECT_EQ(c3d.byte(0), 2);     // parameters at block 2
  EXPECT_EQ(c3d.byte(1), 0x50);  // C3D key
  EXPECT_EQ(c3d.header_word(2), 3);
  EXPECT_EQ(c3d.header_word(3), 0);  // no analog
  EXPECT_EQ(c3d.header_word(4), 1);
  EXPECT_EQ(c3d.header_word(5), 50);
  EXPECT_FLOAT_EQ(c3d.header_float(7), -largest_coordinate(t) / 32000);
  EXPECT_EQ(c3d.header_word(9), 2 + c3d.parameter_blocks());
  EXPECT_EQ(c3d.header_word(10), 0);
  EXPECT_EQ(c3d.header_float(11), 100.0f);
  EXPECT_EQ(c3d.header_word(150), 12345);
  const std::size_t data_bytes = 50 * 3 * 16;
  EXPECT_EQ(c3d.size(), (c3d.header_word(9) - 1u) * 512u + (data_bytes + 511) / 512 * 512);
}

TEST(C3dWriter, ParameterSectionHoldsPointAnalogAndTrialGroups) {
  auto t = synthetic_trajectories(50, 3, 100.0, 1234);
  t.labels[1] = "RigidSetLeftWrist";
  const C3dTestReader c3d = written(t);
  EXPECT_EQ(c3d.processor(), 84);
  EXPECT_EQ(c3d.parameter("POINT:USED").word(), 3);
  EXPECT_EQ(c3d.parameter("POINT:FRAMES").word(), 50);
  EXPECT_EQ(c3d.parameter("POINT:DATA_START").word(), c3d.header_word(9));
  EXPECT_EQ(c3d.parameter("POINT:SCALE").real(), c3d.header_float(7));
  EXPECT_EQ(c3d.parameter("POINT:RATE").real(), 100.0f);
  EXPECT_EQ(c3d.parameter("POINT:UNITS").text(), "mm");
  // Labels padded with spaces to the longest.
  const auto& labels = c3d.parameter("POINT:LABELS");
  EXPECT_EQ(labels.dimensions, (std::vector<int>{17, 3}));
  EXPECT_EQ(labels.strings(), (std::vector<std::string>{"M001             ", "RigidSetLeftWrist",
                                                        "M003             "}));
  EXPECT_EQ(c3d.parameter("POINT:DESCRIPTIONS").dimensions[1], 3);
  EXPECT_EQ(c3d.parameter("ANALOG:USED").word(), 0);
  EXPECT_EQ(c3d.parameter("TRIAL:ACTUAL_START_FIELD").dimensions, std::vector<int>{2});
  EXPECT_EQ(c3d.parameter("TRIAL:ACTUAL_START_FIELD").word(0), 1);
  EXPECT_EQ(c3d.parameter("TRIAL:ACTUAL_END_FIELD").word(0), 50);
  EXPECT_EQ(c3d.parameter("TRIAL:ACTUAL_END_FIELD").word(1), 0);
  EXPECT_EQ(c3d.parameter("SYNCAP:FIRST_FRAME").text(), "1234");
}

TEST(C3dWriter, DataHoldsPositionsAndResidualWordsWithGapsInvalid) {
  const auto t = synthetic_trajectories(50, 3, 100.0, 0);
  const C3dTestReader c3d = written(t);
  for (std::size_t f = 0; f < 50; ++f) expect_points_match(c3d, t, f);
}

TEST(C3dWriter, ResidualZeroMarksUnmeasuredLargeOnesSaturateCamerasKeepSevenBits) {
  tracking::MarkerTrajectories t;
  t.labels = {"A", "B", "C"};
  t.rate_hz = 50;
  t.samples = {{tracking::MarkerSample{{3200, 0, 0}, 0.0, 0b101},  // scale 0.1 mm
                tracking::MarkerSample{{1, 2, 3}, 1e6, 0x1ff},
                tracking::MarkerSample{{1, 2, 3}, 0.01, 0}}};
  const C3dTestReader c3d = written(t);
  EXPECT_FLOAT_EQ(c3d.header_float(7), -0.1f);
  EXPECT_EQ(c3d.point(0, 0, 3).fourth, static_cast<float>(0b101 << 8 | 0));
  EXPECT_EQ(c3d.point(0, 1, 3).fourth, static_cast<float>(0x7f << 8 | 255));
  EXPECT_EQ(c3d.point(0, 2, 3).fourth, 1.0f);  // measured: at least one unit
}

TEST(C3dWriter, MoreThan255MarkersContinueInLabels2) {
  const auto t = synthetic_trajectories(4, 300, 250.0, 0);
  const C3dTestReader c3d = written(t);
  EXPECT_EQ(c3d.header_word(2), 300);
  EXPECT_EQ(c3d.parameter("POINT:USED").word(), 300);
  EXPECT_EQ(c3d.parameter("POINT:LABELS").dimensions, (std::vector<int>{4, 255}));
  EXPECT_EQ(c3d.parameter("POINT:LABELS2").dimensions, (std::vector<int>{4, 45}));
  EXPECT_EQ(c3d.parameter("POINT:DESCRIPTIONS2").dimensions[1], 45);
  auto labels = c3d.parameter("POINT:LABELS").strings();
  const auto more = c3d.parameter("POINT:LABELS2").strings();
  labels.insert(labels.end(), more.begin(), more.end());
  EXPECT_EQ(labels, t.labels);
  for (std::size_t f = 0; f < 4; ++f) expect_points_match(c3d, t, f);
}

TEST(C3dWriter, RecordingPast65535FramesCountsInTrialEndField) {
  const auto t = synthetic_trajectories(70000, 2, 120.0, 7);
  const C3dTestReader c3d = written(t);
  EXPECT_EQ(c3d.header_word(5), 65535);
  EXPECT_EQ(c3d.parameter("POINT:FRAMES").word(), 65535);
  const auto& end = c3d.parameter("TRIAL:ACTUAL_END_FIELD");
  EXPECT_EQ(end.word(0) | end.word(1) << 16, 70000);
  EXPECT_EQ(c3d.size(), (c3d.header_word(9) - 1u) * 512u + 70000u * 2 * 16);
  for (std::size_t f : {0u, 65534u, 65535u, 65536u, 69999u}) expect_points_match(c3d, t, f);
}

TEST(C3dWriter, RefusesMoreMarkersThanC3dCounts) {
  const auto path = fresh_path(".c3d");
  const auto t = synthetic_trajectories(1, 32768, 100.0, 0);
  try {
    write_c3d(path, t);
    FAIL() << "32768 markers were written";
  } catch (const ExportError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_NE(std::string(e.what()).find("32768 markers"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace syncap::io
