// cameras.json: the cameras of a set-up in the thesis' model. Format
// (docs/reference/camera-model.md):
//
//   {"cameras": [{"id": 0, "image_size": [1280, 1024], "pixel_size": [0.0067, 0.0067],
//                 "c": 6.0, "xp": 0.02, "yp": -0.03, "k1": ..., "k2": ..., "k3": ...,
//                 "p1": ..., "p2": ..., "sc": ..., "sh": ...,
//                 "X0": ..., "Y0": ..., "Z0": ..., "omega": ..., "phi": ..., "kappa": ...,
//                 "std": {"c": ..., ... every parameter from "c" to "kappa"}}, ...]}
//
// Lengths in mm, angles in rad, "std" optional. A calibration adds a top-level "quality" object
// (CalibrationQuality below; `syncap calibrate` writes it). Reading is strict: a missing, mistyped,
// unknown or out-of-range field is an error naming the file, the camera and the field.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/camera_model.hpp"
#include "sensor/opencv_camera_file.hpp"

namespace syncap::sensor {

// A camera file that cannot be read or written; what() starts with the file name, e.g.
// `cameras.json: camera 3: field "c" must be a positive number`.
class CameraFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How well a calibration fits its observations (the "quality" object of cameras.json):
//   {"sigma0_px": 0.11, "rms_px": 0.12, "per_camera_rms_px": {"0": 0.1, ...},
//    "observations": 1800, "outliers_removed": 3,
//    "wand_length_mean_mm": 1000.0, "wand_length_sd_mm": 0.2}   (the wand figures null: LED)
struct CalibrationQuality {
  double sigma0_px = 0.0;                     // a posteriori sigma0 x the a priori sigma of a pixel
  double rms_px = 0.0;                        // of the accepted residuals, both coordinates
  std::map<int, double> per_camera_rms_px;    // by camera id
  long observations = 0;                      // image measurements accepted
  long outliers_removed = 0;                  // by data snooping (and undetermined after it)
  std::optional<double> wand_length_mean_mm;  // of the adjusted wands; none in LED mode
  std::optional<double> wand_length_sd_mm;
  // The calibration's own judgement (calibration/verdict.hpp): "good", "weak" or "failed"; empty
  // in files written before it existed. The reasons, one sentence each, worst first.
  std::string verdict;
  std::vector<std::string> verdict_reasons;
};

// A cameras.json with its optional quality block.
struct CameraSet {
  std::vector<CameraModel> cameras;
  std::optional<CalibrationQuality> quality;
};

// Any camera file a lab has, told by its name and content: cameras.json (a quality block is
// checked and ignored), an OpenCV-style .yaml/.yml/.json (opencv_camera_file.hpp) or an anipose /
// Pose2Sim .toml (toml_camera_file.hpp). OpenCV and TOML cameras keep their lens exactly
// (CameraModel::opencv_lens).
std::vector<CameraModel> read_cameras(const std::filesystem::path& file);

// OpenCV cameras (of a YAML, JSON or TOML file) as the cameras they are exactly: the ideal camera
// with the lens kept as OpenCV defines it (camera_keeping_opencv_lens, kOpenCvPixelMm pixels).
std::vector<CameraModel> cameras_keeping_lenses(const std::vector<OpenCvCameraEntry>& entries);
void write_cameras(const std::filesystem::path& file, const std::vector<CameraModel>& cameras);

// The same on text; `source` names the text in error messages (usually the file name).
std::vector<CameraModel> parse_cameras(std::string_view text, std::string_view source);
std::string format_cameras(const std::vector<CameraModel>& cameras);

CameraSet read_camera_set(const std::filesystem::path& file);
void write_camera_set(const std::filesystem::path& file, const CameraSet& set);
CameraSet parse_camera_set(std::string_view text, std::string_view source);
std::string format_camera_set(const CameraSet& set);

}  // namespace syncap::sensor
