#include "sensor/camera_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

std::vector<CameraModel> two_cameras() {
  std::mt19937 rng(41);
  CameraModel a = test::basler_camera();
  a.id = 0;
  CameraModel b = test::random_camera(rng, true);
  b.id = 7;
  CameraStdDevs s;
  s.interior = {1e-3, 2e-3, 3e-3, 1e-5, 1e-7, 0.0, 1e-6, 2e-6, 1e-5, 2e-5};
  s.exterior = {0.5, 0.6, 0.7, 1e-4, 2e-4, 3e-4};
  b.std_devs = s;
  return {a, b};
}

void expect_same(const InteriorOrientation& a, const InteriorOrientation& b) {
  EXPECT_EQ(interior_block(a), interior_block(b));
}
void expect_same(const ExteriorOrientation& a, const ExteriorOrientation& b) {
  EXPECT_EQ(exterior_block(a), exterior_block(b));
}

TEST(CameraFile, WriteThenReadGivesTheSameCamerasBitForBit) {
  const auto cameras = two_cameras();
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("syncap-cameras-" + std::to_string(getpid()) + ".json");
  write_cameras(file, cameras);
  const auto read = read_cameras(file);
  std::filesystem::remove(file);
  ASSERT_EQ(read.size(), cameras.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].id, cameras[i].id);
    EXPECT_EQ(read[i].sensor.width_px, cameras[i].sensor.width_px);
    EXPECT_EQ(read[i].sensor.height_px, cameras[i].sensor.height_px);
    EXPECT_EQ(read[i].sensor.pixel_width_mm, cameras[i].sensor.pixel_width_mm);
    EXPECT_EQ(read[i].sensor.pixel_height_mm, cameras[i].sensor.pixel_height_mm);
    expect_same(read[i].interior, cameras[i].interior);
    expect_same(read[i].exterior, cameras[i].exterior);
    ASSERT_EQ(read[i].std_devs.has_value(), cameras[i].std_devs.has_value());
    if (read[i].std_devs) {
      expect_same(read[i].std_devs->interior, cameras[i].std_devs->interior);
      expect_same(read[i].std_devs->exterior, cameras[i].std_devs->exterior);
    }
  }
  EXPECT_EQ(format_cameras(read), format_cameras(cameras));
}

TEST(CameraFile, DocumentedExampleReads) {
  // The example of docs/reference/camera-model.md.
  const char* text = R"({
  "cameras": [
    {
      "id": 3,
      "image_size": [1280, 1024],
      "pixel_size": [0.0067, 0.0067],
      "c": 6.1, "xp": 0.021, "yp": -0.034,
      "k1": 2.1e-3, "k2": -3.0e-5, "k3": 1.0e-7, "p1": 2.0e-5, "p2": -1.5e-5,
      "sc": 1.2e-4, "sh": -6.0e-5,
      "X0": 4200.0, "Y0": -800.0, "Z0": 2300.0,
      "omega": 1.275273, "phi": -0.047836, "kappa": 1.397131,
      "std": {"c": 0.002, "xp": 0.001, "yp": 0.001, "k1": 1e-5, "k2": 1e-7, "k3": 0,
              "p1": 1e-6, "p2": 1e-6, "sc": 1e-5, "sh": 1e-5,
              "X0": 0.9, "Y0": 0.7, "Z0": 1.1, "omega": 1e-4, "phi": 1e-4, "kappa": 1e-4}
    }
  ]
})";
  const auto cameras = parse_cameras(text, "cameras.json");
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].id, 3);
  EXPECT_EQ(cameras[0].sensor.width_px, 1280);
  EXPECT_EQ(cameras[0].interior.c, 6.1);
  EXPECT_EQ(cameras[0].exterior.kappa, 1.397131);
  ASSERT_TRUE(cameras[0].std_devs.has_value());
  EXPECT_EQ(cameras[0].std_devs->exterior.Z0, 1.1);
}

