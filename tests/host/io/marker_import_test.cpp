// The C3D and TRC importers (io/c3d_reader.hpp, io/trc_reader.hpp): what our exports write reads
// back the same (every value of the synthetic trajectories, gaps, residuals, camera masks); the
// real files of ../shared/data/motion/real-markers read as their sources describe them; bad
// files are refused naming the file and the place.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "export_test_paths.hpp"
#include "io/c3d_reader.hpp"
#include "io/c3d_writer.hpp"
#include "io/import_error.hpp"
#include "io/trc_reader.hpp"
#include "io/trc_writer.hpp"
#include "synthetic_trajectories.hpp"

namespace syncap::io {
namespace {

using testing::fresh_path;
using testing::synthetic_trajectories;

void expect_same(const tracking::MarkerTrajectories& a, const tracking::MarkerTrajectories& b,
                 double position_tolerance, bool residuals) {
  ASSERT_EQ(a.labels, b.labels);
  EXPECT_NEAR(a.rate_hz, b.rate_hz, 1e-4);
  EXPECT_EQ(a.first_frame, b.first_frame);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t f = 0; f < a.samples.size(); ++f) {
    for (std::size_t m = 0; m < a.labels.size(); ++m) {
      const auto& x = a.samples[f][m];
      const auto& y = b.samples[f][m];
      ASSERT_EQ(x.has_value(), y.has_value()) << "frame " << f << " marker " << m;
      if (!x) continue;
      EXPECT_LT((x->position_mm - y->position_mm).norm(), position_tolerance);
      if (!residuals) continue;
      // C3D's residual: a byte in units of POINT:SCALE (about 0.04 mm for these coordinates).
      EXPECT_NEAR(x->residual_mm, y->residual_mm, 0.02);
      EXPECT_EQ(x->cameras & 0x7f, y->cameras);
    }
  }
}

TEST(MarkerImport, C3dWrittenByOurExportReadsBack) {
  const auto t = synthetic_trajectories(300, 12, 120.0, 5);
  const std::string path = fresh_path(".c3d");
  write_c3d(path, t);
  const C3dFile read = read_c3d(path);
  EXPECT_EQ(read.units, "mm");
  expect_same(t, read.trajectories, 1e-9, true);
}

TEST(MarkerImport, TrcWrittenByOurExportReadsBack) {
  const auto t = synthetic_trajectories(200, 7, 60.0, 1);
  const std::string path = fresh_path(".trc");
  write_trc(path, t);
  const TrcFile read = read_trc(path);
  EXPECT_EQ(read.units, "mm");
  expect_same(t, read.trajectories, 1e-3, false);  // TRC holds 5 decimals
  EXPECT_EQ(read_marker_trajectories(path).samples.size(), 200u);
}

TEST(MarkerImport, TrcInMetresComesOutInMillimetres) {
  const std::string path = fresh_path(".trc");
  std::ofstream(path) << "PathFileType\t4\t(X/Y/Z)\tx.trc\n"
                         "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
                         "100\t100\t2\t2\tm\n"
                         "Frame#\tTime\tA\t\t\tB\t\t\n"
                         "\t\tX1\tY1\tZ1\tX2\tY2\tZ2\n"
                         "\n"
                         "1\t0\t0.5\t1\t1.5\t\t\t\n"
                         "2\t0.01\t0\t0\t0\t0.25\t0\t1\n";
  const TrcFile read = read_trc(path);
  ASSERT_EQ(read.trajectories.samples.size(), 2u);
  EXPECT_EQ(read.trajectories.samples[0][0]->position_mm, Eigen::Vector3d(500, 1000, 1500));
  EXPECT_FALSE(read.trajectories.samples[0][1]);  // empty fields: a gap
  EXPECT_FALSE(read.trajectories.samples[1][0]);  // 0, 0, 0: how exporters write a gap
  EXPECT_EQ(read.trajectories.samples[1][1]->position_mm, Eigen::Vector3d(250, 0, 1000));
}

TEST(MarkerImport, BadFilesAreRefusedNamingTheFileAndThePlace) {
  const std::string c3d = fresh_path(".c3d");
  std::ofstream(c3d) << "not a c3d file at all";
  EXPECT_THROW(
      {
        try {
          read_c3d(c3d);
        } catch (const ImportError& e) {
          EXPECT_NE(std::string(e.what()).find(c3d), std::string::npos);
          EXPECT_NE(std::string(e.what()).find("not a C3D file"), std::string::npos) << e.what();
          throw;
        }
      },
      ImportError);
  const auto t = synthetic_trajectories(50, 3, 100.0, 1);
  write_c3d(c3d, t);
  std::filesystem::resize_file(c3d, std::filesystem::file_size(c3d) - 600);  // cut the data
  try {
    read_c3d(c3d);
    FAIL() << "a cut file read";
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("frame"), std::string::npos) << e.what();
  }
  const std::string trc = fresh_path(".trc");
  std::ofstream(trc) << "PathFileType\t4\n"
                        "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
                        "100\t100\t1\t1\tfurlong\n"
                        "Frame#\tTime\tA\n\t\tX1\tY1\tZ1\n1\t0\t1\t2\t3\n";
  try {
    read_trc(trc);
    FAIL() << "an unknown unit read";
  } catch (const ImportError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3: unknown Units 'furlong'"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read_marker_trajectories(fresh_path(".csv")), ImportError);
}

std::filesystem::path real_markers() {
  const char* data = std::getenv("SYNCAP_DATA");
  return data ? std::filesystem::path(data) / "motion" / "real-markers" : std::filesystem::path();
}

TEST(MarkerImport, RealFilesReadAsTheirSourcesDescribeThem) {
  if (real_markers().empty() || !std::filesystem::exists(real_markers() / "Qualisys.c3d"))
    GTEST_SKIP() << "needs SYNCAP_DATA with motion/real-markers (set it to ../shared/data)";
  const C3dFile qualisys = read_c3d((real_markers() / "Qualisys.c3d").string());
  EXPECT_EQ(qualisys.trajectories.labels.size(), 55u);
  EXPECT_DOUBLE_EQ(qualisys.trajectories.rate_hz, 200.0);
  EXPECT_EQ(qualisys.trajectories.samples.size(), 340u);
  EXPECT_EQ(qualisys.units, "mm");
  const TrcFile running = read_trc((real_markers() / "subject02_running.trc").string());
  EXPECT_EQ(running.trajectories.labels.size(), 41u);
  EXPECT_DOUBLE_EQ(running.trajectories.rate_hz, 60.0);
  EXPECT_EQ(running.trajectories.samples.size(), 600u);
  // L.Bicep is 0, 0, 0 in every frame: missing throughout.
  const auto bicep =
      std::find(running.trajectories.labels.begin(), running.trajectories.labels.end(), "L.Bicep");
  ASSERT_NE(bicep, running.trajectories.labels.end());
  const std::size_t m = static_cast<std::size_t>(bicep - running.trajectories.labels.begin());
  for (const auto& row : running.trajectories.samples) EXPECT_FALSE(row[m]);
}

}  // namespace
}  // namespace syncap::io
