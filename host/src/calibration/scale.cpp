#include "calibration/scale.hpp"

#include <Eigen/Core>
#include <string>

namespace syncap::calibration {
namespace {

Eigen::Vector3d centre_of(const estimators::BundleAdjustmentResult& r, int camera) {
  for (const estimators::StationResult& s : r.stations) {
    if (s.camera_id == camera) return {s.exterior.X0, s.exterior.Y0, s.exterior.Z0};
  }
  throw ScaleError("--scale-from: camera " + std::to_string(camera) + " is not in the calibration");
}

}  // namespace

double scale_for(const estimators::BundleAdjustmentResult& result,
                 const KnownCameraDistance& known) {
  if (!(known.distance_mm > 0)) throw ScaleError("--scale-from: the distance must be > 0 mm");
  const double measured =
      (centre_of(result, known.camera_a) - centre_of(result, known.camera_b)).norm();
  if (!(measured > 0)) {
    throw ScaleError("--scale-from: cameras " + std::to_string(known.camera_a) + " and " +
                     std::to_string(known.camera_b) + " have the same centre");
  }
  return known.distance_mm / measured;
}

void apply_scale(double s, estimators::BundleAdjustmentResult& result, scene::Network& network) {
  const auto models = static_cast<Eigen::Index>(result.models.size());
  for (size_t i = 0; i < result.stations.size(); ++i) {
    auto& station = result.stations[i];
    station.exterior.X0 *= s;
    station.exterior.Y0 *= s;
    station.exterior.Z0 *= s;
    for (int k = 0; k < 3; ++k) station.exterior_sigma[static_cast<size_t>(k)] *= s;
    // Covariance layout (bundle_adjustment.hpp): interiors [10 each], then exteriors [6 each].
    const Eigen::Index at = 10 * models + 6 * static_cast<Eigen::Index>(i);
    if (result.camera_covariance.rows() >= at + 3) {
      result.camera_covariance.middleRows(at, 3) *= s;
      result.camera_covariance.middleCols(at, 3) *= s;
    }
  }
  for (auto& point : result.points) {
    for (int k = 0; k < 3; ++k) {
      point.xyz[static_cast<size_t>(k)] *= s;
      point.sigma[static_cast<size_t>(k)] *= s;
    }
    point.covariance *= s * s;
  }
  for (auto& station : network.stations) {
    station.exterior.X0 *= s;
    station.exterior.Y0 *= s;
    station.exterior.Z0 *= s;
  }
  for (auto& point : network.points) {
    for (double& x : point.xyz) x *= s;
  }
}

}  // namespace syncap::calibration
