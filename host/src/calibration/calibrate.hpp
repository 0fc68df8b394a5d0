// The calibration pipeline of `syncap calibrate` (docs/design/calibration.md, "syncap calibrate"),
// from observations to calibrated cameras:
//
//   1. identify the wand's targets (or the LED) per camera and frame (wand_identification.hpp);
//   2. build the network: a camera model and a station per camera, an object point per target and
//      frame seen by at least two cameras, the wand's distances between neighbouring targets;
//      start interiors from the image size alone (below);
//   3. start values from the measurements alone (network_start.hpp: RDLT pair tree, resection,
//      scale from the wand);
//   4. the bundle adjustment (estimators/bundle_adjustment.hpp) in two stages: first c, xp, yp
//      and the exterior orientations with the lens distortion held at zero and no snooping (the
//      start's camera constants can be 20-30 % off, a free distortion model would swallow part of
//      that error), then every interior value free, with data snooping;
//      Between the stages the network is levelled (below);
//   5. the cameras with their standard deviations, the quality figures and the report.
//
// The levelled frame: with nothing surveyed, the result's frame is chosen from what a capture
// set-up has: the origin at the centroid of the wand positions (the middle of the capture
// volume), Z up at right angles to the cameras' image-right axes (cameras hang without roll, so
// those are horizontal whatever their pitch; the mean image-up axis when they are all alike), Y
// horizontal from the first camera towards
// the origin, X = Y x Z. Scale from the wand (mm); an LED gives no scale. The frame is set on
// the approximations before the last adjustment, whose free-network datum then shifts it by a
// few centimetres at most (the simulated 3-camera test: 46 mm).
//
// Start interiors from the image size alone: the principal point at the centre, no distortion,
// and c from a typical horizontal field of view (`field_of_view_deg`, 60 deg: between a 6 mm lens
// on a 2/3" sensor, 54 deg, and on the Basler A620f's 1/2", 71 deg): c = (width x pixel size / 2)
// / tan(fov / 2). The pixel size comes from the sensor's data sheet (`pixel_size_mm`); when it is
// not known any value gives the same pixels (c and the distortion then come out in units of that
// nominal pixel size).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/check_points.hpp"
#include "calibration/halves.hpp"
#include "calibration/model_selection.hpp"
#include "calibration/network_start.hpp"
#include "calibration/observations.hpp"
#include "calibration/plausibility.hpp"
#include "calibration/report.hpp"
#include "calibration/scale.hpp"
#include "calibration/start_search.hpp"
#include "calibration/wand_identification.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::calibration {

