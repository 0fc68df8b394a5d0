// The articulated body fitted to every frame's visual hull and tracked (docs/design/body-fit.md,
// "Live"): the stage after the hull stage. Points spread over the hull's surface (what needs() asks
// of the hull stage) are the observations. The first frame with a hull starts the body
// automatically (fitting::start_body); every later frame is fitted from the tracker's
// prediction, and a frame whose fit loses the track (too few points kept) starts again from its
// own hull. Each frame the stage worked on gets a pipeline::BodyFitSummary (the pose, the
// joints' centres, the fit's RMS and points kept, flags); a frame without a hull is flagged,
// never fitted from nothing, and the stage never stops the pipeline.
#pragma once

#include <string>

#include <cstdint>
#include <limits>
#include "body/skeleton.hpp"
#include "fitting/body_start.hpp"
#include "fitting/body_tracker.hpp"
#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"

#include "reconstruction/hull_stage.hpp"

namespace syncap::reconstruction {

struct BodyFitStageOptions {
  // Points spread over each hull's surface for the fit (asked of the hull stage: needs()).
  std::size_t hull_points = 1600;
  fitting::BodyTrackerOptions tracker;
  fitting::BodyStartOptions start;
  // The hull's points' standard deviation [mm]: the hull is the silhouettes' cones' intersection,
  // it lies on or outside the body, by up to centimetres between the views
  // (docs/design/body-fit.md).
  double point_sigma_mm = 10.0;
  // Drops the track on every frame whose number is a multiple of this, so that the frame starts
  // the body automatically: measures the automatic start all through a recording (syncap fit
  // --restart-every); 0: never.
  int restart_every = 0;
  // After a start that found no body, the next start is tried this many frames later; the frames
  // between are flagged FLAG_NO_START at no cost. A start costs a few fits (0.1-5 s on a hull
  // that is no standing person), so a recording without a person to start costs its share of one
  // attempt a frame (syncap fit --body-start-retry-frames). 1: every frame.
  int start_retry_frames = 10;
  // ... or more, so that failed starts cost at most this much a frame on average: a start that
  // took T ms of CPU time (the thread's: the same on a loaded machine) is retried after
  // T / start_budget_ms frames when that is longer (a seated person's
  // hull cost 6 s an attempt on a real studio recording: every 30th frame). 0: no budget.
  double start_budget_ms = 200.0;
};

struct BodyFitStageStats {
  long frames = 0;       // groups with a hull (or a failed one)
  long no_hull = 0;      // of them, no hull or too few points to fit
  long starts = 0;       // automatic starts that found the body
  long no_start = 0;     // automatic starts that did not
  long start_waits = 0;  // frames not tried after a start that found no body (start_retry_frames)
  long tracked = 0;      // frames fitted by the tracker
  long lost = 0;         // of them, the track lost (and started again on the same frame)
  std::string last_problem;
  pipeline::RecentValues fit_us;  // per frame: a start or a tracked fit
};

class BodyFitStage : public pipeline::Stage {
 public:
  // Throws std::invalid_argument when the skeleton lacks a fitted joint.
  explicit BodyFitStage(const body::Skeleton& skeleton, BodyFitStageOptions options = {});
  // What the stage needs of the hull stage before it: points over each hull's surface.
  static HullProducts needs(const BodyFitStageOptions& options) {
    HullProducts products;
    products.surface_samples = options.hull_points;
    return products;
  }
  const char* name() const override { return "body fit"; }
  void process(pipeline::FrameWork& work) override;
  const BodyFitStageStats& stats() const { return stats_; }
  // The frame before which no start is tried (after one that found no body).
  int64_t next_start_frame() const { return next_start_frame_; }
  const fitting::PoseParameters& parameters() const { return parameters_; }
  // "host body: ..." lines: frames, starts, tracked, lost, time p50/p99, the last problem.
  std::string summary() const;

 private:
  void fit(int64_t frame_number, std::span<const fitting::SurfacePoint> points,
           pipeline::BodyFitSummary& body);
  // The automatic start on this frame's points; the tracker goes on from it when it found the body.
  // Frames to wait after a start that failed in `start_ms` (start_retry_frames, start_budget_ms).
  int retry_frames(double start_ms) const;
  void start(int64_t frame_number, std::span<const fitting::SurfacePoint> points,
             pipeline::BodyFitSummary& body);
  void describe(const fitting::SurfaceFit& fit, pipeline::BodyFitSummary& body) const;

  fitting::PoseParameters parameters_;
  std::vector<std::string> joint_names_;  // body_frame_t's joints (parameters_.reported_nodes())
  BodyFitStageOptions options_;
  fitting::BodyTracker tracker_;
  BodyFitStageStats stats_;
  int64_t next_start_frame_ = std::numeric_limits<int64_t>::min();
  int64_t failed_start_frame_ = std::numeric_limits<int64_t>::max();  // the last start that failed
};

}  // namespace syncap::reconstruction
