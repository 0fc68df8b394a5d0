// The host's visual hulls (syncap-host --hull --hull-meshes DIR) against the simulator's true
// body (truth/body.jsonl: the person's ellipsoids per frame; docs/visual-hull.md, "Measured on
// the replay bench"). A hull must hold the body: the body's surface, sampled evenly on every
// ellipsoid where no other ellipsoid covers it and above the floor, counts as covered where a
// point is inside the hull or within the tolerance of its surface. The hull's volume is compared
// with the body's (the union of the ellipsoids, sampled on a grid), and the hull's reprojection
// IoU per view (what the host measured against the edges' silhouettes, --hull-iou) is gathered.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace syncap::compare {

struct HullCheck {
  long frames = 0;  // frames with a true body and a hull record
  long meshes = 0;  // of those, with a mesh file read and checked
  long failed = 0;  // hull records flagged FAILED
  long surface_points = 0;
  long covered_points = 0;
  double worst_miss_mm = 0;           // the farthest body point outside a hull
  std::vector<double> volume_ratios;  // hull / true body, per mesh
  std::vector<double> view_ious;      // every view of every hull record with IoUs
  double coverage() const;
};

// Throws InputError naming the file (and line) that cannot be read.
HullCheck check_hulls(const std::filesystem::path& truth_dir,
                      const std::filesystem::path& groups_file,
                      const std::filesystem::path& mesh_dir, double tolerance_mm);

// "hull: N frames, M meshes, coverage ..., volume ratio ..., reprojection IoU ...\n"
std::string format_hull_check(const HullCheck& check, double tolerance_mm);

}  // namespace syncap::compare
