// `syncap clip`: per camera of a cameras.json, the capture volume's outline as a clip polygon
// message; --remove sends polygons of no points; bad arguments and files are named.
#include "clip_command.hpp"
#include "syncap/proto/command_auth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "help_check.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/test_cameras.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

struct ClipRun {
  int status = -1;
  std::vector<nlohmann::json> lines;
  std::string out;  // the JSON lines, or --help
  std::string err;
};

ClipRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  ClipRun r;
  r.status = clip_command(args, out, err);
  r.out = out.str();
  if (r.out.starts_with("{")) {
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
      r.lines.push_back(nlohmann::json::parse(line));
  }
  r.err = err.str();
  return r;
}

class ClipCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = std::filesystem::temp_directory_path() /
            ("syncap_clip_" + std::to_string(::getpid()) + ".json");
    sensor::CameraModel a = sensor::test::basler_camera();  // id 3
    sensor::CameraModel b = a;
    b.id = 4;
    b.exterior = sensor::test::looking_at({-4000, 1500, 2200}, {0, 0, 1000});
    sensor::write_cameras(file_, {a, b});
  }
  void TearDown() override { std::filesystem::remove(file_); }
  std::filesystem::path file_;
};

TEST_F(ClipCommandTest, OneOutlinePerCameraInsideItsImage) {
  const ClipRun r = run({"--cameras", file_.string(), "--volume", "-1000,-1000,0,1000,1000,2000"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0]["camera_id"], 3);
  EXPECT_EQ(r.lines[1]["camera_id"], 4);
  for (const nlohmann::json& m : r.lines) {
    EXPECT_EQ(m["image_width"], 1280);
    const int n = m["num_points"];
    EXPECT_GE(n, 4);
    ASSERT_EQ(m["x"].size(), static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      EXPECT_GE(m["x"][i].get<int>(), 0);
      EXPECT_LT(m["x"][i].get<int>(), 1280);
      EXPECT_GE(m["y"][i].get<int>(), 0);
      EXPECT_LT(m["y"][i].get<int>(), 1024);
    }
  }
  // Sequences increase, so that an edge can tell a newer polygon.
  EXPECT_LT(r.lines[0]["sequence"].get<int64_t>(), r.lines[1]["sequence"].get<int64_t>());
}

// Polygon area (shoelace) of a message line.
double area_of(const nlohmann::json& m) {
  double twice = 0;
  const std::size_t n = m["x"].size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    twice += m["x"][i].get<double>() * m["y"][j].get<double>() -
             m["x"][j].get<double>() * m["y"][i].get<double>();
  }
  return std::abs(twice) / 2;
}

// --floor: the volume's floor plane (grown by --floor-extent) as REGION_FLOOR messages; the
// floor's centre is inside, the top of the volume's centre line is not, for the camera looking
// from the side (id 4, 2.2 m up, 4.3 m away).
TEST_F(ClipCommandTest, FloorIsTheVolumesFloorPlaneGrown) {
  const std::vector<std::string> base{"--cameras", file_.string(), "--volume",
                                      "-1000,-1000,0,1000,1000,2000", "--floor"};
  const ClipRun r = run(base);
  ASSERT_EQ(r.status, kExitOk) << r.err;
  ASSERT_EQ(r.lines.size(), 2u);
  for (const nlohmann::json& m : r.lines) EXPECT_EQ(m["region"], "floor");
  const sensor::CameraModel side = sensor::read_cameras(file_)[1];
  std::vector<cv::Point> polygon;
  for (std::size_t i = 0; i < r.lines[1]["x"].size(); ++i)
    polygon.emplace_back(r.lines[1]["x"][i].get<int>(), r.lines[1]["y"][i].get<int>());
  const auto inside = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d px = side.project(p).pixel;
    return cv::pointPolygonTest(polygon, cv::Point2f(float(px.x()), float(px.y())), false) > 0;
  };
  EXPECT_TRUE(inside({0, 0, 0}));
  EXPECT_TRUE(inside({1800, 0, 0}));  // beyond the volume, within the extent: a shadow's place
  EXPECT_FALSE(inside({0, 0, 2000}));
  std::vector<std::string> tight = base;
  tight.insert(tight.end(), {"--floor-extent", "0"});
  const ClipRun small = run(tight);
  ASSERT_EQ(small.status, kExitOk) << small.err;
  EXPECT_LT(area_of(small.lines[1]), area_of(r.lines[1]) * 0.8);
}

