// `syncap cameras convert`: a camera file between cameras.json, OpenCV YAML and anipose/Pose2Sim
// TOML, the OpenCV lens carried exactly both ways, a thesis lens fitted with its residual said.
#include "cameras_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera.hpp"
#include "sensor/test_cameras.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct ConvertRun {
  int status = -1;
  std::string out, err;
};

ConvertRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  ConvertRun r;
  r.status = cameras_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

class CamerasConvert : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("cameras_convert_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // A studio camera with OpenCV's strong barrel lens, 3.6 m from the origin.
    std::ofstream(dir_ / "studio.yaml")
        << "%YAML:1.0\ncameras:\n  - id: 2\n    image_size: [644, 486]\n"
           "    camera_matrix: [490.76, 0, 334.69, 0, 493.26, 222.40, 0, 0, 1]\n"
           "    distortion: [-0.3687, 0.2032, 3.3e-4, 1.8e-5, -0.0712]\n"
           "    rvec: [-1.373, 0.496, 0.614]\n    tvec: [289.0, 1008.0, 3400.0]\n";
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// Projections of a few points in front of a camera.
std::vector<Eigen::Vector2d> pixels_of(const sensor::CameraModel& c) {
  std::vector<Eigen::Vector2d> pixels;
  for (double x : {-300.0, 0.0, 250.0}) {
    for (double y : {-200.0, 0.0, 300.0}) {
      const Eigen::Vector3d p =
          c.projection_centre() + 3000.0 * c.back_project({322.0 + x, 243.0 + y}).direction;
      pixels.push_back(c.project(p).pixel);
    }
  }
  return pixels;
}

TEST_F(CamerasConvert, OpenCvToJsonToTomlAndBackKeepsTheLensExactly) {
  const sensor::CameraModel original = sensor::read_cameras(path("studio.yaml")).at(0);
  ConvertRun r = run({"convert", path("studio.yaml"), path("cameras.json")});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("camera 2: 644x486, f 493.3 px"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("OpenCV lens (exact)"), std::string::npos) << r.out;
  r = run({"convert", path("cameras.json"), path("calib.toml")});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  r = run({"convert", path("calib.toml"), path("back.yaml")});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("translations taken in metres"), std::string::npos) << r.out;
  for (const char* file : {"cameras.json", "calib.toml", "back.yaml"}) {
    const std::vector<sensor::CameraModel> read = sensor::read_cameras(path(file));
    ASSERT_EQ(read.size(), 1u) << file;
    EXPECT_EQ(read[0].id, 2) << file;
    ASSERT_TRUE(read[0].opencv_lens) << file;
    EXPECT_EQ(read[0].opencv_lens->distortion, original.opencv_lens->distortion) << file;
    const std::vector<Eigen::Vector2d> a = pixels_of(original), b = pixels_of(read[0]);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - b[i]).norm(), 1e-6) << file;
  }
}

TEST_F(CamerasConvert, AThesisLensWrittenAsOpenCvSaysHowCloselyItFits) {
  sensor::write_cameras(path("basler.json"), {sensor::test::basler_camera()});
  const ConvertRun r = run({"convert", path("basler.json"), path("basler.yaml")});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("camera 3: 1280x1024"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("thesis lens (as OpenCV's: up to 0.0"), std::string::npos) << r.out;
}

TEST_F(CamerasConvert, TheTomlUnitCanBeGiven) {
  ASSERT_EQ(run({"convert", path("studio.yaml"), path("calib.toml")}).status, kExitOk);
  // The TOML holds metres (3.4 m); read as mm the camera is 3.4 mm from the origin.
  const ConvertRun r = run({"convert", path("calib.toml"), path("mm.json"), "--toml-unit-mm", "1"});
  ASSERT_EQ(r.status, kExitOk) << r.err;
  const sensor::CameraModel c = sensor::read_cameras(path("mm.json")).at(0);
  EXPECT_LT(c.projection_centre().norm(), 10.0);
}

TEST_F(CamerasConvert, BadInputIsNamed) {
  ConvertRun r = run({"convert", path("studio.yaml"), path("cameras.txt")});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("the extension must be .json, .yaml, .yml or .toml"), std::string::npos)
      << r.err;
  std::ofstream(path("broken.json")) << "{\"cameras\": [{\"id\": 1}]}";
  r = run({"convert", path("broken.json"), path("out.yaml")});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("broken.json: camera 1: field"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out.yaml")));
  r = run({});
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("usage: syncap cameras convert"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace syncap::tools
