// The unified least squares self-calibrating bundle adjustment of thesis section 4.1.3 (lines
// 2669-2930) on Ceres, with the covariance of the parameters and the tests of section 4.1.4:
//
//   - parameter blocks: interior[10] per camera model, exterior[6] per station, and the object
//     points, grouped where distance constraints link them (cost_functors.hpp);
//   - residuals: image measurements / sigma_px, parameter observations (eqs 4.40-4.41) for
//     kObserved values, distance constraints; kFixed values are constants;
//   - datum: from the fixed and observed exterior / object point values when there are any;
//     otherwise a free network: solved with a minimal-constraint datum (the first station's
//     exterior orientation held, and, without distances, one coordinate of the second station's
//     centre for the scale), its covariance S-transformed to the inner-constraint datum of the
//     object points (minimum trace of their covariance). docs/design/calibration.md, "Bundle
//     adjustment";
//   - statistics: sigma0, redundancy, the variance-factor test, the goodness of fit of the
//     standardised residuals, data snooping with iterative rejection.
//
// Usage:
//   scene::Network network = ...;          // models, stations, points, measurements, distances
//   BundleAdjustmentResult r = estimators::adjust(network, {});
//   r.models[0].interior.c, r.models[0].interior_sigma[InteriorBlock::kC], r.sigma0, ...
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimators/statistical_tests.hpp"
#include "scene/network.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {

// Where an adjustment stands, after each of Ceres' iterations: what a long adjustment tells
// while it runs (a 20-camera rig's takes minutes).
struct AdjustmentProgress {
  int solve = 0;               // 1 for the first solve, then one more per round of data snooping
  int iteration = 0;           // of this solve, 0 the start
  double cost = 0;             // Ceres' cost, half the weighted sum of squares
  long measurements_kept = 0;  // image measurements in this solve (not yet rejected)
};

// What adjust() needs beyond the network (whose DesignOptions and ResidualTest it follows).
struct BundleOptions {
  int num_threads = 1;
  // The standard deviation given to a distance constraint of sigma 0 ("exact") [mm].
  double exact_distance_sigma_mm = 1e-4;
  // Ceres' progress per iteration on stderr (OUTPUT ITERATIONS also switches it on).
  bool log_iterations = false;
  // Called after every iteration of every solve (the caller throttles what it prints).
  std::function<void(const AdjustmentProgress&)> progress;
};

// Thrown for a network adjust() cannot take: the message names the element (measurement index,
// station, point, distance) and what is wrong.
struct NetworkError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct ModelResult {
  std::string name;
  sensor::InteriorOrientation interior;
  std::array<double, sensor::InteriorBlock::kSize> interior_sigma{};  // 0 when fixed
  Eigen::Matrix<double, 10, 10> interior_covariance = Eigen::Matrix<double, 10, 10>::Zero();
  // Table 4.6: the correlations of the estimated (not fixed) interior values, in block order.
  std::vector<int> estimated_interior;  // InteriorBlock indices
  Eigen::MatrixXd interior_correlation;
};

struct StationResult {
  std::string name;
  int camera_id = -1;
  sensor::ExteriorOrientation exterior;
  std::array<double, sensor::ExteriorBlock::kSize> exterior_sigma{};  // 0 when fixed
  double rms_px = 0.0;    // of the residuals of its accepted measurements, both coordinates
  long measurements = 0;  // accepted
  long rejected = 0;      // removed by data snooping or as undetermined
};

struct PointResult {
  std::string name;
  std::array<double, 3> xyz{};
  std::array<double, 3> sigma{};  // stdX, stdY, stdZ [mm]
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  bool adjusted = false;  // false: dropped (fewer than two rays from distinct stations)
};

enum class MeasurementStatus {
  kAccepted,
  kRejectedBlunder,  // data snooping: |w| above the critical value
  kUndetermined,     // its point had fewer than two rays from distinct stations
};

// One image measurement after the adjustment, in the order of Network::measurements.
struct MeasurementResult {
  double residual_u = 0.0;  // v = adjusted - measured [px] (at the last adjustment it was in)
  double residual_v = 0.0;
  double w_u = 0.0;  // standardised residuals v / (sigma0 sigma_px sqrt(q_vv)); 0 if not computed
  double w_v = 0.0;
  double redundancy_u = 0.0;  // q_vv / q_ll: the share of the residual the network controls
  double redundancy_v = 0.0;
  MeasurementStatus status = MeasurementStatus::kAccepted;
};

// A measurement data snooping removed, in the order of removal.
struct RejectedMeasurement {
  size_t index = 0;  // into Network::measurements
  std::string station;
  std::string point;
  int64_t frame_number = -1;
  double w = 0.0;  // its test statistic (both coordinates) as the 1-D |w| of equal probability
  // Rejected with its point: one of the point's three rays was wrong, but which one the data
  // could not tell (see data_snooping.hpp); w is then below the critical value.
  bool ambiguous = false;
};

enum class Datum {
  kGivenParameters,   // fixed / observed exterior or object point values
  kInnerConstraints,  // free network: minimal constraints, covariance S-transformed
};

struct BundleAdjustmentResult {
  bool converged = false;
  int iterations = 0;       // of the last adjustment
  int adjustments = 0;      // 1 + the re-adjustments after rejections
  std::string termination;  // Ceres' message of the last adjustment
  Datum datum = Datum::kGivenParameters;

  long observations = 0;  // residuals: 2 per measurement, + parameter observations + distances
  long unknowns = 0;      // estimated values (minus the minimal constraints of a free network)
  long redundancy = 0;
  double sigma0 = 0.0;  // a posteriori, sqrt(v^T P v / r)

  bool covariance_computed = false;
  bool tests_computed = false;
  VarianceFactorTest variance_test;
  GoodnessOfFitTest goodness_of_fit;
  double critical_w = 0.0;

  std::vector<ModelResult> models;
  std::vector<StationResult> stations;
  std::vector<PointResult> points;
  std::vector<MeasurementResult> measurements;
  std::vector<RejectedMeasurement> rejected;
  // The covariance of all camera parameters: models' interior[10] in order, then stations'
  // exterior[6] in order (rows of fixed values zero). The linearised one, sigma0^2 times the
  // cofactors; with DesignOptions::covariance_stretches or covariance_cells, each value's
  // variance the larger of that and the scatter over those clusters (cluster_covariance.hpp),
  // which the sigmas report.
  Eigen::MatrixXd camera_covariance;
  Eigen::MatrixXd linearised_camera_covariance;
  int covariance_stretches = 0;  // clusters camera_covariance came from (0: not clustered)
  int covariance_cells = 0;
  std::vector<std::string> messages;  // what happened: datum, triangulations, rejections
};

// Adjusts the network. Points without approximation (and all points with IGNORE APPROXIMATES) are
// triangulated from the stations' approximate orientations; stations need approximations.
// Throws NetworkError for a network it cannot take, naming the element.
BundleAdjustmentResult adjust(const scene::Network& network, const BundleOptions& options);

// The result as text a person reads: the adjustment's figures and tests, per camera the interior
// orientation with standard deviations, rms and removals, and the correlation matrices of the
// interior parameters laid out as thesis Table 4.6 (upper triangle).
std::string format_summary(const BundleAdjustmentResult& result);

}  // namespace syncap::estimators
