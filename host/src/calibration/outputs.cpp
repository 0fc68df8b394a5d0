#include "calibration/outputs.hpp"

#include <fstream>
#include <stdexcept>

#include "calibration/exports.hpp"
#include "calibration/report.hpp"
#include "sdl/sdl.hpp"
#include "sensor/camera_file.hpp"

namespace syncap::calibration {
namespace {

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << text;
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": write error");
}

// The adjusted network: the final adjustment's values as the approximations of the input.
scene::Network adjusted_network(const CalibrationResult& result) {
  scene::Network network = result.network;
  const auto& r = result.adjustment;
  for (size_t m = 0; m < network.models.size(); ++m)
    network.models[m].interior = r.models[m].interior;
  for (size_t s = 0; s < network.stations.size(); ++s) {
    network.stations[s].exterior = r.stations[s].exterior;
    network.stations[s].has_approximation = true;
  }
  for (size_t p = 0; p < network.points.size() && p < r.points.size(); ++p) {
    if (!r.points[p].adjusted) continue;
    network.points[p].xyz = r.points[p].xyz;
    network.points[p].has_approximation = true;
  }
  return network;
}

}  // namespace

std::vector<std::filesystem::path> write_calibration(const CalibrationResult& result,
                                                     const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw std::runtime_error(folder.string() + ": cannot create the folder: " + ec.message());
  std::vector<std::filesystem::path> written;
  const auto put = [&](const char* name, const std::string& text) {
    write_text(folder / name, text);
    written.push_back(folder / name);
  };
  put("cameras.json", sensor::format_camera_set({result.cameras, result.quality}));
  put("report.txt", format_report_text(result.report));
  put("report.html", format_report_html(result.report));
  put("residuals.csv", format_residuals_csv(result.report));
  put("points.csv", format_points_csv(result.report));
  put("cameras.opencv.yaml", format_opencv_yaml(result.cameras));
  put("calibration.toml", format_calibration_toml(result.cameras, result.quality.rms_px));
  put("scene.sdl", sdl::write(adjusted_network(result)));
  return written;
}

}  // namespace syncap::calibration
