// OpenCV-style camera files (YAML or JSON through cv::FileStorage): a sequence `cameras`, each
// with its id, K (camera_matrix), the distortion k1 k2 p1 p2 [k3], R or rvec, t (tvec) and the
// image size: what `syncap calibrate` writes as cameras.opencv.yaml, and what OpenCV's own
// calibration gives (docs/reference/file-formats.md).
#pragma once

#include <filesystem>
#include <vector>

#include "sensor/opencv_camera.hpp"

namespace syncap::sensor {

struct OpenCvCameraEntry {
  int id = 0;  // the entry's `id`, else its index
  OpenCvCamera camera;
};

// Throws CameraFileError naming the file, the camera's index and the field: unreadable, no
// cameras, a field missing, the wrong count of numbers, K not [fx s cx; 0 fy cy; 0 0 1], R not a
// rotation, skew with distortion.
std::vector<OpenCvCameraEntry> read_opencv_camera_file(const std::filesystem::path& path);

// The intrinsics of an OpenCV calibration: a file as above (poses ignored), or one camera's
// (OpenCV's calibration sample and many labs' tools: top-level `camera_matrix` or `CameraMatrix`
// or `K`, `distortion_coefficients` or `DistortionCoeffs` or `distortion`, optional
// `image_width` and `image_height`), YAML, JSON or XML. rvec = tvec = 0; image_size 0 x 0 where
// the file has none. Throws CameraFileError naming the file and the field.
std::vector<OpenCvCameraEntry> read_opencv_intrinsics(const std::filesystem::path& path);

// Whether `path` is an OpenCV-style camera file: a .yaml or .yml, or a JSON file whose first
// camera has K or camera_matrix.
bool is_opencv_camera_file(const std::filesystem::path& path);

}  // namespace syncap::sensor