struct CalibrationOptions {
  WandSpec wand;
  IdentificationOptions identification;
  double pixel_size_mm = 0.005;                   // nominal, when the source does not know it
  std::map<int, double> pixel_size_mm_by_camera;  // overrides per camera id
  double field_of_view_deg = 60.0;                // horizontal, for the start value of c
  // The start is searched from these horizontal fields of view too (start_search.hpp), on
  // start_search_frames frames evenly spread; field_of_view_deg is tried first and wins ties.
  // Empty: the start from field_of_view_deg alone.
  std::vector<double> start_fields_of_view_deg{40, 50, 60, 70, 80, 90, 100};
  int start_search_frames = 200;
  // This share of the frames is held out of the adjustment and predicted afterwards
  // (check_points.hpp); 0: none.
  double check_point_share = 0.1;
  // Calibrate the two halves of the adjusted frames (first, second) too and compare them
  // (halves.hpp); needs 2 x 40 frames.
  bool compare_halves = true;
  // One interior orientation for all cameras (identical cameras and lenses): one camera model
  // the stations share; their sensors must be alike.
  bool shared_interior = false;
  // When set (one per camera model, in camera id order), the start interiors instead of those from
  // field_of_view_deg, and no start search.
  std::vector<sensor::InteriorOrientation> start_interiors;
  double sigma_px = 0.1;            // a priori standard deviation of a measured coordinate
  double wand_sigma_mm = 0.2;       // of each wand distance (the wand's manufacture, flexing)
  double critical_snooping = 3.29;  // |w| above this is a blunder
  // Standardise the residuals with the a posteriori sigma0 (robust to a wrong sigma_px).
  bool snoop_with_a_posteriori_sigma0 = true;
  // Interior values estimated in the final adjustment (InteriorBlock indices); the others stay 0.
  // Empty: the mode's default, square pixels (sc, sh held) and for a wand c, xp, yp, k1, k2, k3,
  // p1, p2, for an LED (weaker: one point a frame, no scale) the same without k3.
  std::vector<int> free_interior;
  // The free interior values are candidates: the base model first, the further groups only
  // where the data carry them (model_selection.hpp). false: exactly free_interior. Unset: true
  // for an LED, false for a wand (see selects_model()).
  std::optional<bool> select_model;
  // The principal point is observed at the image centre with this share of the sensor width as
  // its standard deviation (a soft prior: lenses sit centred on their sensor); 0: no prior.
  // Unset: 0.03 for an LED, none for a wand (see principal_point_sigma()).
  std::optional<double> principal_point_sigma_share;
  // LED mode: the scale from a known distance between two cameras' centres (scale.hpp); without
  // it positions are in the arbitrary units of the start's first base.
  std::optional<KnownCameraDistance> scale_from;
  int max_frames = 0;  // use at most this many frames, evenly spread (0: all)
  // > 1: also the interior sigmas of this many re-adjustments of measurements simulated from the
  // result (estimators/bootstrap.hpp), in the report beside the linearised ones.
  int bootstrap_samples = 0;
  // The sigmas also from the scatter over this many contiguous stretches of the adjusted frames
  // and over the cells of a grid this many cells wide on each image, each the largest of those
  // and the linearised one (estimators/cluster_covariance.hpp): the errors that follow the
  // target along the recording or belong to a place in the image; 0: not from those.
  int covariance_stretches = 30;
  int covariance_cells = 8;
  NetworkStartOptions start;
  // Called with one line per step ("identified 3 cameras: ...", "start values: ..."); the CLI
  // prints them on a terminal.
  std::function<void(const std::string&)> progress;
};

struct CalibrationResult {
  std::vector<sensor::CameraModel> cameras;  // adjusted, with standard deviations
  sensor::CalibrationQuality quality;
  CalibrationReport report;
  Identification identification;
  scene::Network network;  // as adjusted in the final stage (start values filled)
  NetworkStartReport start;
  estimators::BundleAdjustmentResult adjustment;
  StartSearch start_search;           // empty when options.start_fields_of_view_deg is
  ModelSelection model;               // the interior values estimated and the tests behind them
  std::vector<int64_t> check_frames;  // held out of the adjustment
  CheckPointResult check_points;
  HalvesAgreement halves;
  // Whether the result can be trusted: every finding of the checks (verdict.hpp), worst first.
  Verdict verdict = Verdict::kGood;
  std::vector<Finding> findings;
  // Indices into network.measurements of the wand's points, per point name (for tests).
  std::map<std::string, std::vector<size_t>> measurements_of_point;
};

// Observations that cannot be calibrated (too few cameras, a camera that never saw the wand,
// options that contradict the observations); the message names the camera or the option.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The defaults that depend on the mode. A wand (scale, three targets, seen over the images)
// determines the principal point and the further distortion terms where the rendered bench
// can check it: on the short ring-6cam-person run (30 wand positions) the model selection and
// the prior made the true targets reproject at 0.25 px RMS instead of 0.15 px, while its own
// tests found p1, p2, k3 insignificant (the rendered discs' 0.13 px centroid bias is not noise).
// One LED in a small volume does not determine them, and there they decide the geometry
// (docs/design/calibration.md, "Is it right?").
bool selects_model(const CalibrationOptions& options);
double principal_point_sigma(const CalibrationOptions& options);

// The index into network.models (and an adjustment's models) of station `s`'s camera model.
size_t model_index(const scene::Network& network, size_t station);

// The network of step 2, from identified targets (exposed for tests and for `syncap bundle`-like
// uses that want to edit it before adjusting).
scene::Network build_network(const Observations& observations, const Identification& identification,
                             const CalibrationOptions& options);

// Steps 1-5. Throws CalibrationError, NetworkStartError or estimators::NetworkError.
CalibrationResult calibrate(const Observations& observations, const CalibrationOptions& options);

}  // namespace syncap::calibration
