#include "controllers/stage_chain.hpp"

#include "body/hanim_model.hpp"
#include "outputs/body_message_stage.hpp"
#include "outputs/frame_line_stage.hpp"
#include "outputs/hull_message_stage.hpp"
#include "outputs/json_lines_stage.hpp"
#include "outputs/search_region_stage.hpp"

namespace syncap::controllers {

reconstruction::HullProducts PipelineOptions::hull_products() const {
  reconstruction::HullProducts products;
  if (body.enabled) products = products.with(reconstruction::BodyFitStage::needs(body.stage));
  if (surface.enabled) products = products.with(reconstruction::SurfaceStage::needs());
  return products;
}

namespace {

// Appends `stage` and returns it, to keep a pointer for the figures after the run.
template <typename S>
S* append(StageChain& chain, std::unique_ptr<S> stage) {
  S* kept = stage.get();
  chain.stages.push_back(std::move(stage));
  return kept;
}

void check(const std::vector<sensor::CameraModel>& cameras, const PipelineOptions& o,
           const Sinks& sinks) {
  const auto needs_cameras = [&](bool enabled, const char* what) {
    if (enabled && cameras.empty())
      throw StageChainError(std::string(what) + ": needs the cameras (a calibration)");
  };
  needs_cameras(o.hull.enabled, "hull");
  needs_cameras(o.body.enabled, "body");
  needs_cameras(o.surface.enabled, "surface");
  if (o.search_regions.enabled && !o.body.enabled)
    throw StageChainError("search regions: need the body (the tracked body)");
  if (o.search_regions.enabled && !sinks.send_search_region)
    throw StageChainError("search regions: need a sender (signed with the command key)");
}

void add_marker_stages(const std::vector<sensor::CameraModel>& cameras, const MarkerOptions& o,
                       const Sinks& sinks, StageChain& chain) {
  chain.markers =
      append(chain, std::make_unique<reconstruction::MarkerStage>(cameras, o.matching, o.stage));
  chain.tracking = append(chain, std::make_unique<reconstruction::TrackingStage>(
                                     o.tracker, sinks.tracks, o.frame_rate_hz));
  if (!o.rigid_sets.empty())
    chain.rigid_sets = append(chain, std::make_unique<reconstruction::RigidSetStage>(o.rigid_sets));
  if (sinks.publish_markers)
    chain.marker_message =
        append(chain, std::make_unique<outputs::MarkerMessageStage>(sinks.publish_markers));
}

void add_body_stages(const std::vector<sensor::CameraModel>& cameras, const PipelineOptions& o,
                     const Sinks& sinks, StageChain& chain) {
  chain.body = append(
      chain, std::make_unique<reconstruction::BodyFitStage>(body::hanim_skeleton(), o.body.stage));
  if (sinks.publish_body)
    chain.stages.push_back(std::make_unique<outputs::BodyMessageStage>(sinks.publish_body));
  if (sinks.poses != nullptr)
    chain.stages.push_back(std::make_unique<outputs::PoseRecordStage>(*sinks.poses));
  if (o.search_regions.enabled)
    chain.stages.push_back(std::make_unique<outputs::SearchRegionStage>(
        cameras, o.search_regions.stage, sinks.send_search_region));
}

}  // namespace

StageChain make_stages(const std::vector<sensor::CameraModel>& cameras, const PipelineOptions& o,
                       const Sinks& sinks) {
  check(cameras, o, sinks);
  StageChain chain;
  const bool markers = o.markers.enabled && !cameras.empty();
  if (markers) add_marker_stages(cameras, o.markers, sinks, chain);
  if (o.hull_built()) {
    chain.hull = append(chain, std::make_unique<reconstruction::HullStage>(cameras, o.hull.stage,
                                                                           o.hull_products()));
    if (sinks.publish_hull)
      chain.stages.push_back(std::make_unique<outputs::HullMessageStage>(sinks.publish_hull));
  }
  if (o.body.enabled) add_body_stages(cameras, o, sinks, chain);
  if (o.surface.enabled)
    chain.surface =
        append(chain, std::make_unique<reconstruction::SurfaceStage>(cameras, o.surface.stage));
  if (sinks.frame_lines != nullptr)
    chain.stages.push_back(std::make_unique<outputs::FrameLineStage>(
        *sinks.frame_lines, sinks.frame_line_cameras, markers));
  if (sinks.json_lines != nullptr)
    chain.stages.push_back(std::make_unique<outputs::JsonLinesStage>(*sinks.json_lines, markers));
  return chain;
}

}  // namespace syncap::controllers
