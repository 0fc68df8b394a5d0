#include "calibration_check.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <Eigen/Geometry>

#include "sensor/rotation.hpp"

namespace syncap::compare {
namespace {

using sensor::CameraModel;

// The cameras of both sets, paired by id; the true ones the estimate lacks in `missing`.
struct CommonCameras {
  std::vector<const CameraModel*> truth, estimated;
  std::vector<int> missing;
};

CommonCameras common_cameras(const std::vector<CameraModel>& truth,
                             const std::vector<CameraModel>& estimated) {
  std::map<int, const CameraModel*> by_id;
  for (const CameraModel& c : estimated) by_id[c.id] = &c;
  CommonCameras common;
  for (const CameraModel& t : truth) {
    const auto it = by_id.find(t.id);
    if (it == by_id.end()) {
      common.missing.push_back(t.id);
      continue;
    }
    common.truth.push_back(&t);
    common.estimated.push_back(it->second);
  }
  if (common.truth.size() < 3) {
    throw std::invalid_argument("the calibration shares " + std::to_string(common.truth.size()) +
                                " cameras with the truth; at least 3 are needed to align them");
  }
  return common;
}

// truth = scale * rotation * estimated + translation, least squares over the common centres.
Similarity fit_similarity(const std::vector<const CameraModel*>& truth,
                          const std::vector<const CameraModel*>& estimated, bool with_scale) {
  Eigen::Matrix3Xd from(3, estimated.size()), to(3, truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    from.col(static_cast<Eigen::Index>(i)) = estimated[i]->projection_centre();
    to.col(static_cast<Eigen::Index>(i)) = truth[i]->projection_centre();
  }
  const Eigen::Matrix4d t = Eigen::umeyama(from, to, with_scale);
  Similarity s;
  s.scale = t.block<3, 1>(0, 0).norm();
  s.rotation = t.block<3, 3>(0, 0) / s.scale;
  s.translation = t.block<3, 1>(0, 3);
  return s;
}

// The estimated camera expressed in the true frame: centre mapped, axes rotated. The interior
// orientation is unchanged by a similarity.
CameraModel in_true_frame(const CameraModel& estimated, const Similarity& s) {
  CameraModel moved = estimated;
  const Eigen::Vector3d centre =
      s.scale * s.rotation * estimated.projection_centre() + s.translation;
  const Eigen::Matrix3d rotation = s.rotation * estimated.rotation();
  const sensor::RotationAngles angles = sensor::angles_from_rotation(rotation);
  moved.exterior = {centre.x(), centre.y(), centre.z(), angles.omega, angles.phi, angles.kappa};
  return moved;
}

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

void reproject(const CameraModel& truth, const CameraModel& moved,
               const std::vector<Eigen::Vector3d>& targets, CameraCheck& check,
               double& sum_squared_all, long& count_all) {
  double sum_squared = 0;
  for (const Eigen::Vector3d& x : targets) {
    const auto a = truth.project(x);
    const auto b = moved.project(x);
    if (!a.ok() || !b.ok() || !truth.contains(a.pixel)) continue;
    const double d = (a.pixel - b.pixel).norm();
    sum_squared += d * d;
    check.reprojection_max_px = std::max(check.reprojection_max_px, d);
    ++check.points;
  }
  if (check.points > 0) check.reprojection_rms_px = std::sqrt(sum_squared / check.points);
  sum_squared_all += sum_squared;
  count_all += check.points;
}

}  // namespace

Similarity fit_to_truth(const std::vector<CameraModel>& truth,
                        const std::vector<CameraModel>& estimated, bool with_scale) {
  const CommonCameras common = common_cameras(truth, estimated);
  return fit_similarity(common.truth, common.estimated, with_scale);
}

CalibrationCheck check_calibration(const std::vector<CameraModel>& truth,
                                   const std::vector<CameraModel>& estimated,
                                   const std::vector<Eigen::Vector3d>& targets) {
  const CommonCameras common = common_cameras(truth, estimated);
  const auto& common_truth = common.truth;
  const auto& common_estimated = common.estimated;
  CalibrationCheck check;
  check.missing = common.missing;
  const Similarity s = fit_similarity(common_truth, common_estimated, true);
  check.scale = s.scale;
  double sum_squared = 0;
  long count = 0;
  for (std::size_t i = 0; i < common_truth.size(); ++i) {
    const CameraModel& t = *common_truth[i];
    const CameraModel moved = in_true_frame(*common_estimated[i], s);
    CameraCheck c;
    c.id = t.id;
    c.centre_error_mm = (moved.projection_centre() - t.projection_centre()).norm();
    c.rotation_error_deg = angle_deg(moved.rotation(), t.rotation());
    c.dc_mm = moved.interior.c - t.interior.c;
    c.dxp_mm = moved.interior.xp - t.interior.xp;
    c.dyp_mm = moved.interior.yp - t.interior.yp;
    c.dk1 = moved.interior.k1 - t.interior.k1;
    reproject(t, moved, targets, c, sum_squared, count);
    check.cameras.push_back(c);
  }
  if (count > 0) check.reprojection_rms_px = std::sqrt(sum_squared / count);
  return check;
}

std::string format_calibration_check(const CalibrationCheck& check) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line,
                "calibration against the true cameras (after a similarity, scale %.6f):\n",
                check.scale);
  out += line;
  std::snprintf(line, sizeof line, "  %-6s %10s %8s %9s %9s %9s %10s %7s %9s %9s\n", "camera",
                "centre_mm", "rot_deg", "dc_mm", "dxp_mm", "dyp_mm", "dk1", "points", "rms_px",
                "max_px");
  out += line;
  for (const CameraCheck& c : check.cameras) {
    std::snprintf(line, sizeof line,
                  "  %-6d %10.3f %8.4f %+9.4f %+9.4f %+9.4f %+10.2e %7ld %9.4f %9.4f\n", c.id,
                  c.centre_error_mm, c.rotation_error_deg, c.dc_mm, c.dxp_mm, c.dyp_mm, c.dk1,
                  c.points, c.reprojection_rms_px, c.reprojection_max_px);
    out += line;
  }
  std::snprintf(line, sizeof line, "  reprojection of the true targets: RMS %.4f px\n",
                check.reprojection_rms_px);
  out += line;
  for (int id : check.missing) out += "  camera " + std::to_string(id) + ": not calibrated\n";
  return out;
}

}  // namespace syncap::compare
