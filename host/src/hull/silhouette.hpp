// A view's silhouette as polygons in pixel coordinates: outlines and holes, any nesting. Which
// contour is a hole follows from the nesting (the cone's caps count it), so contours carry no
// flag; `hole` is informative.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace syncap::hull {

struct Contour {
  std::vector<Eigen::Vector2d> points;  // pixels, (0, 0) the centre of the top-left pixel
  bool hole = false;
};

struct Silhouette {
  std::vector<Contour> contours;
  bool empty() const { return contours.empty(); }
  std::size_t vertex_count() const;
};

// Default contour simplification: cv::approxPolyDP's epsilon in pixels. 1 px keeps the
// reprojection within a pixel of the mask's outline with about a tenth of its vertices.
inline constexpr double kDefaultSimplifyPx = 1.0;

// The contours of the non-zero pixels of an 8-bit mask, opened with a 3x3 square first (parts
// thinner than 3 px would pinch the cone), by cv::findContours (RETR_CCOMP), each
// simplified with cv::approxPolyDP(epsilon = simplify_px; 0 keeps every corner of the pixel
// outline); contours of fewer than 3 points after it are dropped; then on_pixel_edges (below).
Silhouette silhouette_from_mask(const cv::Mat& mask, double simplify_px = kDefaultSimplifyPx);

// The contours moved half a pixel away from the foreground (outlines outwards, holes inwards,
// mitred at corners), from the boundary pixels' centres, where cv::findContours traces them (the
// edges' silhouettes and silhouette_from_mask), to the pixels' outer edges, where the object's
// outline is. Without it every view's cone is half a pixel thin and the hull misses the object
// by that much along its rims (3 mm at 4 m with a 630 px focal length).
Silhouette on_pixel_edges(Silhouette silhouette);

// Sets to 255 the pixels of an 8-bit mask whose centres lie inside the polygons (even-odd over
// all of them; a centre on a left edge is inside, on a right edge outside). cv::fillPoly also
// fills the pixels its edges' lines touch, half a pixel more all round, which hid that
// findContours' outlines run half a pixel inside the object.
void fill_pixel_centres(cv::Mat& mask, const std::vector<std::vector<Eigen::Vector2d>>& polygons);

// The mask of the silhouette's pixel centres (fill_pixel_centres), 255 inside: a silhouette on
// pixel edges (on_pixel_edges) gives back the mask it came from.
cv::Mat rasterize(const Silhouette& silhouette, cv::Size size);

// Intersection over union of the non-zero pixels of two masks of the same size (1 when both
// are empty).
double mask_iou(const cv::Mat& a, const cv::Mat& b);

}  // namespace syncap::hull
