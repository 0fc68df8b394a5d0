// Surface measurement of the person (thesis 5.2.4, lines 4830-5053): seeds on the visual hull,
// GC3 along each seed's 3D scan line in the images that see it (facet-ID visibility), the
// candidate rules (a clear peak, back-matching), then multi-image least-squares matching
// constrained to one 3D point, which gives the point and its standard deviation. Every seed that
// gives no point is counted by its reason.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "surface/facet_id_image.hpp"
#include "surface/multi_image_lsm.hpp"
#include "surface/scan_line.hpp"

namespace syncap::surface {

struct SurfaceMatchingOptions {
  double seed_spacing_px = 4.0;  // seeds on a grid of this spacing in each reference image
  int half_window = 5;           // the window is (2 half + 1)^2 pixels
  // A view is used for a seed when the hull's normal there is within this angle of the view's
  // direction, and the facet-ID image says the facet is seen.
  double max_view_angle_deg = 70.0;
  int min_search_views = 2;
  // Lengths in object units (mm for our cameras); 0 takes each from the hull's size, the
  // diagonal of its bounding box (the share in brackets; a person of 2 m gets 5, 15, 120 mm):
  double visibility_tolerance = 0.0;  // FacetIdImage::sees (0.25 %)
  // the scan line runs from this far in front of the hull's surface (0.75 %) to this far behind
  // it (6 %): the surface lies inside the hull.
  double search_front = 0.0;
  double search_depth = 0.0;
  double step_px = 0.5;           // the sweep's step in the fastest search image
  double min_template_sd = 4.0;   // [DN]: a flatter reference window has no texture to match
  double min_object_share = 0.6;  // of the reference window on the object's mask (else: edge)
  double min_sncc = 0.7;          // the best peak's SNCC
  double max_second_peak = 0.5;   // the second peak over the first (thesis: a half or a third)
  double back_matching_px = 1.5;  // thesis: inverse matching within 1.5 pixels
  bool least_squares = true;      // false: the GC3 peak is the result (the NCC sweep baseline)
  LsmOptions lsm;
  // A point whose sigma0 exceeds this times the median of all points' is a blunder (the
  // residuals are not the images' noise: an occlusion edge, a specularity, a wrong peak).
  double blunder_sigma0_ratio = 1.4;
};

enum class Rejection {
  kOccluded,      // fewer than min_search_views views see the seed's facet
  kNoTexture,     // the reference window is flat, or mostly off the object (its mask)
  kLowNcc,        // no SNCC peak of min_sncc
  kAmbiguous,     // a second peak of more than max_second_peak of the first
  kBackMatching,  // matching back from the best search image lands elsewhere
  kNotConverged,  // least squares did not converge (or left its start)
  kBlunder,       // the statistical test on sigma0
  kCount
};
const char* rejection_name(Rejection r);

struct MatchedPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d ray_origin = Eigen::Vector3d::Zero();  // the reference's projection centre
  Eigen::Vector3d ray_direction = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // the hull's, at the seed
  double sigma_ray_mm = 0.0;                          // along the ray
  double sigma_normal_mm = 0.0;  // along the normal: sigma_ray * |direction . normal|
  double sncc = 0.0;             // the GC3 peak's
  double sweep_t = 0.0;          // the GC3 peak's depth along the ray (the NCC sweep result)
  double sigma0 = 0.0;           // LSM's residual standard deviation [DN]
  int iterations = 0;
  int reference = 0;                                // view index
  Eigen::Vector2i pixel = Eigen::Vector2i::Zero();  // in the reference image
  std::vector<int> search;                          // view indices
};

struct SurfaceMatchingResult {
  std::vector<MatchedPoint> points;
  // The lengths used (the options', or those taken from the hull's size).
  double visibility_tolerance = 0.0, search_front = 0.0, search_depth = 0.0;
  std::size_t seeds = 0;
  std::array<std::size_t, static_cast<std::size_t>(Rejection::kCount)> rejected{};
  double sweep_seconds = 0.0;  // GC3 with the candidate rules (one thread)
  double lsm_seconds = 0.0;
  double visibility_seconds = 0.0;
  std::size_t rejected_by(Rejection r) const { return rejected[static_cast<std::size_t>(r)]; }
};

// Matches the surface seen by `views` (each with its image) around `hull` (outward-oriented
// triangles). Deterministic; one thread.
SurfaceMatchingResult match_surface(const std::vector<MatchingView>& views,
                                    const std::vector<Facet>& hull,
                                    const SurfaceMatchingOptions& options = {});

}  // namespace syncap::surface
