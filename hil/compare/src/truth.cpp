#include "truth.hpp"

#include <set>
#include <tuple>

#include "csv_reader.hpp"
#include "input_error.hpp"
#include "sensor/camera_file.hpp"

namespace syncap::compare {
namespace {

int small_integer(const CsvRow& row, std::size_t column, const char* what) {
  const long value = row.integer(column);
  if (value < 0 || value > 1'000'000) {
    row.fail(std::string(what) + " " + std::to_string(value) + " is out of range");
  }
  return static_cast<int>(value);
}

}  // namespace

TruthFrames read_frames(const std::filesystem::path& file) {
  TruthFrames frames;
  read_csv(file, {"frame", "time_s", "phase", "phase_type", "led_on", "gain"},
           [&](const CsvRow& row) {
             TruthFrame f{row.integer(0),           row.number(1), small_integer(row, 2, "phase"),
                          std::string(row.text(3)), row.flag(4),   row.number(5)};
             if (f.phase_type.empty()) row.fail("field phase_type is empty");
             if (!frames.emplace(f.frame, f).second) {
               row.fail("frame " + std::to_string(f.frame) + " appears twice");
             }
           });
  if (frames.empty()) throw InputError(file.string() + ": no frames");
  return frames;
}

std::map<int, sensor::CameraModel> read_true_cameras(const std::filesystem::path& cameras_json) {
  std::map<int, sensor::CameraModel> cameras;
  try {
    for (auto& camera : sensor::read_cameras(cameras_json)) cameras[camera.id] = std::move(camera);
  } catch (const sensor::CameraFileError& e) {
    throw InputError(e.what());  // already names the file, the camera and the field
  }
  if (cameras.empty()) throw InputError(cameras_json.string() + ": no cameras");
  return cameras;
}

ImageSizes read_image_sizes(const std::filesystem::path& cameras_json) {
  ImageSizes images;
  for (const auto& [id, camera] : read_true_cameras(cameras_json)) {
    images[id] = {camera.sensor.width_px, camera.sensor.height_px};
  }
  return images;
}

std::vector<Projection> read_projections(const std::filesystem::path& file,
                                         const TruthFrames& frames, const ImageSizes& images) {
  std::vector<Projection> projections;
  std::set<std::tuple<long, int, int>> seen;
  read_csv(file, {"frame", "camera", "target", "x_px", "y_px", "radius_px", "visible"},
           [&](const CsvRow& row) {
             Projection p{row.integer(0),
                          small_integer(row, 1, "camera"),
                          small_integer(row, 2, "target"),
                          row.number(3),
                          row.number(4),
                          row.number(5),
                          row.flag(6)};
             if (!frames.contains(p.frame)) {
               row.fail("frame " + std::to_string(p.frame) + " is not in frames.csv");
             }
             if (!images.contains(p.camera)) {
               row.fail("camera " + std::to_string(p.camera) + " is not in cameras.json");
             }
             if (p.radius_px < 0) row.fail("field radius_px is negative");
             if (!seen.emplace(p.frame, p.camera, p.target).second) {
               row.fail("frame " + std::to_string(p.frame) + " camera " + std::to_string(p.camera) +
                        " target " + std::to_string(p.target) + " appears twice");
             }
             projections.push_back(p);
           });
  return projections;
}

std::vector<std::array<double, 3>> read_target_positions(const std::filesystem::path& file) {
  std::vector<std::array<double, 3>> targets;
  read_csv(file, {"frame", "target", "X_mm", "Y_mm", "Z_mm", "radius_mm"}, [&](const CsvRow& row) {
    targets.push_back({row.number(2), row.number(3), row.number(4)});
  });
  return targets;
}

Truth read_truth(const std::filesystem::path& dir) {
  Truth truth;
  truth.dir = dir;
  truth.frames = read_frames(dir / "truth" / "frames.csv");
  truth.cameras = read_true_cameras(dir / "cameras.json");
  for (const auto& [id, camera] : truth.cameras) {
    truth.images[id] = {camera.sensor.width_px, camera.sensor.height_px};
  }
  for (const Projection& p :
       read_projections(dir / "truth" / "projections.csv", truth.frames, truth.images)) {
    truth.projections[{p.frame, p.camera}].push_back(p);
  }
  return truth;
}

}  // namespace syncap::compare
