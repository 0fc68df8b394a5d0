// `syncap bundle FILE.sdl [--out DIR]`: reads a scene description (docs/reference/sdl.md), runs the
// self-calibrating bundle adjustment (estimators::adjust) as its design block says, prints the
// summary, and writes the adjusted network as SDL.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "scene/network.hpp"

namespace syncap::tools {

// SIMULATE: replaces every measurement's u, v by the projection of its point's approximate
// coordinates through its station's approximate camera plus Gaussian noise of its sigma_px, and
// every distance by the distance of the approximate points plus noise of its sigma, drawn from
// std::mt19937(network.design.simulation_seed). Throws std::invalid_argument naming the
// measurement or distance that cannot be simulated (unknown name, no approximate values, a point
// that does not project).
void simulate_observations(scene::Network& network);

// Parses its options with CLI11 (--help: the design tags, the options, the exit statuses).
int bundle_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
