// Is a calibrated camera one that can exist? A weak network (one LED, a few hundred points, a
// small volume) has several minima, and the wrong one can fit the measurements as well as the
// right one: a low RMS does not tell them apart (issue 14: RMS 0.130 px with camera centres
// 26 % of their spread off). These checks look at what the data cannot vouch for:
//
//   - the principal point: inside the image, near its centre (lenses are centred on the sensor
//     to a few per cent of its size; a shift lens is the exception the user knows of);
//   - the focal length against the field of view it gives (the model is a central projection
//     with Brown's distortion, not a fisheye);
//   - the radial correction r -> r (1 + k1 r^2 + k2 r^4 + k3 r^6) increasing over the measured
//     radii (else two image points map to one ray: eq 4.10 folds), and over the whole image;
//   - every accepted measurement's adjusted point in front of its camera.
//
// Each finding is `kWeak` (use with care, say why) or `kFailed` (the geometry is wrong); the
// limits are documented in docs/design/calibration.md ("Is it right?").
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::calibration {

enum class Verdict { kGood = 0, kWeak = 1, kFailed = 2 };

const char* verdict_name(Verdict verdict);  // "good", "weak", "failed"

struct Finding {
  Verdict severity = Verdict::kWeak;
  int camera = -1;   // the camera id, -1 for the network
  std::string text;  // one sentence naming the camera and the figure
};

struct PlausibilityLimits {
  // Principal point offset from the image centre, per axis, as a share of the half image size
  // (e.g. 0.15 of 329 px = 49 px for 659 px): weak beyond, failed beyond the second (82 px
  // there; the wrong minima of issue 14 had 200 px and more).
  double weak_principal_offset = 0.15;
  double failed_principal_offset = 0.25;
  // Horizontal field of view from c [deg]: weak outside [weak_min, weak_max], failed outside
  // [failed_min, failed_max].
  double weak_min_fov_deg = 15.0;
  double weak_max_fov_deg = 120.0;
  double failed_min_fov_deg = 3.0;
  double failed_max_fov_deg = 160.0;
  // Measurements whose adjusted point lies behind the camera, as a share of its measurements:
  // failed beyond (a few can be undetected blunders of a two-ray point near the camera).
  double failed_behind_share = 0.01;
};

// What one camera's checks need besides the camera: the pixels it measured (accepted ones) and
// for each whether its adjusted point lies in front of the camera.
struct CameraEvidence {
  sensor::CameraModel camera;
  std::vector<Eigen::Vector2d> pixels;
  long behind = 0;  // accepted measurements whose adjusted point is behind the camera
};

std::vector<Finding> check_camera(const CameraEvidence& evidence,
                                  const PlausibilityLimits& limits = {});

// The evidence of every station of an adjusted network (one per station, in its order).
std::vector<CameraEvidence> camera_evidence(const scene::Network& network,
                                            const estimators::BundleAdjustmentResult& result);

// check_camera on every station; the findings in station order.
std::vector<Finding> check_cameras(const scene::Network& network,
                                   const estimators::BundleAdjustmentResult& result,
                                   const PlausibilityLimits& limits = {});

// The largest radius [mm, from the principal point] up to which the radial correction of
// `interior` increases, searched up to `up_to_mm`; up_to_mm when it increases all the way.
double monotonic_radius_mm(const sensor::InteriorOrientation& interior, double up_to_mm);

// The worst severity of the findings (kGood when there are none).
Verdict worst(const std::vector<Finding>& findings);

}  // namespace syncap::calibration
