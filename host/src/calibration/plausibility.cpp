#include "calibration/plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string camera_label(int id) { return "camera " + std::to_string(id); }

// The principal point against the image centre, per axis.
void check_principal_point(const sensor::CameraModel& c, const PlausibilityLimits& limits,
                           std::vector<Finding>& out) {
  const double dx_px = c.interior.xp / c.sensor.pixel_width_mm;
  const double dy_px = c.interior.yp / c.sensor.pixel_height_mm;
  const double share = std::max(std::abs(dx_px) / (0.5 * c.sensor.width_px),
                                std::abs(dy_px) / (0.5 * c.sensor.height_px));
  if (share <= limits.weak_principal_offset) return;
  const bool outside = share >= 1.0;
  const Verdict severity =
      share > limits.failed_principal_offset ? Verdict::kFailed : Verdict::kWeak;
  out.push_back({severity, c.id,
                 util::printf_string("%s: principal point %.0f, %.0f px (right, down) from the "
                                     "image centre (%.0f %% of the half image%s)",
                                     camera_label(c.id).c_str(), dx_px, 0.0 - dy_px, 100.0 * share,
                                     outside ? ", outside the image" : "")});
}

void check_field_of_view(const sensor::CameraModel& c, const PlausibilityLimits& limits,
                         std::vector<Finding>& out) {
  const double half_width_mm = 0.5 * c.sensor.width_px * c.sensor.pixel_width_mm;
  const double fov_deg =
      c.interior.c > 0 ? 2.0 * std::atan(half_width_mm / c.interior.c) * 180 / kPi : 180.0;
  const bool failed = fov_deg < limits.failed_min_fov_deg || fov_deg > limits.failed_max_fov_deg;
  const bool weak = fov_deg < limits.weak_min_fov_deg || fov_deg > limits.weak_max_fov_deg;
  if (!weak && !failed) return;
  out.push_back({failed ? Verdict::kFailed : Verdict::kWeak, c.id,
                 util::printf_string("%s: focal length %.1f px gives a horizontal field of view "
                                     "of %.1f deg",
                                     camera_label(c.id).c_str(),
                                     c.interior.c / c.sensor.pixel_width_mm, fov_deg)});
}

// The radius [mm] of the farthest of `pixels` (or of the image corners) from the principal point.
double farthest_radius_mm(const sensor::CameraModel& c,
                          const std::vector<Eigen::Vector2d>& pixels) {
  double r = 0;
  const Eigen::Vector2d principal(c.interior.xp, c.interior.yp);
  for (const Eigen::Vector2d& p : pixels) {
    r = std::max(r, (c.image_from_pixel(p) - principal).norm());
  }
  return r;
}

void check_distortion(const CameraEvidence& e, std::vector<Finding>& out) {
  const sensor::CameraModel& c = e.camera;
  const double w = c.sensor.width_px - 0.5, h = c.sensor.height_px - 0.5;
  const double corner_mm = farthest_radius_mm(c, {{-0.5, -0.5}, {w, -0.5}, {-0.5, h}, {w, h}});
  const double measured_mm = farthest_radius_mm(c, e.pixels);
  const double monotonic_mm = monotonic_radius_mm(c.interior, corner_mm);
  if (monotonic_mm >= corner_mm) return;
  const double px = c.sensor.pixel_width_mm;
  const bool folds_on_data = monotonic_mm < measured_mm;
  out.push_back(
      {folds_on_data ? Verdict::kFailed : Verdict::kWeak, c.id,
       util::printf_string(
           "%s: the radial distortion folds at %.0f px from the principal point (%s, which "
           "reach %.0f px; the image corners %.0f px): points beyond have no unique ray",
           camera_label(c.id).c_str(), monotonic_mm / px,
           folds_on_data ? "inside the measured points" : "beyond the measured points",
           measured_mm / px, corner_mm / px)});
}

