// The host's stage chain, composed once (COLMAP's controllers/): every program that runs the
// stages on frame groups (syncap-host live, syncap markers and syncap fit offline) builds them
// here from a PipelineOptions and the Sinks it wants the results in, and gets them in the one
// order they run in:
//
//   markers -> tracking -> rigid sets -> marker message -> hull -> hull message -> body fit ->
//   body message -> pose record -> search regions -> surface -> frame line -> JSON lines
//
// The markers' message leaves before the slower hull is built; the surface, last of the 3D
// stages, hands its frame to a thread of its own and returns at once. A stage that needs another
// stage's product states it (BodyFitStage::needs, SurfaceStage::needs); the chain asks it of the
// producer, so no consumer sets its producer's options.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "controllers/pipeline_options.hpp"
#include "outputs/marker_message_stage.hpp"
#include "outputs/pose_record_stage.hpp"
#include "pipeline/frame_work.hpp"
#include "reconstruction/rigid_set_stage.hpp"
#include "reconstruction/tracking_stage.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/body_frame_t.hpp"
#include "syncap/clip_polygon_t.hpp"
#include "syncap/hull_frame_t.hpp"
#include "syncap/marker_frame_t.hpp"
#include "tracking/track_history.hpp"

namespace syncap::controllers {

// Where the chain's results go; each unset sink leaves its stage out. The caller owns every
// stream and record, which must outlive the stages.
struct Sinks {
  std::function<void(const marker_frame_t&)> publish_markers;
  std::function<void(const hull_frame_t&)> publish_hull;
  std::function<void(const body_frame_t&)> publish_body;
  // Sends a search region to the edges (the caller signs it); needed with search_regions.
  std::function<void(clip_polygon_t&)> send_search_region;
  // A line per frame group ("frame 12: trigger ok, cameras 3/3 | ..."), with how many cameras
  // are expected.
  std::ostream* frame_lines = nullptr;
  std::size_t frame_line_cameras = 0;
  std::ostream* json_lines = nullptr;        // every group (and its markers) as a JSON line
  tracking::TrackHistory* tracks = nullptr;  // the tracked markers, for the C3D/TRC exports
  outputs::PoseRecord* poses = nullptr;      // the fitted poses, for the BVH/C3D/TRC exports
};

// The chain, and its stages that callers read figures from after the run (null when absent).
struct StageChain {
  std::vector<std::unique_ptr<pipeline::Stage>> stages;
  const reconstruction::MarkerStage* markers = nullptr;
  const reconstruction::TrackingStage* tracking = nullptr;
  const reconstruction::RigidSetStage* rigid_sets = nullptr;
  const outputs::MarkerMessageStage* marker_message = nullptr;
  const reconstruction::HullStage* hull = nullptr;
  const reconstruction::BodyFitStage* body = nullptr;
  const reconstruction::SurfaceStage* surface = nullptr;
};

// Bad combinations of options and sinks: what() names the option ("body: needs the cameras").
class StageChainError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The stages for `options` and `sinks`. The 3D stages need `cameras` (the calibration): without
// them only the frame lines and JSON lines run, and a 3D stage asked for throws StageChainError,
// as do search regions without a body or a sender.
StageChain make_stages(const std::vector<sensor::CameraModel>& cameras,
                       const PipelineOptions& options, const Sinks& sinks);

}  // namespace syncap::controllers
