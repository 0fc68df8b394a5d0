// The photogrammetric network: everything a bundle adjustment takes in (thesis section 4.1.3,
// the blocks of Fig 4.9). It is what the scene description language (host/src/sdl) reads and
// writes, what `syncap calibrate` builds from wand observations, and what the bundle adjustment
// (host/src/estimators) adjusts. Results (adjusted values, covariances, test outcomes) live in the
// estimators' result types, not here.
//
// Units: lengths in mm, angles in rad, image measurements in pixels (u right, v down, pixel
// (0, 0) = centre of the top-left pixel), as in docs/reference/camera-model.md.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sensor/camera_parameters.hpp"

namespace syncap::scene {

// How one unknown enters the adjustment (thesis eqs 4.40-4.41: parameter observations).
enum class ParameterMode {
  kFree,      // estimated, no prior
  kFixed,     // held at its value (a constant)
  kObserved,  // estimated, with an observation of its value of standard deviation `sigma`
};

struct ParameterPrior {
  ParameterMode mode = ParameterMode::kFree;
  double sigma = 0.0;  // for kObserved, in the parameter's unit (> 0)

  static ParameterPrior free() { return {}; }
  static ParameterPrior fixed() { return {ParameterMode::kFixed, 0.0}; }
  static ParameterPrior observed(double s) { return {ParameterMode::kObserved, s}; }
};

// Priors of the ten interior parameters, in sensor::InteriorBlock order (c, xp, yp, k1, k2, k3,
// p1, p2, sc, sh). The observed value of a kObserved parameter is the camera's approximate value.
using InteriorPriors = std::array<ParameterPrior, sensor::InteriorBlock::kSize>;
// Priors of the six exterior parameters, in sensor::ExteriorBlock order (X0, Y0, Z0, omega, phi,
// kappa).
using ExteriorPriors = std::array<ParameterPrior, sensor::ExteriorBlock::kSize>;

// The camera model of one or more stations (cameras may share a model; in a multi-camera network
// each camera usually has its own).
struct CameraModel {
  std::string name;
  sensor::SensorGeometry sensor;         // known in advance, never estimated
  sensor::InteriorOrientation interior;  // approximate (or observed, or fixed) values
  InteriorPriors priors;                 // default: all free
};

// A camera station: one exposure position of a camera model. For a synchronized network each
// physical camera is one station.
struct Station {
  std::string name;
  int camera_id = -1;                    // the edge's camera id, -1 when not from a live network
  std::string model;                     // CameraModel::name
  sensor::ExteriorOrientation exterior;  // approximate values
  bool has_approximation = false;        // exterior holds usable approximate values
  ExteriorPriors priors;                 // default: all free
};

// An object point. Control points carry known coordinates (fixed or observed); new points carry
// only approximate ones (or none: has_approximation = false).
struct ObjectPoint {
  std::string name;
  std::array<double, 3> xyz{0.0, 0.0, 0.0};
  bool has_approximation = false;
  std::array<ParameterPrior, 3> priors;  // default: all free (a new point)
};

// One image measurement: where `station` saw `point`, in pixels, with its standard deviation.
struct ImageMeasurement {
  std::string station;
  std::string point;
  double u = 0.0;
  double v = 0.0;
  double sigma_px = 0.1;
  int64_t frame_number = -1;  // where it came from, for reports; -1 when unknown
};

// A spatial distance constraint between two object points (the wand: thesis section 4.1.3.3).
struct DistanceConstraint {
  std::string point_a;
  std::string point_b;
  double distance = 0.0;  // [mm]
  double sigma = 0.0;     // [mm]; 0 = exact (enforced with a large weight)
};

// The design-block tags of thesis section 4.2.1: what the adjustment computes and prints.
struct DesignOptions {
  bool simulate = false;                   // SIMULATE: measurements generated from the approximates
  uint32_t simulation_seed = 1;            // SIMULATE SEED n: the random seed of the noise
  bool unified_least_squares = true;       // UNIFIED LEAST SQUARES: parameter observations in use
  bool residuals = true;                   // RESIDUALS
  bool calculate_covariance = true;        // CALCULATE COVARIANCE
  bool statistical_tests = true;           // STATISTICAL TESTS
  bool force_complete = false;             // FORCE COMPLETE: all iterations even when converged
  std::optional<int> exact_iterations;     // EXACT ITERATIONS n
  bool ignore_approximates = false;        // IGNORE APPROXIMATES: compute starting values anew
  bool sort = false;                       // SORT: output sorted by name
  bool output_coefficient_matrix = false;  // OUTPUT COEFFICIENT MATRIX
  bool output_misclosures = false;         // OUTPUT MISCLOSURES
  bool output_corrections = false;         // OUTPUT CORRECTIONS
  bool output_messages = true;             // OUTPUT MESSAGES
  bool output_iterations = false;          // OUTPUT ITERATIONS
  bool output_iterations_inline = false;   // OUTPUT ITERATIONS INLINE
  bool debug = false;                      // DEBUG
  bool wait = false;                       // WAIT: pause between iterations (interactive)
  int max_iterations = 50;                 // convergence control
  double convergence_tolerance = 1e-10;    // relative change of the cost
  // COVARIANCE STRETCHES n, COVARIANCE CELLS n: the camera parameters' sigmas also from the
  // scatter of the data over n contiguous stretches of the recording (its frames in order) and
  // over the cells of an n-wide grid on each image, the largest of those and the linearised one
  // each (estimators/cluster_covariance.hpp); 0: the linearised alone.
  int covariance_stretches = 0;
  int covariance_cells = 0;
};

// The residual test block (thesis section 4.1.4): significance levels and rejection.
struct ResidualTest {
  double alpha_variance = 0.05;     // two-tailed chi-square test of the variance factor
  double alpha_goodness = 0.05;     // goodness of fit of the standardised residuals
  double critical_snooping = 3.29;  // |w| above this is a blunder (data snooping, eq 4.31)
  bool iterative_rejection = true;  // remove the worst blunder and re-adjust, repeatedly
  int max_rejections = 1000;
  // Each round removes the worst measurement of every point beyond the critical value, not
  // only the worst of all: a blunder raises the residuals of its own point's other rays, barely
  // those of other points, so big networks need as many rounds as a point has blunders, not as
  // the network has (a simulated 20-camera LED rig with 130 blunders: 130 re-adjustments of 3.5 s
  // each, against a few).
  bool reject_per_point = false;
  // Data snooping standardises with the a priori sigma0 = 1 (Baarda's w-test, the default) or
  // with the a posteriori sigma0 (Pope's tau-like variant, robust to a wrong sigma_px).
  bool snoop_with_a_posteriori_sigma0 = false;
};

struct Network {
  DesignOptions design;
  std::vector<CameraModel> models;
  std::vector<Station> stations;
  std::vector<ObjectPoint> points;
  std::vector<ImageMeasurement> measurements;
  std::vector<DistanceConstraint> distances;
  ResidualTest residual_test;
};

// The network restricted to the named points: their measurements and the distances between them.
inline Network restricted_to_points(Network network, const std::set<std::string>& points) {
  std::erase_if(network.points, [&](const ObjectPoint& p) { return !points.count(p.name); });
  std::erase_if(network.measurements,
                [&](const ImageMeasurement& m) { return !points.count(m.point); });
  std::erase_if(network.distances, [&](const DistanceConstraint& d) {
    return !points.count(d.point_a) || !points.count(d.point_b);
  });
  return network;
}

}  // namespace syncap::scene