void check_in_front(const CameraEvidence& e, const PlausibilityLimits& limits,
                    std::vector<Finding>& out) {
  if (e.behind == 0) return;
  const double share =
      static_cast<double>(e.behind) / static_cast<double>(std::max<size_t>(e.pixels.size(), 1));
  out.push_back(
      {share > limits.failed_behind_share ? Verdict::kFailed : Verdict::kWeak, e.camera.id,
       util::printf_string("%s: %ld of its %zu measured points lie behind it",
                           camera_label(e.camera.id).c_str(), e.behind, e.pixels.size())});
}

}  // namespace

const char* verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::kGood:
      return "good";
    case Verdict::kWeak:
      return "weak";
    case Verdict::kFailed:
      break;
  }
  return "failed";
}

double monotonic_radius_mm(const sensor::InteriorOrientation& io, double up_to_mm) {
  // d/dr of r (1 + k1 r^2 + k2 r^4 + k3 r^6); sampled finely enough for the polynomial's few
  // turns (a degree-6 polynomial in r has at most 3 positive roots).
  constexpr int kSteps = 1000;
  for (int i = 1; i <= kSteps; ++i) {
    const double r = up_to_mm * i / kSteps;
    const double r2 = r * r;
    const double slope = 1.0 + r2 * (3.0 * io.k1 + r2 * (5.0 * io.k2 + r2 * 7.0 * io.k3));
    if (slope <= 0.0) return up_to_mm * (i - 1) / kSteps;
  }
  return up_to_mm;
}

std::vector<Finding> check_camera(const CameraEvidence& evidence,
                                  const PlausibilityLimits& limits) {
  std::vector<Finding> out;
  check_principal_point(evidence.camera, limits, out);
  check_field_of_view(evidence.camera, limits, out);
  check_distortion(evidence, out);
  check_in_front(evidence, limits, out);
  return out;
}

std::vector<CameraEvidence> camera_evidence(const scene::Network& network,
                                            const estimators::BundleAdjustmentResult& result) {
  std::map<std::string, size_t> model_index, station_index, point_index;
  for (size_t m = 0; m < network.models.size(); ++m) model_index[network.models[m].name] = m;
  for (size_t p = 0; p < network.points.size(); ++p) point_index[network.points[p].name] = p;
  std::vector<CameraEvidence> out;
  // Per station its centre and its z' axis: in front when z' . (X - X0) < 0 (the camera looks
  // along -z').
  std::vector<Eigen::Vector3d> centre, back;
  for (size_t s = 0; s < network.stations.size(); ++s) {
    const scene::Station& station = network.stations[s];
    station_index[station.name] = s;
    const size_t m = model_index.at(station.model);
    CameraEvidence e;
    e.camera.id = station.camera_id;
    e.camera.sensor = network.models[m].sensor;
    e.camera.interior = result.models[m].interior;
    e.camera.exterior = result.stations[s].exterior;
    centre.push_back(e.camera.projection_centre());
    back.push_back(e.camera.rotation().col(2));
    out.push_back(e);
  }
  for (size_t i = 0; i < network.measurements.size(); ++i) {
    if (result.measurements[i].status != estimators::MeasurementStatus::kAccepted) continue;
    const scene::ImageMeasurement& meas = network.measurements[i];
    const auto p = point_index.find(meas.point);
    if (p == point_index.end() || !result.points[p->second].adjusted) continue;
    const size_t s = station_index.at(meas.station);
    out[s].pixels.emplace_back(meas.u, meas.v);
    const Eigen::Vector3d point(result.points[p->second].xyz.data());
    if (back[s].dot(point - centre[s]) >= 0) ++out[s].behind;
  }
  return out;
}

std::vector<Finding> check_cameras(const scene::Network& network,
                                   const estimators::BundleAdjustmentResult& result,
                                   const PlausibilityLimits& limits) {
  std::vector<Finding> out;
  for (const CameraEvidence& e : camera_evidence(network, result)) {
    for (Finding& f : check_camera(e, limits)) out.push_back(std::move(f));
  }
  return out;
}

Verdict worst(const std::vector<Finding>& findings) {
  Verdict v = Verdict::kGood;
  for (const Finding& f : findings) v = std::max(v, f.severity);
  return v;
}

}  // namespace syncap::calibration
