// The markers of a frame group: the blobs of the calibrated cameras matched across cameras and
// triangulated with their precision (matching::MarkerMatcher). Blobs of cameras the calibration
// does not know are left out, and counted. So are blobs the edge flagged NOT_ROUND (unless kept):
// a marker partly hidden by the body, or two markers run together, make a spot whose centroid is
// off by up to a pixel; on the mocap replay (markers-8cam-body) leaving them out took the ghosts
// from 4.7 % to 1.8 % and the found markers from 97.3 % to 98.8 % (docs/reconstruction.md).
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
  long blobs_not_round = 0;           // flagged NOT_ROUND by the edge: left out
  long blobs_used = 0;                // in a marker
};

class MarkerStage : public pipeline::Stage {
 public:
  MarkerStage(std::vector<sensor::CameraModel> cameras, matching::MatchOptions options,
              bool keep_not_round = false);
  const char* name() const override { return "markers"; }
  void process(pipeline::FrameWork& work) override;
  const MarkerStageStats& stats() const { return stats_; }

 private:
  matching::MarkerMatcher matcher_;
  bool keep_not_round_;
  std::map<int, std::size_t> index_of_camera_;  // camera id -> the matcher's index
  MarkerStageStats stats_;
};

}  // namespace syncap::reconstruction
