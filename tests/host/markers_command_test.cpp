// `syncap markers`: bad arguments and files are named (exit 2) before any log is read; --help is
// complete; --hull builds the hull of every frame from a log's silhouettes. Its reconstruction on
// a recorded log is checked by every hil run (the "offline" lines of hil/run, hil.run.* in ctest,
// and hil/calibrated's markers and hulls through a calibration from the wand phase).
#include "markers_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <CGAL/Polygon_mesh_processing/measure.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "ball_log.hpp"
#include "help_check.hpp"
#include "hull/hull_scenes.hpp"
#include "hull/mesh.hpp"
#include "io/lcm_log_reader.hpp"
#include "malformed_messages.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/test_cameras.hpp"
#include "subcommand.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct MarkersRun {
  int status = -1;
  std::string out, err;
};

MarkersRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  MarkersRun r;
  r.status = markers_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

class MarkersCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("syncap_markers_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    sensor::write_cameras(dir_ / "cameras.json", {sensor::test::basler_camera()});
    std::ofstream(dir_ / "empty.lcmlog").put('\0');
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> args(std::vector<std::string> more) const {
    std::vector<std::string> a = {"--input",       "lcmlog:" + (dir_ / "empty.lcmlog").string(),
                                  "--calibration", (dir_ / "cameras.json").string(),
                                  "--out",         (dir_ / "out").string()};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }
  fs::path dir_;
};

TEST_F(MarkersCommandTest, BadNumbersAreNamedWithTheirOption) {
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--sigma-px", "nan"}, {"--tolerance-px", "-1"}, {"--acceleration", "0"}}) {
    const MarkersRun r = run(args({option, value}));
    EXPECT_EQ(r.status, kExitUsage) << option;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "markers.jsonl")) << option;
  }
}

TEST_F(MarkersCommandTest, ABrokenRigidSetFileIsNamedWithItsLine) {
  std::ofstream(dir_ / "sets.yaml") << "rigid_sets:\n  - name: wand\n    markers:\n"
                                       "      - {name: a, position: [0, 0, 0]}\n";
  const MarkersRun r = run(args({"--rigid-sets", (dir_ / "sets.yaml").string()}));
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--rigid-sets"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir_ / "sets.yaml").string() + ":"), std::string::npos) << r.err;
}

// --hull: every frame's hull from the log's silhouettes, as syncap-host --hull builds it live:
// a mesh per frame whose volume is the ball's (a little more: the hull of 6 views), and the
// "hull" object of every JSON line with its per-view IoU.
TEST(MarkersCommandHull, BuildsEveryFramesHullFromTheLogsSilhouettes) {
  const fs::path dir =
      fs::temp_directory_path() / ("syncap_markers_hull_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::vector<sensor::CameraModel> cameras = hull::test::person_cameras(6);
  sensor::write_cameras(dir / "cameras.json", cameras);
  test_logs::write_ball_log(dir / "ball.lcmlog", cameras, 3);
  const MarkersRun r = run({"--input", "lcmlog:" + (dir / "ball.lcmlog").string(), "--calibration",
                            (dir / "cameras.json").string(), "--out", (dir / "out").string(),
                            "--hull", "--hull-iou", "--hull-meshes", (dir / "hull").string()});
  EXPECT_EQ(r.status, kExitOk) << r.out << r.err;
  EXPECT_NE(r.out.find("3 hulls"), std::string::npos) << r.out;
  const double ball = 4.0 / 3.0 * std::numbers::pi * 300.0 * 300.0 * 300.0;
  for (int frame = 0; frame < 3; ++frame) {
    const fs::path mesh = dir / "hull" / ("hull_" + std::to_string(frame) + ".ply");
    ASSERT_TRUE(fs::exists(mesh)) << mesh;
    const double volume = CGAL::Polygon_mesh_processing::volume(hull::read_mesh(mesh));
    EXPECT_GT(volume, ball);
    EXPECT_LT(volume, 1.15 * ball);
  }
  std::ifstream jsonl(dir / "out" / "markers.jsonl");
  std::string line;
  int lines_with_hull = 0;
  while (std::getline(jsonl, line))
    if (line.find("\"hull\"") != std::string::npos &&
        line.find("\"view_iou\"") != std::string::npos)
      ++lines_with_hull;
  EXPECT_EQ(lines_with_hull, 3);
  fs::remove_all(dir);
}

TEST_F(MarkersCommandTest, HelpIsComplete) {
  const MarkersRun r = run({"--help"});
  EXPECT_EQ(r.status, kExitOk);
  test::expect_help_mentions(
      r.out, {"--input", "--calibration", "--out-dir", "--camera-ids", "--volume", "--sigma-px",
              "--tolerance-px", "--keep-not-round", "--acceleration", "--rigid-sets", "--max-lag",
              "--hull", "--hull-method", "--hull-iou", "--hull-meshes"});
}

}  // namespace
}  // namespace syncap::tools
