// The network both calibration-side benchmarks measure: six cameras on a full ring, 1000 wand
// frames of three targets (18000 image measurements), simulated by the estimators' wand
// simulation with its defaults otherwise.
#pragma once

#include "estimators/bundle_adjustment_simulation.hpp"

namespace syncap::bench {

inline scene::Network six_camera_wand_network() {
  estimators::WandSimulation sim;
  sim.cameras = 6;
  sim.arc_deg = 360.0;
  sim.frames = 1000;
  return estimators::simulate_wand_network(sim).network;
}

}  // namespace syncap::bench
