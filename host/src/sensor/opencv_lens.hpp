// OpenCV's lens distortion (k1 k2 p1 p2 k3 of cv::projectPoints) kept exactly, as a map between
// a camera's ideal pixels and its measured ones: measured = K distort(K^-1 ideal). A camera read
// from an OpenCV file is its ideal camera in the thesis' model (exact, opencv_camera.hpp) with
// this lens on top, so every program projects and back-projects as OpenCV does, with no refit.
// The thesis' own correction (eq 4.10) goes the other way (a polynomial in the measured
// coordinates); no finite set of its coefficients matches OpenCV's in the corners, which is why
// the lens is kept as OpenCV defines it (docs/reference/camera-model.md, "OpenCV lenses").
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

namespace syncap::sensor {

// Undistorting (the inverse of distort) stops when Newton's step in normalised coordinates is
// below this (1e-12 is about 1e-9 pixel)...
inline constexpr double kLensTolerance = 1e-12;
// ...and gives up after this many steps.
inline constexpr int kLensMaxIterations = 50;

struct OpenCvLens {
  // K the distortion is defined through: fx, skew, cx; 0, fy, cy; 0, 0, 1 [px], pixel (0, 0) at
  // the centre of the top-left pixel. For a camera read from an OpenCV file this is its K, which
  // is also the ideal camera's.
  Eigen::Matrix3d camera_matrix = Eigen::Matrix3d::Identity();
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3, OpenCV's order

  // Whether every coefficient is 0 (the lens changes nothing).
  bool is_identity() const;

  // The measured pixel of an ideal pixel: OpenCV's distortion of the normalised coordinates.
  Eigen::Vector2d distort(const Eigen::Vector2d& ideal_pixel) const;

  // d(measured pixel) / d(ideal pixel) at an ideal pixel.
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& ideal_pixel) const;

  // The ideal pixel of a measured pixel: distort inverted by Newton's method from the measured
  // pixel, to kLensTolerance. None when it does not converge or the solution lies beyond a fold
  // of the distortion (is_one_to_one_up_to), where OpenCV's model has a second, unphysical
  // branch.
  std::optional<Eigen::Vector2d> undistort(const Eigen::Vector2d& pixel) const;

  // undistort, or for a pixel beyond the fold (no ideal pixel distorts to it: the corners of a
  // lens OpenCV fitted with no points there) the ideal pixel at the fold in the pixel's
  // direction, the outermost ray the lens reaches; the pixel itself for a lens without a fold
  // that still does not converge.
  Eigen::Vector2d undistort_or_fold(const Eigen::Vector2d& pixel) const;

  // Whether the distortion is one-to-one on the way from the principal point to an ideal pixel:
  // a positive Jacobian determinant at every one of 16 samples. A point beyond a fold, far
  // outside the image, would otherwise be drawn back into it.
  bool is_one_to_one_up_to(const Eigen::Vector2d& ideal_pixel) const;
};

}  // namespace syncap::sensor
