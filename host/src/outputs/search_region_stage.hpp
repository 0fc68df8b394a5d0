// Sends each camera's edge the tracked body's search region after every fitted frame
// (clip_polygon_t of kind REGION_SEARCH on SYNCAP_EDGE_CLIP, signed by the caller's publish):
// the body's ellipsoids at the fitted pose, projected and grown (fitting::search_region). The
// edge then classifies only inside, for the frames it is valid for (docs/design/segmentation.md,
// "Regions from the host"). syncap-host's --search-regions.
#pragma once

#include <functional>
#include <vector>

#include "body/pose.hpp"
#include "body/skeleton.hpp"
#include "fitting/pose_parameters.hpp"
#include "fitting/search_region.hpp"
#include "pipeline/frame_work.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/clip_polygon_t.hpp"

namespace syncap::outputs {

struct SearchRegionStageOptions {
  fitting::SearchRegionOptions region;
  int lead = 1;          // a fit of frame F serves from frame F + lead on
  int valid_frames = 8;  // for this many frames (0.27 s at 30 Hz): a lost track expires
};

// The search region message of `camera` for a body at `ellipsoids` fitted on frame `frame`
// (sequence and signature left to the sender). No points when the body reaches behind the camera
// (the whole frame) or is not in its image; `whole_image` says which.
clip_polygon_t search_region_message(const sensor::CameraModel& camera,
                                     const std::vector<body::Ellipsoid>& ellipsoids, int64_t frame,
                                     const SearchRegionStageOptions& options,
                                     bool* whole_image = nullptr);

class SearchRegionStage : public pipeline::Stage {
 public:
  using Publish = std::function<void(clip_polygon_t&)>;  // signs and sends
  SearchRegionStage(std::vector<sensor::CameraModel> cameras, SearchRegionStageOptions options,
                    Publish publish);
  const char* name() const override { return "search regions"; }
  void process(pipeline::FrameWork& work) override;

  long frames_sent() const { return frames_sent_; }  // fitted frames whose regions were sent

 private:
  std::vector<sensor::CameraModel> cameras_;
  SearchRegionStageOptions options_;
  Publish publish_;
  body::Skeleton skeleton_;
  fitting::PoseParameters parameters_;
  long frames_sent_ = 0;
};

}  // namespace syncap::outputs
