// Partly hidden spots. A marker the body hides in part still makes a round enough spot to pass
// the edge's roundness filter, but a smaller one, and its centroid is off by up to a pixel: on the
// mocap replay 60 % of the markers had such a ray, and their 3D error was twice that of markers
// all of whose spots were whole (docs/design/reconstruction.md). The spot's size tells them apart
// once the point is known: sqrt(area) * distance / (pixels per radian at the spot, through the lens
// model: ViewRay::spot_pixels_per_rad) is the marker's apparent width in mm, the same in every
// camera that sees it whole, smaller in one that sees part of it. So
// a point with enough whole spots is triangulated again from those alone.
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "geometry/triangulation.hpp"

namespace syncap::reconstruction {

struct PartialSpotOptions {
  // A spot is partial when its apparent width is below this fraction of the point's second
  // widest spot's (see whole_spots). A whole spot's width varies by some 5-10 % between cameras
  // (its threshold area is quantised to pixels, its distance differs); a quarter of the disc hidden
  // takes 13 % off.
  double min_width_ratio = 0.85;
  // Partial spots are left out only when at least this many whole ones remain: fewer rays fix
  // the point less well, and two from near cameras fix it badly along their baseline.
  int min_whole_rays = 3;
  // The spots kept are weighted by what their size says: a spot whose area is a share h short of
  // a whole spot's (the typical width, merged_spots.hpp) has its centroid moved by about
  // k * h * its radius (a disc cut by a straight edge: k ~ 0.9), added to the blob noise in its
  // ray's sigma. 0: every kept spot weighs the same.
  double shift_per_hidden_share = 0.9;
  bool enabled() const { return min_width_ratio > 0; }
};

// The apparent width [mm] of a spot of `area_px` pixels on `ray` for a point at `point`.
double apparent_width_mm(const geometry::ViewRay& ray, double area_px,
                         const Eigen::Vector3d& point);

// Which of a point's rays saw its marker whole (true) by the rule above; all true when fewer than
// options.min_whole_rays would remain, or the point has fewer rays than that.
std::vector<bool> whole_spots(std::span<const geometry::ViewRay> rays,
                              std::span<const double> areas_px, const Eigen::Vector3d& point,
                              const PartialSpotOptions& options);

}  // namespace syncap::reconstruction