TEST_F(ClipCommandTest, OnlyTheCamerasAskedForAndRemove) {
  const ClipRun r = run({"--cameras", file_.string(), "--remove", "--camera", "4"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_EQ(r.lines[0]["camera_id"], 4);
  EXPECT_EQ(r.lines[0]["num_points"], 0);
  // --camera repeats, one id each time.
  const ClipRun both =
      run({"--cameras", file_.string(), "--remove", "--camera", "3", "--camera", "4"});
  ASSERT_EQ(both.status, kExitOk) << both.err;
  EXPECT_EQ(both.lines.size(), 2u);
  const ClipRun two_ids = run({"--cameras", file_.string(), "--remove", "--camera", "3", "4"});
  EXPECT_EQ(two_ids.status, kExitUsage);
  EXPECT_NE(two_ids.err.find("unexpected argument '4'"), std::string::npos) << two_ids.err;
}

TEST_F(ClipCommandTest, AVolumeACameraCannotSeeIsNamedAndTheOthersStillGo) {
  // A volume around camera 4 itself reaches behind it: no clip there, and said so.
  const ClipRun r =
      run({"--cameras", file_.string(), "--volume", "-4500,1000,1700,-3500,2000,2700"});
  EXPECT_EQ(r.status, kExitReportedErrors);
  EXPECT_NE(r.err.find("camera 4"), std::string::npos) << r.err;
  bool camera4 = false;
  for (const nlohmann::json& m : r.lines) {
    if (m["camera_id"] != 4) continue;
    camera4 = true;
    EXPECT_EQ(m["num_points"], 0);
  }
  EXPECT_TRUE(camera4);
}

TEST_F(ClipCommandTest, BadArgumentsAndFilesAreNamed) {
  ClipRun r = run({"--cameras", file_.string(), "--volume", "1,2,3"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--volume: '1,2,3'"), std::string::npos) << r.err;
  r = run({"--cameras", file_.string(), "--volume", "nan,0,0,1,1,1"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--volume: 'nan,0,0,1,1,1'"), std::string::npos) << r.err;
  for (const std::string margin : {"nan", "-1", "1001", "8px"}) {
    r = run({"--cameras", file_.string(), "--remove", "--margin-px", margin});
    EXPECT_EQ(r.status, kExitUsage) << margin;
    EXPECT_NE(r.err.find("--margin-px: '" + margin + "'"), std::string::npos) << r.err;
  }
  r = run({"--cameras", file_.string(), "--remove", "--camera", "1.5"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--camera: '1.5'"), std::string::npos) << r.err;
  r = run({"--cameras", file_.string(), "--volume", "0,0,0,1,1,1", "--remove"});
  EXPECT_EQ(r.status, kExitUsage);
  r = run({"--cameras", "/nonexistent/cameras.json", "--remove"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("/nonexistent/cameras.json"), std::string::npos) << r.err;
  r = run({"--cameras", file_.string(), "--remove", "--camera", "7"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("none of the cameras"), std::string::npos) << r.err;
}

// Edges apply only signed polygons: --publish needs the installation's key, and every published
// polygon carries a MAC of it (memq://: LCM's in-process provider, no network).
TEST_F(ClipCommandTest, PublishedPolygonsAreSignedWithTheKey) {
  ClipRun r = run({"--cameras", file_.string(), "--remove", "--publish", "--lcm-url", "memq://"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--publish needs --command-key FILE"), std::string::npos) << r.err;
  const std::string key_file = file_.string() + ".key";
  const proto::CommandKey key = proto::CommandKey::generate();
  key.save(key_file, /*replace=*/true);
  r = run({"--cameras", file_.string(), "--remove", "--publish", "--lcm-url", "memq://", "--key",
           key_file});
  std::filesystem::remove(key_file);
  ASSERT_EQ(r.status, kExitOk) << r.err;
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_NE(r.lines[0]["sender"], 0);
  EXPECT_NE(r.lines[0]["mac"], std::string(64, '0'));
  EXPECT_LT(r.lines[0]["sequence"].get<int64_t>(), r.lines[1]["sequence"].get<int64_t>());
}

// Issue 15: an unknown last option said "needs a value".
TEST_F(ClipCommandTest, UnknownOptionIsNamedAsUnknownWherever) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--cameras", file_.string(), "--remove", "--x"},
        std::vector<std::string>{"--x", "1", "--cameras", file_.string(), "--remove"}}) {
    const ClipRun r = run(args);
    EXPECT_EQ(r.status, kExitUsage);
    EXPECT_EQ(r.err.rfind("syncap clip: unknown option '--x'\n", 0), 0u) << r.err;
  }
}

// --help: every option with its meaning and default, both forms, the exit statuses.
TEST_F(ClipCommandTest, HelpIsComplete) {
  const ClipRun r = run({"--help"});
  EXPECT_EQ(r.status, kExitOk);
  syncap::test::expect_help_mentions(
      r.out,
      {"usage: syncap clip --calibration FILE --volume", "syncap clip --calibration FILE --remove",
       "--calibration FILE", "--volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX", "--margin-px PX",
       "(default 8)", "--camera ID", "(repeatable)", "--remove", "--publish", "--command-key FILE",
       "--lcm-url URL", "(default udpm://", "--floor", "--floor-extent MM", "(default 1000)",
       "Exit status: 0 done"});
}

}  // namespace
}  // namespace syncap::tools
