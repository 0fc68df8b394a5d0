// The markers of a frame group: the blobs of the calibrated cameras matched across cameras and
// triangulated with their precision (matching::MarkerMatcher). Blobs of cameras the calibration
// does not know are left out, and counted. So are blobs the edge flagged NOT_ROUND (unless kept):
// a marker partly hidden by the body, or two markers run together, make a spot whose centroid is
// off by up to a pixel; on the mocap replay (markers-8cam-body) leaving them out took the ghosts
// from 4.7 % to 1.8 % and the found markers from 97.3 % to 98.8 % (docs/design/reconstruction.md).
// A point with spots the body hides in part (smaller, with their centroids off; see
// partial_spots.hpp) is triangulated again from its whole spots when enough remain. A spot of
// two markers run together (wider than a whole spot; merged_spots.hpp) is never one marker's
// view: left out of its point, and a point without two other spots is no marker.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <vector>

#include "matching/marker_matcher.hpp"
#include "pipeline/frame_work.hpp"
#include "reconstruction/merged_spots.hpp"
#include "reconstruction/partial_spots.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::reconstruction {

struct MarkerStageStats {
  long frames = 0;
  long markers = 0;
  long two_camera_markers = 0;
  long blobs = 0;
  long blobs_of_unknown_cameras = 0;  // cameras outside the calibration
  long blobs_not_round = 0;           // flagged NOT_ROUND by the edge: left out
  long blobs_used = 0;                // in a marker
  long partial_spots_left_out = 0;    // matched, but left out of the point's position
  long merged_spots_left_out = 0;     // wider than one marker's: left out of the point
  long merged_points_dropped = 0;     // points without two spots besides merged ones
};

struct MarkerStageOptions {
  bool keep_not_round = false;  // also match blobs the edge flagged NOT_ROUND
  PartialSpotOptions partial_spots;
  MergedSpotOptions merged_spots;
};

class MarkerStage : public pipeline::Stage {
 public:
  MarkerStage(std::vector<sensor::CameraModel> cameras, matching::MatchOptions options,
              MarkerStageOptions stage_options = {});
  const char* name() const override { return "markers"; }
  void process(pipeline::FrameWork& work) override;
  const MarkerStageStats& stats() const { return stats_; }

 private:
  // A matched point's rays and its spots' apparent widths.
  struct PointSpots {
    std::vector<geometry::ViewRay> rays;
    std::vector<double> areas_px, widths_mm;
  };
  PointSpots spots_of(const matching::MatchedPoint& p,
                      const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                      const std::vector<std::vector<double>>& areas) const;
  // The widths of this frame's spots of points seen by three or more cameras, into the typical
  // whole spot's width (when merged spots or the spots' weights are on).
  void learn_spot_width(const std::vector<PointSpots>& points);
  // Each spot's image sigma: the blobs' own, and the centroid shift a spot narrower than a whole
  // one suggests (partial_spots.hpp); empty when no typical width is known or it is off.
  std::vector<double> spot_sigmas(std::span<const geometry::ViewRay> rays,
                                  std::span<const double> areas_px,
                                  const Eigen::Vector3d& point) const;
  // The marker of matched point `p`, its position from its whole spots; nothing when merged
  // spots leave it fewer than two.
  std::optional<pipeline::Marker3d> marker_of(const matching::MatchedPoint& p,
                                              const PointSpots& spots);

  matching::MarkerMatcher matcher_;
  double sigma_px_;
  MarkerStageOptions options_;
  TypicalSpotWidth typical_width_;
  std::map<int, std::size_t> index_of_camera_;  // camera id -> the matcher's index
  MarkerStageStats stats_;
};

}  // namespace syncap::reconstruction
