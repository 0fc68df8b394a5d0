// The markers of a frame group: the blobs of the calibrated cameras matched across cameras and
// triangulated with their precision (matching::MarkerMatcher). Blobs of cameras the calibration
// does not know are left out, and counted.
#pragma once

#include <map>
#include <vector>

#include "matching/marker_matcher.hpp"
#include "pipeline/frame_work.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::reconstruction {

struct MarkerStageStats {
  long frames = 0;
  long markers = 0;
  long two_camera_markers = 0;
  long blobs = 0;
  long blobs_of_unknown_cameras = 0;  // cameras outside the calibration
  long blobs_used = 0;                // in a marker
};

class MarkerStage : public pipeline::Stage {
 public:
  MarkerStage(std::vector<sensor::CameraModel> cameras, matching::MatchOptions options);
  const char* name() const override { return "markers"; }
  void process(pipeline::FrameWork& work) override;
  const MarkerStageStats& stats() const { return stats_; }

 private:
  matching::MarkerMatcher matcher_;
  std::map<int, std::size_t> index_of_camera_;  // camera id -> the matcher's index
  MarkerStageStats stats_;
};

}  // namespace syncap::reconstruction
