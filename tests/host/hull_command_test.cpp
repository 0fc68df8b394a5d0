// `syncap hull`: a synthetic sphere seen by four cameras from files (cameras.json and PNG
// masks) gives hull.ply and hull.obj and a good IoU per view; bad files are named. OpenCV-style
// camera files (YAML, JSON) with lens distortion give the hull of the ideal cameras.
#include "hull_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "help_check.hpp"
#include "hull/hull_scenes.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct HullRun {
  int status = -1;
  std::string out, err;
};

HullRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  HullRun r;
  r.status = hull_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

// cameras.json and masks/cam0N.png of a sphere seen by four cameras, in a fresh folder.
class HullCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_hull_command_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "masks");
    const std::vector<sensor::CameraModel> cameras = hull::test::ring_cameras(4);
    sensor::write_cameras(dir_ / "cameras.json", cameras);
    for (const hull::HullView& v : hull::test::views_of(hull::test::sphere_mesh(500.0), cameras))
      cv::imwrite((dir_ / "masks" / ("cam0" + std::to_string(v.camera.id) + ".png")).string(),
                  v.mask);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> args(const std::string& method = "exact") const {
    return {"--cameras", (dir_ / "cameras.json").string(), "--masks",  (dir_ / "masks").string(),
            "--out",     (dir_ / "out").string(),          "--method", method};
  }

  fs::path dir_;
};

