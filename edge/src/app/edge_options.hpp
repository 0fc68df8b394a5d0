// Command line of syncap-edge.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "detection/blob_detector.hpp"

namespace syncap::edge {

struct EdgeOptions {
  int camera_id = 0;
  std::string source;          // "replay:FOLDER" or "aravis:ADDRESS"
  std::string trigger_source;  // aravis: camera TriggerSource; empty: as configured
  double exposure_us = 0;      // aravis: 0 = as configured
  bool udp_socket = false;     // aravis: plain UDP socket instead of a packet socket
  bool blobs = true;           // --mode blobs|mask|both
  bool mask = false;
  int train_frames = 0;  // mask: train on the first N frames (0: wait for the command)
  double contour_tolerance_px = 1.0;
  std::string lcm_url;
  BlobDetectorConfig detector;
  double heartbeat_s = 1.0;
  bool exit_after_last = false;  // leave after the trigger's last pulse of a run
  bool quiet = false;
};

// A bad command line; what() names the option and the value.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses argv[1..]; throws UsageError. --help is reported as UsageError("help").
EdgeOptions parse_edge_options(const std::vector<std::string>& args);

std::string edge_usage();

}  // namespace syncap::edge
