// Internal to adjust() (bundle_adjustment.hpp): the network checked and its names resolved to
// indices, so that the adjustment works with indices and every error names its element once.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene/network.hpp"

namespace syncap::estimators {

struct ResolvedNetwork {
  explicit ResolvedNetwork(const scene::Network& of) : network(of) {}

  const scene::Network& network;
  std::vector<int> station_model;                    // per station: its camera model
  std::vector<int> measurement_station;              // per image measurement
  std::vector<int> measurement_point;                // per image measurement
  std::vector<std::pair<int, int>> distance_points;  // per distance: its two points
};

// Throws NetworkError (bundle_adjustment.hpp) naming the element and what is wrong.
ResolvedNetwork resolve(const scene::Network& network);

// A control point: none of its coordinates is free, so it keeps its given value.
bool point_held(const scene::ObjectPoint& point);

// A name as the messages show it.
inline std::string quoted(const std::string& s) { return "\"" + s + "\""; }

}  // namespace syncap::estimators
