// Start values of a multi-camera network (thesis section 4.1.2: relative orientations as the
// starting point of the bundle adjustment): from the image measurements of common points (wand
// targets, LEDs) alone, the approximate exterior orientation of every station and approximate
// coordinates of every point seen twice.
//
// The way: the pair graph weighted by the number of shared points; its maximum spanning tree,
// rooted at the best-connected station; the relative orientation (RDLT,
// estimators/relative_orientation.hpp) along each tree edge, chained into the root's frame with
// each edge's scale taken from points already triangulated; stations the tree cannot place
// (failed or weak edges) by spatial resection (cv::solvePnPRansac) on the triangulated points;
// finally the scale from the known distances (the median of true / measured wand lengths).
//
// The frame: the root station's sensor frame (its projection centre at the origin, angles zero,
// looking along -Z), in mm when the network has distance constraints. The bundle adjustment moves
// it where the datum says.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "estimators/relative_orientation.hpp"
#include "scene/network.hpp"

namespace syncap::calibration {

struct NetworkStartOptions {
  // A station must share at least this many observations with the others, a tree edge this many
  // points, and a resection needs this many triangulated points.
  int min_shared_observations = 12;
  // The length of the first base when the network has no distance constraint [mm].
  double default_base_mm = 1000.0;
  // A ray farther than this from its triangulated point is left out of the point [px].
  double max_ray_error_px = 4.0;
  estimators::RelativeOrientationOptions relative;
};

// What happened, for the log and the tests.
struct NetworkStartEdge {
  std::string parent;  // station names
  std::string child;
  int shared_points = 0;
  bool oriented = false;  // false: the relative orientation failed, the child was resected
  estimators::RelativeOrientation relative;
};

struct NetworkStartReport {
  std::string root;                     // station name
  std::vector<NetworkStartEdge> edges;  // the spanning tree, in the order it was walked
  std::vector<std::string> resected;    // stations placed by spatial resection
  int triangulated_points = 0;
  int untriangulated_points = 0;      // seen by fewer than two oriented stations
  int distances_used = 0;             // distance constraints behind the scale
  double scale = 1.0;                 // applied to the relative model (true / measured)
  bool scale_from_distances = false;  // false: the first base has default_base_mm
};

struct NetworkStart {
  scene::Network network;  // the input with station exteriors and point approximations filled
  NetworkStartReport report;
};

// Bad input or a network that cannot be started (a camera with too few shared observations, a
// station nothing orients), with a message naming the camera or the measurement.
class NetworkStartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every station gets exterior approximations (has_approximation = true); every point seen by at
// least two oriented stations gets coordinates (has_approximation = true, added to
// network.points when only measured). Throws NetworkStartError.
NetworkStart start_network(const scene::Network& network, const NetworkStartOptions& options = {});

}  // namespace syncap::calibration
