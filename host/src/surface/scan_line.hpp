// The geometrically constrained cross-correlation (GC3, thesis lines 4860-4935 after Zhang 2005):
// a window around a reference pixel, the 3D scan line of that pixel's ray, and the window warped
// into every search image through the local tangent plane at each depth along the line; the sum of
// the normalised cross-correlations (SNCC, eq 5.27) over the search images; its peaks are the
// candidates.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sensor/camera_model.hpp"
#include "surface/match_image.hpp"

namespace syncap::surface {

// One camera with its image and, optionally, the object's mask: a reference window then uses only
// its pixels on the object. Without it, a window on a limb takes in the limb's outline, whose
// edge each view sees on a different contour generator: matched, it puts the point behind the
// surface (on the replay bench's limbs by 5-15 mm for 5x5 to 13x13 windows).
struct MatchingView {
  sensor::CameraModel camera;
  MatchImage image;
  cv::Mat mask;  // 8-bit, the image's size, non-zero on the object; empty: every pixel
  // Each pixel's weight in least squares (CV_32F, empty: 1): its distance from the outline over
  // kOutlineRampPx, at most 1. Near the outline the surface turns away from the camera and the
  // window's model (a smooth depth over the window) holds worst: cutting those pixels (the mask
  // shrunk by 3 px) made the sigmas honest on the bench but lost thin limbs.
  cv::Mat weight;
};

inline constexpr double kOutlineRampPx = 4.0;

// The view with its mask shrunk by `margin_px` (a silhouette's edge pixel mixes object and
// background). Throws std::invalid_argument for a mask of another size or type.
MatchingView make_matching_view(const sensor::CameraModel& camera, const cv::Mat& image,
                                const cv::Mat& mask = {}, int margin_px = 1);

// The reference window and its 3D scan line: X(t) = centre + t * direction, t the distance
// from the projection centre [mm]. The window's pixel k (offset from the reference pixel) sees
// the tangent plane through X(t) at centre + t * plane_rays[k]: the plane's normal fixes how the
// window is warped into the other images ("correlation window warping", mono-restitution).
struct ScanWindow {
  Eigen::Vector2i pixel = Eigen::Vector2i::Zero();  // the reference pixel
  int half = 3;                                     // the window is (2 half + 1)^2 pixels
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  // d X / d u and d X / d v on the plane at t = 1 (scale by t): the window's pixel axes.
  Eigen::Vector3d along_u = Eigen::Vector3d::Zero(), along_v = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> offsets;  // window pixels on the object, row by row
  std::vector<float> grey;               // the reference's grey values there
  std::vector<float> weight;             // and their weights (MatchingView::weight)
  double grey_sd = 0.0;                  // their standard deviation [DN]
  double object_share = 1.0;             // the share of the square window on the object

  Eigen::Vector3d point(double t) const { return centre + t * direction; }
};

// The window around `pixel` of `reference` with the tangent plane's `normal`. Returns nothing
// when the window leaves the image or the plane is seen within ~5 degrees of edge-on.
std::optional<ScanWindow> make_scan_window(const MatchingView& reference,
                                           const Eigen::Vector2i& pixel, int half,
                                           const Eigen::Vector3d& normal);

// Where the window lands in a search image at depth t: its centre, the affine map of the
// window's offsets (pixel = centre + affine * offset) and how the centre moves with t.
struct WarpedWindow {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  Eigen::Matrix2d affine = Eigen::Matrix2d::Identity();
  Eigen::Vector2d per_mm = Eigen::Vector2d::Zero();  // d centre / d t [px/mm]
};
std::optional<WarpedWindow> warp_window(const ScanWindow& window, const MatchingView& search,
                                        double t);

// Whether a search image's pixel (nearest) is on the object: its mask says so, or it has none.
bool on_object(const MatchingView& view, const Eigen::Vector2d& pixel);
// Its weight (nearest pixel): 1 without a weight image.
float weight_at(const MatchingView& view, const Eigen::Vector2d& pixel);

// A search window needs this share of its samples on the object (its mask), as the reference
// window; the samples off it are left out (the search view sees the object's outline there).
inline constexpr double kMinShareOnObject = 0.6;

// Eq 5.25 over the window's samples on the search image's object: the NCC of the reference
// window with the search image's window at `warp`; nothing when the window leaves the image, is
// flat, or has too few samples on the object.
std::optional<double> window_ncc(const ScanWindow& window, const MatchingView& view,
                                 const WarpedWindow& warp);

struct SnccPeak {
  double t = 0.0;     // sub-step depth: the parabola through the peak and its neighbours
  double sncc = 0.0;  // at the sampled peak
};

// SNCC(t) sampled along the scan line, and its peaks, best first.
struct ScanProfile {
  std::vector<double> t;
  std::vector<double> sncc;  // NaN where a search window left its image
  std::vector<SnccPeak> peaks;
};

// Samples SNCC (eq 5.27: the mean of the search images' NCC) on [t_from, t_to] in steps that
// move the window by at most `step_px` in any search image, and finds its local maxima of at
// least `min_peak`.
ScanProfile scan_sncc(const ScanWindow& window, const std::vector<const MatchingView*>& search,
                      double t_from, double t_to, double step_px, double min_peak);

}  // namespace syncap::surface
