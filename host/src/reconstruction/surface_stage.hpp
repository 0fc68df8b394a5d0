// The person's surface measured live (docs/design/matching.md, "Live"): on frames whose group
// carries image patches from the edges (syncap-edge --patch-every N, or `syncap ctl patches N`),
// GC3 and multi-image least-squares matching on the frame's visual hull, on a thread of its own.
// Matching a frame takes far longer than a camera period, so the stage never waits for it: a
// frame that comes while the matcher is busy is dropped and counted, and markers, hull and body
// go on at the camera rate. The rate it reaches is the edges' patch rate, or the matcher's,
// whichever is lower.
#pragma once

#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"
#include "reconstruction/hull_stage.hpp"
#include "sensor/camera_model.hpp"
#include "surface/surface_matcher.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::reconstruction {

struct SurfaceStageOptions {
  surface::SurfaceMatchingOptions matching;
  // Patches needed for a frame (a reference view and two search views at least).
  int min_cameras = 3;
  // The edges' silhouettes are shrunk by this many pixels into the matching masks: their
  // outline is the classification's (IoU ~0.97 against the truth on the replay bench), not
  // the exact object's, and a window across it mixes in background (surface's
  // make_matching_view).
  int mask_margin_px = 2;
  // Writes DIR/surface_<frame>.csv and .ply (surface/point_files.hpp) for every frame
  // matched; empty: no files.
  std::filesystem::path out_dir;
  // Called on the matcher's thread with the frame number before it matches a frame (tests hold
  // the matcher busy with it); empty: nothing.
  std::function<void(int64_t)> on_match_start;
};

// One matched frame.
struct SurfaceFrame {
  int64_t frame_number = 0;
  int cameras = 0;  // patches matched in
  std::size_t seeds = 0;
  std::size_t points = 0;
  double median_sigma_mm = 0;  // along the normal
  // Of the points, those whose projection falls outside a camera's silhouette by more than 3
  // of their sigmas, 0.71 px and mask_margin_px (the outline's own error;
  // surface/hull_consistency.hpp): implausible, a wrong match or cameras that
  // disagree with the images.
  std::size_t outside_silhouettes = 0;
  double match_ms = 0;  // decoding the patches, matching, writing (wall)
};

struct SurfaceStageStats {
  long frames_with_patches = 0;
  long matched = 0;          // frames the matcher finished
  long dropped_busy = 0;     // the matcher was busy with an earlier frame
  long no_hull = 0;          // patches, but the hull stage built no hull for the frame
  long few_cameras = 0;      // fewer than min_cameras patches with a whole silhouette
  long patches_partial = 0;  // camera patches with lost or corrupt parts (matched with the rest)
  long failed = 0;
  std::string last_error;  // names the frame
  long points = 0;
  long points_outside = 0;      // SurfaceFrame::outside_silhouettes, summed
  long frames_implausible = 0;  // frames with such a point
  pipeline::RecentValues match_ms;
  pipeline::RecentValues points_per_frame;
  std::vector<SurfaceFrame> frames;  // the latest 100 matched
};

class SurfaceStage : public pipeline::Stage {
 public:
  SurfaceStage(std::vector<sensor::CameraModel> cameras, SurfaceStageOptions options);
  ~SurfaceStage() override;
  // What the stage needs of the hull stage before it: the mesh's triangles (the seeds and the
  // facet-ID visibility are computed on them).
  static HullProducts needs() {
    HullProducts products;
    products.triangles = true;
    return products;
  }
  const char* name() const override { return "surface"; }
  void process(pipeline::FrameWork& work) override;
  // Waits for the frame being matched.
  void finish() override;
  SurfaceStageStats stats() const;
  // "host surface: ..." lines: frames with patches, matched, dropped, points, time.
  std::string summary() const;

 private:
  struct View {
    sensor::CameraModel camera;
    std::vector<image_patch_t> parts;
    proto::Silhouette silhouette;
  };
  struct Job {
    int64_t frame_number = 0;
    std::shared_ptr<const std::vector<std::array<Eigen::Vector3d, 3>>> triangles;
    std::vector<View> views;
  };
  bool busy() const;
  std::vector<View> views_of(const grouping::FrameGroup& group) const;
  void run(const Job& job);
  void record(const SurfaceFrame& frame, long partial);
  void record_failure(int64_t frame_number, const std::string& what);

  std::vector<sensor::CameraModel> cameras_;
  SurfaceStageOptions options_;
  mutable std::mutex mutex_;  // stats_: the matcher's thread writes, the caller reads
  SurfaceStageStats stats_;
  std::future<void> matching_;
};

}  // namespace syncap::reconstruction
