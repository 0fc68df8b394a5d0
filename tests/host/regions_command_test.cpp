// `syncap regions`: per fitted frame of a host's frame lines and per camera of a cameras.json,
// the body's search region as a clip_polygon_t of kind search; bad input is named.
#include "regions_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "body/hanim_model.hpp"
#include "fitting/pose_parameters.hpp"
#include "help_check.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/test_cameras.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

struct RegionsRun {
  int status = -1;
  std::vector<nlohmann::json> lines;
  std::string out, err;
};

RegionsRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  RegionsRun r;
  r.status = regions_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  if (r.out.starts_with("{")) {
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
      r.lines.push_back(nlohmann::json::parse(line));
  }
  return r;
}

class RegionsCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string stem =
        (std::filesystem::temp_directory_path() / ("syncap_regions_" + std::to_string(::getpid())))
            .string();
    cameras_ = stem + ".json";
    bodies_ = stem + ".jsonl";
    sensor::CameraModel a = sensor::test::basler_camera();  // id 3
    sensor::CameraModel b = a;
    b.id = 4;
    b.exterior = sensor::test::looking_at({-4000, 1500, 2200}, {0, 0, 1000});
    sensor::write_cameras(cameras_, {a, b});
    const fitting::PoseParameters parameters(body::hanim_skeleton());
    const auto rest = parameters.rest();
    const nlohmann::json pose(std::vector<double>(rest.begin(), rest.end()));
    std::ofstream(bodies_)
        << R"({"frame":10,"complete":true,"cameras":{},"body":{"flags":0,"parameters":)"
        << pose.dump() << "}}\n"
        << R"({"frame":11,"complete":true,"cameras":{},"body":{"flags":2}})"
        << "\n"
        << R"({"frame":12,"complete":true,"cameras":{},"body":{"flags":0,"parameters":)"
        << pose.dump() << "}}\n";
  }
  void TearDown() override {
    std::filesystem::remove(cameras_);
    std::filesystem::remove(bodies_);
  }
  std::string cameras_, bodies_;
};

TEST_F(RegionsCommandTest, OneSearchRegionPerCameraAndFittedFrame) {
  const RegionsRun r =
      run({"--cameras", cameras_, "--bodies", bodies_, "--lead", "2", "--frames", "3"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  ASSERT_EQ(r.lines.size(), 4u);  // frames 10 and 12 (11 has no fit) x cameras 3 and 4
  EXPECT_EQ(r.lines[0]["camera_id"], 3);
  EXPECT_EQ(r.lines[1]["camera_id"], 4);
  EXPECT_EQ(r.lines[0]["region"], "search");
  EXPECT_EQ(r.lines[0]["frame_number"], 12);
  EXPECT_EQ(r.lines[2]["frame_number"], 14);
  EXPECT_EQ(r.lines[0]["valid_frames"], 3);
  EXPECT_GE(r.lines[0]["num_points"].get<int>(), 3);
  EXPECT_EQ(r.lines[0]["image_width"], 1280);
  const RegionsRun one = run({"--cameras", cameras_, "--bodies", bodies_, "--camera", "4"});
  ASSERT_EQ(one.lines.size(), 2u);
  EXPECT_EQ(one.lines[0]["camera_id"], 4);
}

TEST_F(RegionsCommandTest, BadInputIsNamed) {
  std::ofstream(bodies_, std::ios::app) << "{\"frame\":\"x\"}\n";
  RegionsRun r = run({"--cameras", cameras_, "--bodies", bodies_});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find(bodies_ + ":4"), std::string::npos) << r.err;
  r = run({"--cameras", cameras_, "--bodies", "/nonexistent.jsonl"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("/nonexistent.jsonl"), std::string::npos) << r.err;
  r = run({"--cameras", cameras_, "--bodies", bodies_, "--publish"});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--publish needs --command-key"), std::string::npos) << r.err;
  std::ofstream(bodies_) << R"({"frame":11,"complete":true,"cameras":{},"body":{"flags":2}})"
                         << "\n";
  r = run({"--cameras", cameras_, "--bodies", bodies_});
  EXPECT_EQ(r.status, kExitReportedErrors);
  EXPECT_NE(r.err.find("no frame with a fitted body"), std::string::npos) << r.err;
}

TEST_F(RegionsCommandTest, HelpIsComplete) {
  const RegionsRun r = run({"--help"});
  EXPECT_EQ(r.status, kExitOk);
  syncap::test::expect_help_mentions(
      r.out, {"usage: syncap regions --calibration FILE --bodies FRAMES.jsonl", "--margin-px PX",
              "(default 25)", "--lead N", "(default 1)", "--frames N", "--camera ID", "--publish",
              "--command-key FILE", "--lcm-url URL", "Exit status: 0 done"});
}

}  // namespace
}  // namespace syncap::tools
