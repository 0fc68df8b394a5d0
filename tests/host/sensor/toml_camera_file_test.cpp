// anipose / Pose2Sim camera files (sensor/toml_camera_file.hpp): read as OpenCV cameras with the
// lens kept, the length unit told from the rig's size, errors naming the file, table and key.
#include "sensor/toml_camera_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sensor/camera_file.hpp"

namespace syncap::sensor {
namespace {

namespace fs = std::filesystem;

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path file = fs::path(::testing::TempDir()) / name;
  std::ofstream(file) << text;
  return file;
}

// What Pose2Sim writes (translation in metres; the tables named after the cameras).
std::string pose2sim_table(const std::string& name, double tz) {
  return "[" + name + "]\nname = \"" + name +
         "\"\nsize = [ 1920.0, 1080.0,]\n"
         "matrix = [ [ 1500.0, 0.0, 960.0,], [ 0.0, 1500.0, 540.0,], [ 0.0, 0.0, 1.0,],]\n"
         "distortions = [ -0.21, 0.05, 0.001, -0.0005,]\n"
         "rotation = [ 0.1, -2.0, 0.3,]\ntranslation = [ 0.1, 0.2, " +
         std::to_string(tz) + ",]\nfisheye = false\n\n";
}

TEST(TomlCameraFile, Pose2SimMetresAreReadAsMillimetresWithTheLensKept) {
  const fs::path file = write_file("pose2sim_calib.toml", pose2sim_table("cam_01", 3.5) +
                                                              pose2sim_table("cam_02", 4.0) +
                                                              "[metadata]\nadjusted = false\n");
  const TomlCameraFile read = read_toml_camera_file(file);
  ASSERT_EQ(read.cameras.size(), 2u);
  EXPECT_TRUE(read.unit_inferred);
  EXPECT_EQ(read.length_unit_mm, 1000.0);
  EXPECT_EQ(read.cameras[0].id, 1);
  EXPECT_EQ(read.cameras[1].id, 2);
  EXPECT_NEAR(read.cameras[0].camera.tvec[2], 3500.0, 1e-9);
  EXPECT_EQ(read.cameras[0].camera.distortion[0], -0.21);
  EXPECT_EQ(read.cameras[0].camera.distortion[4], 0.0);  // four coefficients: k3 = 0

  const std::vector<CameraModel> cameras = read_cameras(file);
  ASSERT_EQ(cameras.size(), 2u);
  ASSERT_TRUE(cameras[1].opencv_lens.has_value());
  EXPECT_EQ(cameras[1].opencv_lens->distortion[0], -0.21);
  EXPECT_EQ(cameras[1].sensor.width_px, 1920);
}

TEST(TomlCameraFile, MillimetresAreToldFromTheRigsSizeOrGiven) {
  const fs::path file = write_file("anipose_mm.toml", pose2sim_table("cam_0", 3500.0));
  const TomlCameraFile inferred = read_toml_camera_file(file);
  EXPECT_EQ(inferred.length_unit_mm, 1.0);
  EXPECT_NEAR(inferred.cameras[0].camera.tvec[2], 3500.0, 1e-9);
  const TomlCameraFile given = read_toml_camera_file(file, 10.0);  // cm
  EXPECT_FALSE(given.unit_inferred);
  EXPECT_NEAR(given.cameras[0].camera.tvec[2], 35000.0, 1e-9);
}

TEST(TomlCameraFile, TablesWithoutNumbersAreNumberedInOrder) {
  const fs::path file =
      write_file("named.toml", pose2sim_table("left", 3.0) + pose2sim_table("right", 3.0));
  const TomlCameraFile read = read_toml_camera_file(file);
  ASSERT_EQ(read.cameras.size(), 2u);
  EXPECT_EQ(read.cameras[0].id, 0);
  EXPECT_EQ(read.cameras[1].id, 1);
}

void expect_error(const fs::path& file, const std::string& part) {
  try {
    read_toml_camera_file(file);
    ADD_FAILURE() << "no error for " << file;
  } catch (const CameraFileError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(TomlCameraFile, ErrorsNameTheFileTheTableAndTheKey) {
  std::string text = pose2sim_table("cam_3", 3.0);
  const fs::path fisheye =
      write_file("fisheye.toml", text.replace(text.find("fisheye = false"), 15, "fisheye = true"));
  expect_error(fisheye, fisheye.string() + ": [cam_3]: key \"fisheye\" is true");

  text = pose2sim_table("cam_3", 3.0);
  const fs::path no_matrix =
      write_file("no_matrix.toml",
                 text.erase(text.find("matrix"), text.find("distortions") - text.find("matrix")));
  expect_error(no_matrix, no_matrix.string() + ": [cam_3]: key \"matrix\" is missing");

  text = pose2sim_table("cam_3", 3.0);
  const fs::path short_rotation = write_file(
      "short_rotation.toml", text.replace(text.find("0.1, -2.0, 0.3,"), 15, "0.1, -2.0,"));
  expect_error(short_rotation, "key \"rotation\" must hold 3 numbers, not 2");

  const fs::path broken = write_file("broken.toml", "[cam_0]\nsize = [1, \n");
  expect_error(broken, broken.string() + ":");
  expect_error(broken, "not valid TOML");

  const fs::path empty = write_file("empty.toml", "[metadata]\nerror = 0.1\n");
  expect_error(empty, "no camera tables");
}

TEST(TomlCameraFile, IsToldByItsExtension) {
  EXPECT_TRUE(is_toml_camera_file("a/Calib.TOML"));
  EXPECT_FALSE(is_toml_camera_file("cameras.json"));
}

}  // namespace
}  // namespace syncap::sensor
