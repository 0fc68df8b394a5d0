// The round trip on real measurements: the LED observations of four real cameras
// ($SYNCAP_DATA/calibration/strawlab-DATA20100906_134124, points.dat: per camera rows x, y, 1,
// one column per frame, NaN where unseen) written as SDL and read back exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "network_equality.hpp"
#include "sdl/sdl.hpp"

namespace syncap::sdl {
namespace {

std::filesystem::path data_dir() {
  const char* root = std::getenv("SYNCAP_DATA");
  return std::filesystem::path(root ? root : "../shared/data") / "calibration" /
         "strawlab-DATA20100906_134124";
}

TEST(SdlRealData, StrawlabLedObservationsRoundTrip) {
  const auto dir = data_dir();
  if (!std::filesystem::exists(dir / "points.dat")) {
    GTEST_SKIP() << "missing " << (dir / "points.dat").string();
  }
  std::ifstream points(dir / "points.dat");
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(points, line);) {
    std::istringstream fields(line);
    std::vector<double> row;
    // "nan" is read by strtod, not by operator>>.
    for (std::string field; fields >> field;) row.push_back(std::strtod(field.c_str(), nullptr));
    rows.push_back(std::move(row));
  }
  ASSERT_EQ(rows.size(), 12u);
  std::ifstream sizes(dir / "Res.dat");
  scene::Network network;
  for (int camera = 0; camera < 4; ++camera) {
    scene::CameraModel model;
    model.name = "sericomyia-mobile.local_" + std::to_string(camera);
    sizes >> model.sensor.width_px >> model.sensor.height_px;
    model.sensor.pixel_width_mm = model.sensor.pixel_height_mm = 0.006;  // not known: a guess
    model.interior.c = 4.0;
    network.models.push_back(model);
    scene::Station station;
    station.name = model.name;
    station.camera_id = camera;
    station.model = model.name;
    network.stations.push_back(station);
  }
  const size_t frames = rows[0].size();
  for (size_t frame = 0; frame < frames; ++frame) {
    const std::string point = "led" + std::to_string(frame);
    bool seen = false;
    for (int camera = 0; camera < 4; ++camera) {
      const double u = rows[3 * camera][frame];
      const double v = rows[3 * camera + 1][frame];
      if (std::isnan(u) || std::isnan(v)) continue;
      network.measurements.push_back(
          {network.stations[camera].name, point, u, v, 0.3, static_cast<int64_t>(frame)});
      seen = true;
    }
    if (seen) network.points.push_back({point, {}, false, {}});
  }
  ASSERT_GT(network.measurements.size(), 1000u);

  const std::string text = write(network);
  const scene::Network parsed = parse_string(text, "strawlab.sdl");
  testing::expect_same_network(network, parsed);
  EXPECT_EQ(write(parsed), text);
}

}  // namespace
}  // namespace syncap::sdl
