// What the host's stages do, in one structure: the options every program that runs the stage
// chain fills (syncap-host from its command line, syncap markers and syncap fit from theirs) and
// hands to make_stages (controllers/stage_chain.hpp). No transport, file or key here: those are
// the caller's (Sinks).
#pragma once

#include <cstddef>
#include <vector>

#include "matching/marker_matcher.hpp"
#include "outputs/search_region_stage.hpp"
#include "reconstruction/body_fit_stage.hpp"
#include "reconstruction/hull_stage.hpp"
#include "reconstruction/marker_stage.hpp"
#include "reconstruction/surface_stage.hpp"
#include "tracking/marker_tracker.hpp"
#include "tracking/rigid_set.hpp"

namespace syncap::controllers {

// The markers of every frame: matched across cameras, triangulated, tracked (docs/
// reconstruction.md), and the rigid sets' poses among them.
struct MarkerOptions {
  bool enabled = true;
  matching::MatchOptions matching;
  reconstruction::MarkerStageOptions stage;
  tracking::TrackerOptions tracker;
  double frame_rate_hz = 0;  // > 0: the tracker times frames by number at this rate
  std::vector<tracking::RigidSet> rigid_sets;  // none: no rigid set stage
};

// The person's visual hull of every frame with silhouettes (docs/visual-hull.md). Also built,
// without being asked, for the stages that need it (the body, the surface).
struct HullOptions {
  bool enabled = false;
  reconstruction::HullStageOptions stage;
};

// The articulated body fitted to every hull and tracked (docs/body-fit.md).
struct BodyOptions {
  bool enabled = false;
  reconstruction::BodyFitStageOptions stage;
};

// The surface matched on the frames with image patches (docs/matching.md, "Live").
struct SurfaceOptions {
  bool enabled = false;
  reconstruction::SurfaceStageOptions stage;
};

// The tracked body's search regions sent to the edges after every fit (docs/segmentation.md).
struct SearchRegionOptions {
  bool enabled = false;
  outputs::SearchRegionStageOptions stage;
};

struct PipelineOptions {
  MarkerOptions markers;
  HullOptions hull;
  BodyOptions body;
  SurfaceOptions surface;
  SearchRegionOptions search_regions;

  // The hull is built when asked for or when a stage after it needs it.
  bool hull_built() const { return hull.enabled || body.enabled || surface.enabled; }
  // What the stages after the hull need of it (each states its own needs).
  reconstruction::HullProducts hull_products() const;
};

}  // namespace syncap::controllers
