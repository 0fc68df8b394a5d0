// The host's visual hulls (syncap-host --hull --hull-meshes DIR) against the simulator's true
// body (truth/body.jsonl: the person's ellipsoids per frame; docs/design/visual-hull.md, "Measured
// on the replay bench"). A hull must hold the body: the body's surface, sampled evenly on every
// ellipsoid where no other ellipsoid covers it and above the floor, counts as covered where a
// point is inside the hull or within the tolerance of its surface. The hull's volume is compared
// with the body's (the union of the ellipsoids, sampled on a grid), and the hull's reprojection
// IoU per view (what the host measured against the edges' silhouettes, --hull-iou) is gathered.
// The same frames' hulls built from the true masks (polyhedral, the voxel hull where it fails,
// as the host builds them) give the reference: what the method holds when the silhouettes are
// right, so that a shortfall of the live hull is told apart from one of the segmentation.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calibration_check.hpp"

namespace syncap::compare {

struct HullCheck {
  long frames = 0;  // frames with a true body and a hull record
  long meshes = 0;  // of those, with a mesh file read and checked
  long failed = 0;  // hull records flagged FAILED
  long surface_points = 0;
  long covered_points = 0;
  double worst_miss_mm = 0;                       // the farthest body point outside a hull
  std::map<std::string, long> missed_by_segment;  // points beyond the tolerance, by segment
  std::vector<double> volume_ratios;              // hull / true body, per mesh
  std::vector<double> view_ious;                  // every view of every hull record with IoUs
  double coverage() const;
};

struct HullChecks {
  HullCheck live;       // the host's hulls (the edges' silhouettes)
  HullCheck reference;  // the same frames' hulls from the true masks
};

// `to_truth`: for hulls measured through a calibration (syncap markers --hull --calibration),
// the motion of that calibration's frame onto the truth's (fit_to_truth), applied to every
// mesh before it is scored; the reference hulls use the true cameras. Throws InputError naming
// the file (and line) that cannot be read.
HullChecks check_hulls(const std::filesystem::path& truth_dir,
                       const std::filesystem::path& groups_file,
                       const std::filesystem::path& mesh_dir, double tolerance_mm,
                       const std::optional<Similarity>& to_truth = std::nullopt);

// "hull: N frames, M meshes, coverage ..., volume ratio ..., reprojection IoU ...\n" and the
// reference's line.
std::string format_hull_checks(const HullChecks& checks, double tolerance_mm);

}  // namespace syncap::compare