// The error for a camera file whose first camera (id 3) was changed by `edit`.
std::string error_after(const std::function<void(nlohmann::json&)>& edit) {
  auto cameras = two_cameras();
  cameras[0].id = 3;
  nlohmann::json document = nlohmann::json::parse(format_cameras(cameras));
  edit(document["cameras"][0]);
  try {
    parse_cameras(document.dump(), "cameras.json");
  } catch (const CameraFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(CameraFile, ErrorsNameTheFileTheCameraAndTheField) {
  using nlohmann::json;
  EXPECT_EQ(error_after([](json& c) { c["c"] = -6.0; }),
            "cameras.json: camera 3: field \"c\" must be a positive number");
  EXPECT_EQ(error_after([](json& c) { c["c"] = "6"; }),
            "cameras.json: camera 3: field \"c\" must be a number");
  EXPECT_EQ(error_after([](json& c) { c.erase("kappa"); }),
            "cameras.json: camera 3: field \"kappa\" is missing");
  EXPECT_EQ(error_after([](json& c) { c["k4"] = 0.0; }),
            "cameras.json: camera 3: field \"k4\" is unknown");
  EXPECT_EQ(error_after([](json& c) {
              c["image_size"] = {1280.5, 1024};
            }),
            "cameras.json: camera 3: field \"image_size\" must be [width, height] in pixels, two "
            "positive integers");
  EXPECT_EQ(error_after([](json& c) { c["pixel_size"] = {0.0067}; }),
            "cameras.json: camera 3: field \"pixel_size\" must be [width, height] in mm, two "
            "positive numbers");
  EXPECT_EQ(error_after([](json& c) { c["sc"] = 1.5; }),
            "cameras.json: camera 3: fields \"sc\" and \"sh\" must satisfy 1 - sc - sh^2 > 0 (an "
            "invertible affinity)");
  EXPECT_EQ(error_after([](json& c) {
              c["std"] = json::object();
              c["std"]["c"] = 0.1;
            }),
            "cameras.json: camera 3: field \"std.xp\" is missing");
  EXPECT_EQ(error_after([](json& c) {
              c["std"] = nlohmann::json::parse(format_cameras(two_cameras()))["cameras"][1]["std"];
              c["std"]["phi"] = -1.0;
            }),
            "cameras.json: camera 3: field \"std.phi\" must be a non-negative number");
  EXPECT_EQ(error_after([](json& c) { c["id"] = 100; }),
            "cameras.json: cameras[0]: field \"id\" must be an integer from 0 to 99");
  EXPECT_EQ(error_after([](json& c) { c["id"] = 7; }),
            "cameras.json: cameras[1]: id 7 is already used by cameras[0]");
}

TEST(CameraFile, ErrorsForTheFileAsAWhole) {
  const auto message = [](const std::string& text) {
    try {
      parse_cameras(text, "setup/cameras.json");
    } catch (const CameraFileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("[]"),
            "setup/cameras.json: the top level must be an object with a \"cameras\" array");
  EXPECT_EQ(message(R"({"cameras": [], "units": "mm"})"),
            "setup/cameras.json: field \"units\" is unknown");
  EXPECT_EQ(message(R"({"cameras": [42]})"), "setup/cameras.json: cameras[0]: must be an object");
  EXPECT_EQ(message(R"({"cameras": [)").rfind("setup/cameras.json: not valid JSON: ", 0), 0u);
  EXPECT_TRUE(parse_cameras(R"({"cameras": []})", "x").empty());
  // Found by the fuzzer (issue 15): a number beyond double's range was JSON's out_of_range.
  EXPECT_EQ(
      message(R"({"cameras": [], "x": 1e99999})").rfind("setup/cameras.json: not valid JSON: ", 0),
      0u);

  try {
    read_cameras("/nonexistent/cameras.json");
    FAIL() << "no error";
  } catch (const CameraFileError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/cameras.json: cannot open for reading");
  }
}

TEST(CameraFile, QualityBlockRoundTripsAndIsChecked) {
  CameraSet set{two_cameras(), CalibrationQuality{}};
  set.quality->sigma0_px = 0.11;
  set.quality->rms_px = 0.125;
  set.quality->per_camera_rms_px = {{0, 0.12}, {7, 0.13}};
  set.quality->observations = 1800;
  set.quality->outliers_removed = 3;
  set.quality->wand_length_mean_mm = 1000.02;
  set.quality->wand_length_sd_mm = 0.21;
  const CameraSet back = parse_camera_set(format_camera_set(set), "q.json");
  ASSERT_TRUE(back.quality.has_value());
  EXPECT_EQ(back.quality->rms_px, 0.125);
  EXPECT_EQ(back.quality->per_camera_rms_px, set.quality->per_camera_rms_px);
  EXPECT_EQ(back.quality->observations, 1800);
  EXPECT_EQ(back.quality->wand_length_sd_mm, 0.21);
  EXPECT_EQ(parse_cameras(format_camera_set(set), "q.json").size(), 2u);

  set.quality->wand_length_mean_mm.reset();  // LED mode: written as null, read as absent
  set.quality->wand_length_sd_mm.reset();
  const std::string led = format_camera_set(set);
  EXPECT_NE(led.find("\"wand_length_mean_mm\": null"), std::string::npos);
  EXPECT_FALSE(parse_camera_set(led, "q.json").quality->wand_length_mean_mm.has_value());

  nlohmann::json j = nlohmann::json::parse(format_camera_set(set));
  j["quality"]["per_camera_rms_px"]["x"] = 0.1;
  try {
    parse_camera_set(j.dump(), "q.json");
    FAIL() << "a bad camera key was accepted";
  } catch (const CameraFileError& e) {
    EXPECT_STREQ(e.what(),
                 "q.json: field \"quality.per_camera_rms_px.x\" is not a camera id (0-99)");
  }
  j = nlohmann::json::parse(format_camera_set(set));
  j["quality"].erase("rms_px");
  EXPECT_THROW(parse_camera_set(j.dump(), "q.json"), CameraFileError);
  // Found by fuzzing: a count beyond a long's range was cast (undefined behaviour).
  for (const double bad : {3.2e26, 12.5}) {
    j = nlohmann::json::parse(format_camera_set(set));
    j["quality"]["outliers_removed"] = bad;
    try {
      parse_camera_set(j.dump(), "q.json");
      FAIL() << bad << " was accepted as a count";
    } catch (const CameraFileError& e) {
      EXPECT_STREQ(e.what(),
                   "q.json: field \"quality.outliers_removed\" must be a whole number below 9e15");
    }
  }
}

}  // namespace
}  // namespace syncap::sensor
