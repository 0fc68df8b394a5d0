// anipose / Pose2Sim camera files (calibration.toml, Calib.toml): one table a camera with
// `size` [w, h], `matrix` (K, 3 rows), `distortions` (k1 k2 p1 p2 [k3]), `rotation` (Rodrigues,
// world -> camera), `translation`, `fisheye`; a `[metadata]` table. What `syncap calibrate`
// writes as calibration.toml, and what aniposelib's CameraGroup.dump and Pose2Sim's calibration
// write (docs/reference/file-formats.md).
//
// The format carries no length unit: Pose2Sim writes metres, anipose the unit of its board's
// square (often mm). A rig smaller than 0.1 m or larger than 100 m is no rig a person is
// filmed in, so the unit is told from the cameras' distance from the origin: below 100 units
// metres, else mm; `length_unit_mm` overrides it.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "sensor/opencv_camera_file.hpp"

namespace syncap::sensor {

struct TomlCameraFile {
  std::vector<OpenCvCameraEntry> cameras;  // tvec in mm; ids from the tables' trailing digits
  double length_unit_mm = 1000.0;          // what one unit of the file's translations was taken as
  bool unit_inferred = true;               // false when the caller gave it
};

// Throws CameraFileError naming the file, the table and the key (with the line where the TOML
// parser stopped): not TOML, no cameras, a key missing or of the wrong shape, a fisheye camera.
TomlCameraFile read_toml_camera_file(const std::filesystem::path& path,
                                     std::optional<double> length_unit_mm = std::nullopt);

// Whether `path` is a TOML camera file (its extension is .toml).
bool is_toml_camera_file(const std::filesystem::path& path);

}  // namespace syncap::sensor
