// Calibrated cameras in the formats other tools read, converted with sensor::opencv_from_camera
// (exact without lens distortion, fitted otherwise; docs/reference/camera-model.md, "OpenCV"):
//
// - OpenCV YAML (cv::FileStorage): per camera `camera_NN` with `image_size`, `camera_matrix`,
//   `distortion` (k1 k2 p1 p2 k3), `rvec` and `tvec` (object -> camera, tvec in mm), and the
//   conversion's residual `fit_rms_px`.
// - `calibration.toml` as anipose (aniposelib's CameraGroup.load) and Pose2Sim read it: one table
//   `[cam_NN]` a camera with `name`, `size`, `matrix`, `distortions` (k1 k2 p1 p2 k3),
//   `rotation` (Rodrigues), `translation` and `fisheye = false`, then `[metadata]`. Pose2Sim
//   works in metres, so the translation is written in metres; anipose triangulates in the unit of
//   the translation, so its 3D output comes out in metres too.
#pragma once

#include <string>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::calibration {

std::string format_opencv_yaml(const std::vector<sensor::CameraModel>& cameras);

// `error_px` goes into [metadata] (anipose's reprojection error of the calibration).
std::string format_calibration_toml(const std::vector<sensor::CameraModel>& cameras,
                                    double error_px);

}  // namespace syncap::calibration
