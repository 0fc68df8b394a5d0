// A calibration (cameras.json from `syncap calibrate`) against the simulator's true cameras.
//
// A calibration from a wand alone fixes the network only up to a similarity transformation (its
// datum is free: origin, orientation, and the scale comes from the wand length), so the estimated
// projection centres are first mapped onto the true ones by the least-squares similarity
// (Umeyama, through Eigen::umeyama); then every figure compares like with like:
// - per camera: the centre's distance to the truth [mm], the angle between the estimated
//   (rotated into the true frame) and the true orientation [deg], and the interior parameters c,
//   xp, yp [mm] and k1 against the truth;
// - the reprojection of the true target positions (truth/targets.csv) through both camera sets:
//   RMS and maximum pixel distance, the figure that says what the calibration is worth.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sensor/camera_model.hpp"

namespace syncap::compare {

struct CameraCheck {
  int id = 0;
  double centre_error_mm = 0;
  double rotation_error_deg = 0;
  double dc_mm = 0, dxp_mm = 0, dyp_mm = 0, dk1 = 0;
  long points = 0;  // true targets visible to both camera models
  double reprojection_rms_px = 0;
  double reprojection_max_px = 0;
};

struct CalibrationCheck {
  double scale = 1;                  // of the similarity: truth = scale * R * estimated + t
  std::vector<CameraCheck> cameras;  // in the truth's order
  std::vector<int> missing;          // true cameras the calibration lacks
  double reprojection_rms_px = 0;    // all cameras
};

// truth = scale * rotation * estimated + translation.
struct Similarity {
  double scale = 1;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& estimated) const {
    return scale * rotation * estimated + translation;
  }
};

// The transformation of the estimated cameras' frame onto the truth's, least squares over the
// projection centres of the cameras both sets hold (paired by id): a similarity, or with
// `with_scale` false a rigid motion (a wand calibration's scale is meant to be metric, so points
// measured through it are compared after a rigid motion only). Throws std::invalid_argument when
// fewer than three cameras are common.
Similarity fit_to_truth(const std::vector<sensor::CameraModel>& truth,
                        const std::vector<sensor::CameraModel>& estimated, bool with_scale);

// `targets`: true object points [mm] to reproject. Throws std::invalid_argument when fewer than
// three cameras are common to both sets (the similarity is then not determined).
CalibrationCheck check_calibration(const std::vector<sensor::CameraModel>& truth,
                                   const std::vector<sensor::CameraModel>& estimated,
                                   const std::vector<Eigen::Vector3d>& targets);

std::string format_calibration_check(const CalibrationCheck& check);

}  // namespace syncap::compare
