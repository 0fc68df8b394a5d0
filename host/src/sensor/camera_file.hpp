// cameras.json: the cameras of a set-up in the thesis' model. Format (docs/camera-model.md):
//
//   {"cameras": [{"id": 0, "image_size": [1280, 1024], "pixel_size": [0.0067, 0.0067],
//                 "c": 6.0, "xp": 0.02, "yp": -0.03, "k1": ..., "k2": ..., "k3": ...,
//                 "p1": ..., "p2": ..., "sc": ..., "sh": ...,
//                 "X0": ..., "Y0": ..., "Z0": ..., "omega": ..., "phi": ..., "kappa": ...,
//                 "std": {"c": ..., ... every parameter from "c" to "kappa"}}, ...]}
//
// Lengths in mm, angles in rad, "std" optional. Reading is strict: a missing, mistyped, unknown
// or out-of-range field is an error naming the file, the camera and the field.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::sensor {

// A camera file that cannot be read or written; what() starts with the file name, e.g.
// `cameras.json: camera 3: field "c" must be a positive number`.
class CameraFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::vector<CameraModel> read_cameras(const std::filesystem::path& file);
void write_cameras(const std::filesystem::path& file, const std::vector<CameraModel>& cameras);

// The same on text; `source` names the text in error messages (usually the file name).
std::vector<CameraModel> parse_cameras(std::string_view text, std::string_view source);
std::string format_cameras(const std::vector<CameraModel>& cameras);

}  // namespace syncap::sensor
