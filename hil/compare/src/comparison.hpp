// The comparison of the host's frame groups with the simulator's truth, and its verdict.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "groups.hpp"
#include "statistics.hpp"
#include "truth.hpp"

namespace syncap::compare {

struct Thresholds {
  double max_rms_px = 0.1;      // per camera: RMS centroid error of matched counted targets
  double min_detection = 0.98;  // per camera: matched / counted targets in frames it reported
  double match_radius_px = 3;   // a blob farther than this from every target is a false blob
  double min_frames = 0.99;     // complete groups / truth frames
  double min_iou = 0.95;        // per camera: mean IoU of its silhouettes against the true masks
  // per camera: silhouettes received / frames with a true mask must reach min_frames (off: a
  // camera that sent no silhouettes is not judged on them)
  bool require_silhouettes = false;
};

struct FrameCounts {
  long truth = 0;     // frames the simulator rendered
  long at_host = 0;   // of those, frames the host handed out a group for
  long complete = 0;  // of those, groups with the trigger and every camera

  // complete / truth; 0 without truth frames.
  double complete_share() const {
    return truth ? static_cast<double>(complete) / static_cast<double>(truth) : 0.0;
  }
};

struct CameraReport {
  Tally tally;
  long groups_with = 0;     // truth frames whose group holds this camera's blobs
  long groups_without = 0;  // truth frames whose group lacks them
  Samples processing_us;
  SilhouetteTally silhouettes;
};

struct PhaseReport {
  FrameCounts frames;
  Tally tally;  // all cameras
  SilhouetteTally silhouettes;
};

struct Report {
  Thresholds thresholds;
  PhaseReport overall;
  std::map<int, CameraReport> cameras;        // by camera id: in cameras.json or in the groups
  std::map<std::string, PhaseReport> phases;  // by phase type, every type of frames.csv
  std::vector<std::string> phase_types;       // the keys of `phases` in the scenario's order
  long groups_outside_truth = 0;              // groups for frames the truth does not have
  std::vector<std::string> failures;          // empty: pass

  bool pass() const { return failures.empty(); }
};

Report compare(const Truth& truth, const std::vector<Group>& groups, const Thresholds& thresholds);

// One camera in one frame; `image` sizes the border test.
Tally compare_camera_frame(const std::vector<Projection>& targets, const std::vector<Blob>& blobs,
                           const ImageSize& image, double match_radius_px);

}  // namespace syncap::compare
