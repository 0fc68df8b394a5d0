// The visual hull of every frame group with silhouettes (docs/design/visual-hull.md): the edges'
// silhouette contours, with the calibrated cameras, intersected by the method of the options.
// Each group gets a pipeline::HullSummary (volume, area, box, size, time, flags, and per view
// the reprojection IoU when asked) and, when asked, the mesh as a PLY file. A camera of the
// calibration without a silhouette in the group is left out and the frame flagged; fewer than 3
// silhouettes are flagged (the hull is loose); a hull that cannot be built (views that disagree,
// a bad silhouette) is flagged FAILED, counted, and its reason kept: the stage never stops the
// pipeline.
#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hull/visual_hull.hpp"
#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::reconstruction {

enum class HullMethod {
  // The cones' exact intersection, face by face (hull/polyhedral_hull.hpp): ~20 ms for 8 views.
  // Where it fails (a degenerate assembly, a hull the working volume cuts), the voxel hull
  // stands in and the frame is flagged FLAG_FALLBACK.
  kPolyhedral,
  kVoxel,  // octree carving + marching tetrahedra (hull/voxel_hull.hpp): ~0.1 s at 128
  kExact,  // the same solid by CGAL corefinement (hull/visual_hull.hpp): seconds; a reference
};

// "polyhedral", "voxel" or "exact"; std::nullopt otherwise.
std::optional<HullMethod> hull_method_from_name(const std::string& name);
const char* hull_method_name(HullMethod method);

struct HullStageOptions {
  HullMethod method = HullMethod::kPolyhedral;
  int voxel_resolution = 128;  // cells along the hull's longest side (kVoxel)
  // Where the working volume is (default: estimated per frame from the silhouettes, its radius
  // times volume_margin) and the capture volume every hull is clipped to (none: not clipped):
  // what every hull method takes.
  hull::HullOptions hull;
  // A hull every `every` frames (frame_number % every == 0): the others pass untouched.
  int every = 1;
  // A group that waited longer than this in the host [ms] gets no hull (counted): the hull, far
  // slower than the markers, then keeps the worker's queue short instead of holding back every
  // later frame's markers. 0: a hull for every group however late.
  double max_wait_ms = 100.0;
  // Per view, the IoU of the hull's reprojection against the silhouette (rendering the mesh in
  // every camera: milliseconds); a view below `min_view_iou` flags FLAG_VIEWS_DISAGREE.
  bool view_iou = false;
  double min_view_iou = 0.9;
  // The full mesh check (self-intersections: an AABB tree of the faces, several ms); otherwise
  // closedness, orientation and manifoldness only.
  bool check_self_intersection = false;
  // Writes DIR/hull_<frame>.ply for every hull built; empty: no meshes.
  std::filesystem::path mesh_dir;
};

// What later stages need of every hull beyond its measures. A consumer states it
// (BodyFitStage::needs, SurfaceStage::needs) and the pipeline's composer hands the union to the
// hull stage (controllers/stage_chain.hpp): no consumer sets the hull's options.
struct HullProducts {
  // Points spread evenly over each hull's surface into HullSummary::surface_mm; 0: none.
  std::size_t surface_samples = 0;
  // The mesh's triangles into HullSummary::triangles.
  bool triangles = false;

  // What both need: the larger sample, the triangles if either wants them.
  HullProducts with(const HullProducts& other) const {
    return {std::max(surface_samples, other.surface_samples), triangles || other.triangles};
  }
};

struct HullStageStats {
  long frames = 0;        // groups with at least one silhouette, on the --every grid
  long skipped_late = 0;  // of those, no hull: they waited longer than max_wait_ms
  long hulls = 0;         // built
  long failed = 0;
  long few_cameras = 0;
  long cameras_missing = 0;  // silhouettes missing, over all frames
  long not_closed = 0;       // built, but failed a mesh check
  long fallbacks = 0;        // the polyhedral method failed, the voxel hull stood in
  long views_disagree = 0;   // frames with a view below min_view_iou
  double min_view_iou = 1.0;
  std::string last_error;
  pipeline::RecentValues hull_us;  // building one hull
};

class HullStage : public pipeline::Stage {
 public:
  HullStage(std::vector<sensor::CameraModel> cameras, HullStageOptions options,
            HullProducts products = {});
  const char* name() const override { return "hull"; }
  void process(pipeline::FrameWork& work) override;
  const HullStageStats& stats() const { return stats_; }
  // "host hull: ..." lines: frames, hulls, failures, time p50/p99, the last failure.
  std::string summary() const;

 private:
  std::vector<hull::HullView> views_of(const grouping::FrameGroup& group,
                                       pipeline::HullSummary& summary);
  void build(int64_t frame_number, const std::vector<hull::HullView>& views,
             pipeline::HullSummary& summary);
  hull::Mesh hull_of(const std::vector<hull::HullView>& views, pipeline::HullSummary& summary);
  void measure(const hull::Mesh& mesh, const std::vector<hull::HullView>& views,
               pipeline::HullSummary& summary);

  std::vector<sensor::CameraModel> cameras_;
  HullStageOptions options_;
  HullProducts products_;
  HullStageStats stats_;
};

// A silhouette as the edges send it (proto: contours through the boundary pixels' centres), as
// the hull takes it: moved onto the pixels' edges (hull::on_pixel_edges). The hull and surface
// stages both read silhouettes through it.
hull::Silhouette hull_silhouette(const proto::Silhouette& silhouette);

}  // namespace syncap::reconstruction