TEST_F(HullCommand, WritesTheMeshesAndPrintsEachViewsIou) {
  for (const std::string method : {"exact", "polyhedral", "voxel"}) {
    const HullRun r = run(args(method));
    ASSERT_EQ(r.status, kExitOk) << r.err;
    EXPECT_TRUE(fs::file_size(dir_ / "out" / "hull.ply") > 0);
    EXPECT_TRUE(fs::file_size(dir_ / "out" / "hull.obj") > 0);
    EXPECT_NE(r.out.find("view camera 3 ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("reprojection IoU: min 0.9"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("mesh: closed yes, non-manifold vertices 0, self-intersecting no"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("time: "), std::string::npos) << r.out;
  }
}

// With the capture volume the hull stands on its floor (z = -300 cuts the 500 mm ball's bottom
// 200 mm off), and the output gives the extent in mm and the lowest point above the floor.
TEST_F(HullCommand, TheCaptureVolumesFloorClipsTheHull) {
  std::vector<std::string> a = args("polyhedral");
  a.insert(a.end(), {"--volume", "-2000,-2000,-300,2000,2000,2000"});
  const HullRun r = run(a);
  ASSERT_EQ(r.status, kExitOk) << r.err;
  EXPECT_NE(r.out.find("extent: x -5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", z -300.0.."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("floor: the hull's lowest point 0.0 mm above z = -300.0"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(" mm^3, area "), std::string::npos) << r.out;
  a.back() = "-2000,-2000,600,2000,2000,2000";  // above the ball: nothing left
  const HullRun missed = run(a);
  EXPECT_EQ(missed.status, kExitUsage);
  EXPECT_NE(missed.err.find("do not meet"), std::string::npos) << missed.err;
  a.back() = "1,2,3";
  EXPECT_EQ(run(a).status, kExitUsage);
}

TEST_F(HullCommand, AMaskTooManyIsNamed) {
  cv::imwrite((dir_ / "masks" / "cam04.png").string(), cv::Mat::zeros(480, 640, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("5 mask image(s) for 4 camera(s)"), std::string::npos) << r.err;
}

TEST_F(HullCommand, AnEmptyMaskNamesCameraAndFile) {
  cv::imwrite((dir_ / "masks" / "cam02.png").string(), cv::Mat::zeros(480, 640, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("camera 2 ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cam02.png): empty mask"), std::string::npos) << r.err;
}

TEST_F(HullCommand, AMaskOfTheWrongSizeIsNamed) {
  cv::imwrite((dir_ / "masks" / "cam01.png").string(), cv::Mat::zeros(240, 320, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("cam01.png): mask is 320x240, the camera's image 640x480"),
            std::string::npos)
      << r.err;
}

// The volume `syncap hull` prints ("volume V, area").
double printed_volume(const std::string& out) {
  const auto at = out.find(", volume ");
  return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 9));
}

// The ring cameras as OpenCV cameras with a strong lens (k1 -0.2: some 30 px at the corners),
// and each one's view of the sphere through that lens: the ideal mask warped by OpenCV's model.
class OpenCvHullCommand : public HullCommand {
 protected:
  void SetUp() override {
    HullCommand::SetUp();
    fs::create_directories(dir_ / "lens_masks");
    for (const sensor::CameraModel& camera : hull::test::ring_cameras(4)) {
      sensor::OpenCvCamera c = sensor::opencv_from_camera(camera);
      c.distortion = {-0.2, 0.05, 0.001, -0.0005, 0.0};
      const cv::Mat ideal =
          cv::imread((dir_ / "masks" / ("cam0" + std::to_string(camera.id) + ".png")).string(),
                     cv::IMREAD_GRAYSCALE);
      cv::imwrite((dir_ / "lens_masks" / ("cam0" + std::to_string(camera.id) + ".png")).string(),
                  through_lens(ideal, c));
      cameras_.push_back(c);
    }
  }
  // Each pixel of the distorted image shows what its ideal pixel shows.
  static cv::Mat through_lens(const cv::Mat& ideal, const sensor::OpenCvCamera& c) {
    std::vector<cv::Point2f> pixels, ideal_pixels;
    for (int v = 0; v < ideal.rows; ++v)
      for (int u = 0; u < ideal.cols; ++u) pixels.emplace_back(u, v);
    cv::undistortPoints(pixels, ideal_pixels, c.camera_matrix, c.distortion, cv::noArray(),
                        c.camera_matrix);
    cv::Mat map(ideal.size(), CV_32FC2, ideal_pixels.data());
    cv::Mat distorted;
    cv::remap(ideal, distorted, map, cv::noArray(), cv::INTER_NEAREST);
    return distorted;
  }
  // YAML with plain sequences, as a user writes it by hand; `distortion` false leaves it out.
  void write_yaml(const fs::path& file, bool distortion) const {
    std::ofstream out(file);
    out << "%YAML:1.0\ncameras:\n";
    for (const sensor::OpenCvCamera& c : cameras_) {
      const auto list = [](const double* v, int n) {
        std::string text = "[";
        for (int i = 0; i < n; ++i) text += (i ? ", " : "") + std::to_string(v[i]);
        return text + "]";
      };
      cv::Matx33d r;
      cv::Rodrigues(c.rvec, r);
      out << "  - image_size: [" << c.image_size.width << ", " << c.image_size.height << "]\n"
          << "    K: " << list(c.camera_matrix.val, 9) << "\n"
          << "    R: " << list(r.val, 9) << "\n"
          << "    t: " << list(c.tvec.val, 3) << "\n";
      if (distortion) out << "    distortion: " << list(c.distortion.val, 5) << "\n";
    }
  }
  std::vector<std::string> lens_args(const fs::path& cameras) const {
    return {"--cameras", cameras.string(),        "--masks",  (dir_ / "lens_masks").string(),
            "--out",     (dir_ / "out").string(), "--method", "polyhedral"};
  }
  std::vector<sensor::OpenCvCamera> cameras_;
};

TEST_F(OpenCvHullCommand, YamlAndJsonCamerasWithTheirLensGiveTheIdealCamerasHull) {
  const HullRun ideal = run(args("polyhedral"));
  ASSERT_EQ(ideal.status, kExitOk) << ideal.err;
  write_yaml(dir_ / "cameras.yaml", true);
  const HullRun yaml = run(lens_args(dir_ / "cameras.yaml"));
  ASSERT_EQ(yaml.status, kExitOk) << yaml.err;
  EXPECT_NE(yaml.out.find("reprojection IoU: min 0.99"), std::string::npos) << yaml.out;
  EXPECT_NEAR(printed_volume(yaml.out), printed_volume(ideal.out),
              0.01 * printed_volume(ideal.out));
  // The same cameras written by cv::FileStorage as JSON, K and R as OpenCV matrices, R as rvec.
  {
    cv::FileStorage json((dir_ / "cameras.json.tmp").string(),
                         cv::FileStorage::WRITE | cv::FileStorage::FORMAT_JSON);
    json << "cameras"
         << "[";
    for (const sensor::OpenCvCamera& c : cameras_) {
      json << "{"
           << "camera_matrix" << cv::Mat(c.camera_matrix) << "dist_coeffs" << cv::Mat(c.distortion)
           << "rvec" << cv::Mat(c.rvec) << "tvec" << cv::Mat(c.tvec) << "image_width"
           << c.image_size.width << "image_height" << c.image_size.height << "}";
    }
    json << "]";
  }
  fs::rename(dir_ / "cameras.json.tmp", dir_ / "opencv.json");
  const HullRun json = run(lens_args(dir_ / "opencv.json"));
  ASSERT_EQ(json.status, kExitOk) << json.err;
  EXPECT_NEAR(printed_volume(json.out), printed_volume(yaml.out), 1e-6 * printed_volume(yaml.out));
  // The lens matters: the same masks taken as ideal (k1 < 0 draws the outline inwards) give a
  // smaller hull.
  write_yaml(dir_ / "no_lens.yaml", false);
  const HullRun no_lens = run(lens_args(dir_ / "no_lens.yaml"));
  EXPECT_LT(printed_volume(no_lens.out), 0.99 * printed_volume(ideal.out)) << no_lens.out;
}

// The voxel method samples the masks through the same lens: its hull of the lens' masks is the
// hull of the ideal masks.
TEST_F(OpenCvHullCommand, TheVoxelMethodTakesTheLensToo) {
  std::vector<std::string> ideal_args = args("voxel");
  const HullRun ideal = run(ideal_args);
  ASSERT_EQ(ideal.status, kExitOk) << ideal.err;
  write_yaml(dir_ / "cameras.yaml", true);
  std::vector<std::string> lens = lens_args(dir_ / "cameras.yaml");
  lens.back() = "voxel";
  const HullRun voxel = run(lens);
  ASSERT_EQ(voxel.status, kExitOk) << voxel.err;
  EXPECT_NEAR(printed_volume(voxel.out), printed_volume(ideal.out),
              0.01 * printed_volume(ideal.out));
}

TEST_F(OpenCvHullCommand, ABrokenCameraFileNamesCameraAndField) {
  write_yaml(dir_ / "cameras.yaml", true);
  std::string text;
  {
    std::ifstream in(dir_ / "cameras.yaml");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto second_k = text.find("K:", text.find("K:") + 1);
  std::ofstream(dir_ / "broken.yaml")
      << text.substr(0, second_k) << "Kx" << text.substr(second_k + 1);
  HullRun r = run(lens_args(dir_ / "broken.yaml"));
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("broken.yaml: camera 1: K is missing"), std::string::npos) << r.err;
  std::ofstream(dir_ / "short.yaml") << "%YAML:1.0\ncameras:\n  - image_size: [640, 480]\n"
                                        "    K: [600, 0, 320, 0, 600, 240, 0, 0, 1]\n"
                                        "    R: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n    t: [0, 0]\n";
  r = run(lens_args(dir_ / "short.yaml"));
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("short.yaml: camera 0: t must hold 3 finite numbers"), std::string::npos)
      << r.err;
}

TEST(HullCommandUsage, HelpListsEveryOptionAndBadValuesAreNamed) {
  const HullRun help = run({"--help"});
  EXPECT_EQ(help.status, kExitOk);
  test::expect_help_mentions(
      help.out, {"--calibration", "--masks", "--out", "--method", "--simplify", "--threshold",
                 "--largest", "--resolution", "default 1", "Exit status"});
  const HullRun bad = run({"--cameras", "c", "--masks", "m", "--out", "o", "--method", "mesh"});
  EXPECT_EQ(bad.status, kExitUsage);
  EXPECT_NE(bad.err.find("--method"), std::string::npos) << bad.err;
  const HullRun missing =
      run({"--cameras", "/nonexistent.json", "--masks", "/nonexistent", "--out", "/tmp/x"});
  EXPECT_EQ(missing.status, kExitUsage);
  EXPECT_NE(missing.err.find("/nonexistent"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace syncap::tools
