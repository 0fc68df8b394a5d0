// The visual hull of every frame group with silhouettes (docs/visual-hull.md): the edges'
// silhouette contours, with the calibrated cameras, intersected exactly (hull::exact_visual_hull).
// Each group gives a hull_frame_t (volume, area, box, size, time, flags) through a callback, and,
// when asked, the mesh as a PLY file. A camera of the calibration without a silhouette in the
// group is left out and the frame flagged; fewer than 3 silhouettes are flagged (the hull is
// loose); a hull that cannot be built (views that disagree, a bad silhouette) is flagged FAILED,
// counted, and its reason kept: the stage never stops the pipeline.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hull/visual_hull.hpp"
#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/hull_frame_t.hpp"

namespace syncap::reconstruction {

struct HullStageOptions {
  // Where the working volume is; default: estimated per frame from the silhouettes.
  std::optional<hull::WorkingVolume> volume;
  // Writes DIR/hull_<frame>.ply every `mesh_every` frames; empty: no meshes.
  std::filesystem::path mesh_dir;
  int mesh_every = 1;
  // The full mesh check (self-intersections: an AABB tree of the faces, several ms); otherwise
  // closedness, orientation and manifoldness only.
  bool check_self_intersection = false;
};

struct HullStageStats {
  long frames = 0;  // groups with at least one silhouette
  long hulls = 0;   // built
  long failed = 0;
  long few_cameras = 0;
  long cameras_missing = 0;
  long not_closed = 0;  // built, but failed a mesh check
  std::string last_error;
  pipeline::RecentValues hull_us;  // building one hull
};

class HullStage : public pipeline::Stage {
 public:
  using Publish = std::function<void(const hull_frame_t&)>;
  HullStage(std::vector<sensor::CameraModel> cameras, HullStageOptions options, Publish publish);
  const char* name() const override { return "hull"; }
  void process(pipeline::FrameWork& work) override;
  const HullStageStats& stats() const { return stats_; }
  std::string summary() const;

 private:
  std::vector<hull::HullView> views_of(const host::FrameGroup& group, hull_frame_t& message);
  void build(const pipeline::FrameWork& work, std::vector<hull::HullView> views,
             hull_frame_t& message);

  std::vector<sensor::CameraModel> cameras_;
  HullStageOptions options_;
  Publish publish_;
  HullStageStats stats_;
};

// A silhouette as the edges send it (proto), as the hull takes it.
hull::Silhouette hull_silhouette(const proto::Silhouette& silhouette);

}  // namespace syncap::reconstruction
