// The steps of `calibrate()` between the network and its final adjustment (calibrate.hpp, steps
// 3-4), shared by the calibration itself, the search of its start (start_search.hpp) and the
// bootstrap's restarts.
#pragma once

#include "calibration/calibrate.hpp"

namespace syncap::calibration {

// Start interior: centred principal point, no distortion, c from a horizontal field of view.
sensor::InteriorOrientation start_interior(const sensor::SensorGeometry& sensor,
                                           double field_of_view_deg);

// `count` of `frames` (ordered), evenly spread; all of them when count <= 0 or they are fewer.
std::vector<int64_t> evenly_spread(std::vector<int64_t> frames, int count);

// Moves the network (stations and points, rigidly) into the levelled frame documented in
// calibrate.hpp.
void level_network(scene::Network& network);

struct Stage {
  bool distortion_free = false;  // false: only c, xp, yp (those of them the options free)
  bool snoop = false;            // data snooping, covariance and tests
  // The blunders are gone already (a network data snooping cleaned): no snooping, but the
  // covariance and tests, and the hold on c as loose as after snooping.
  bool clean = false;
};

// The stage's free and held values, design and tests on `network`.
void prepare_stage(scene::Network& network, const CalibrationOptions& options, Stage stage);

estimators::BundleAdjustmentResult adjust_stage(scene::Network& network,
                                                const CalibrationOptions& options, Stage stage);

// The adjustment's options with its progress told on options.progress while it runs long: a line
// ("<what>: solve 2, iteration 14, cost 1234.5, 45120 measurements, 3 s") once a second after
// its first second; nothing for an adjustment done within a second.
estimators::BundleOptions adjustment_options(const CalibrationOptions& options,
                                             const std::string& what);

// The second stage's approximate values from a network's observations alone: the start
// (relative orientations, resection, scale), the first stage (c, xp, yp and the exterior, on the
// points the start triangulated), and the levelled frame. The models' interiors are the start's.
struct SecondStageStart {
  scene::Network network;
  NetworkStartReport start;
  estimators::BundleAdjustmentResult first;
};

SecondStageStart second_stage_start(scene::Network network, const CalibrationOptions& options);

}  // namespace syncap::calibration
