// `syncap bundle FILE.sdl [--out DIR]`: reads a scene description (docs/sdl.md), runs the
// self-calibrating bundle adjustment (estimators::adjust) as its design block says, prints the
// summary, and writes the adjusted network as SDL.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "scene/network.hpp"

namespace syncap::tools {

inline constexpr const char* kBundleUsage =
    "usage: syncap bundle FILE.sdl [--out DIR]\n"
    "Reads the scene FILE.sdl (docs/sdl.md), adjusts it (self-calibrating bundle adjustment,\n"
    "docs/calibration.md) as its design block says and prints the summary. Design tags:\n"
    "  SIMULATE            measurements and distances generated from the approximate values\n"
    "                      with noise of their sigmas (seed: SEED n) before adjusting\n"
    "  SORT                models, stations and points sorted by name\n"
    "  OUTPUT MESSAGES     the adjustment's messages before the summary\n"
    "  OUTPUT MISCLOSURES  per measurement: approximate projection - measured [px]\n"
    "  OUTPUT CORRECTIONS  per parameter: adjusted - approximate value\n"
    "  OUTPUT COEFFICIENT MATRIX  d(u, v)/d(parameters) at the adjusted values, as triplets\n"
    "  RESIDUALS           per measurement residuals and w (DIR/residuals.tsv, with --out)\n"
    "  DEBUG               the network's size and the design as read\n"
    "The OUTPUT tables go to DIR/NAME.tsv with --out, else to stdout after the summary.\n"
    "  --out DIR  writes DIR/adjusted.sdl (the adjusted network), DIR/summary.txt and the tables\n"
    "Exit status: 0 adjusted and converged, 1 not converged, 2 usage error or a scene that does\n"
    "not parse or cannot be adjusted (the message names file, line and column or the element).\n";

// SIMULATE: replaces every measurement's u, v by the projection of its point's approximate
// coordinates through its station's approximate camera plus Gaussian noise of its sigma_px, and
// every distance by the distance of the approximate points plus noise of its sigma, drawn from
// std::mt19937(network.design.simulation_seed). Throws std::invalid_argument naming the
// measurement or distance that cannot be simulated (unknown name, no approximate values, a point
// that does not project).
void simulate_observations(scene::Network& network);

int bundle_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
