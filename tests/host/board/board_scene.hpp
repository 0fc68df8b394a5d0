// A checkerboard or a ChArUco board lying on the floor (z = 0) rendered through a camera: each
// pixel's ray meets the floor, 3 x 3 rays a pixel (anti-aliased edges, so that corners are found to
// hundredths of a pixel). White squares 230, black 20, a white margin of one square around the
// squares, a green floor (grey 110) elsewhere.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/core.hpp>

#include "board/board_spec.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/test_cameras.hpp"

namespace syncap::board::test {

// The grey value the floor has at (x, y) with the board's corner (0, 0) at the origin, x along
// its COLS corners, y along its ROWS corners (in the board frame of board_spec.hpp).
inline double floor_grey(const BoardSpec& b, double x, double y) {
  const double s = b.square_mm;
  const double i = x / s + 1.0, j = y / s + 1.0;  // in squares from the squares' corner
  const int cols = b.inner_corners.width + 1, rows = b.inner_corners.height + 1;
  if (i < -1 || j < -1 || i > cols + 1 || j > rows + 1) return 110.0;  // the floor
  if (i < 0 || j < 0 || i >= cols || j >= rows) return 230.0;          // the margin
  return (static_cast<int>(std::floor(i)) + static_cast<int>(std::floor(j))) % 2 == 0 ? 20.0
                                                                                      : 230.0;
}

// The floor of `grey(x, y)` (in the board frame) seen through `camera`.
template <class Grey>
cv::Mat render_floor(const sensor::CameraModel& camera, const Grey& grey) {
  cv::Mat image(camera.sensor.height_px, camera.sensor.width_px, CV_8UC1);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      double sum = 0.0;
      for (int sv = 0; sv < 3; ++sv) {
        for (int su = 0; su < 3; ++su) {
          const sensor::Ray ray = camera.back_project({u + (su - 1) / 3.0, v + (sv - 1) / 3.0});
          if (!(ray.direction.z() < 0.0)) {
            sum += 200.0;  // the wall
            continue;
          }
          const Eigen::Vector3d p = ray.origin - ray.origin.z() / ray.direction.z() * ray.direction;
          sum += grey(p.x(), -p.y());  // z up: the board frame turned half about x
        }
      }
      image.at<unsigned char>(v, u) = static_cast<unsigned char>(std::lround(sum / 9.0));
    }
  }
  return image;
}

inline cv::Mat render_board(const sensor::CameraModel& camera, const BoardSpec& b) {
  return render_floor(camera, [&b](double x, double y) { return floor_grey(b, x, y); });
}

// A ChArUco board as OpenCV draws it (cv::aruco::CharucoBoard::draw, 64 px a square), black 20,
// white 230, with a white margin of one square, on the green floor.
inline cv::Mat render_charuco_board(const sensor::CameraModel& camera, const BoardSpec& b) {
  constexpr int kPxPerSquare = 64;
  const int squares_x = b.inner_corners.width + 1, squares_y = b.inner_corners.height + 1;
  cv::Mat pattern;
  cv::aruco::CharucoBoard::create(squares_x, squares_y, static_cast<float>(b.square_mm),
                                  static_cast<float>(b.marker_mm),
                                  cv::aruco::getPredefinedDictionary(b.dictionary))
      ->draw({squares_x * kPxPerSquare, squares_y * kPxPerSquare}, pattern);
  const double px_per_mm = kPxPerSquare / b.square_mm;
  return render_floor(camera, [&](double x, double y) {
    // The drawing's corner is one square before the first inner corner.
    const double u = (x + b.square_mm) * px_per_mm, v = (y + b.square_mm) * px_per_mm;
    const double margin = kPxPerSquare;
    if (u < -margin || v < -margin || u > pattern.cols + margin || v > pattern.rows + margin)
      return 110.0;                                                              // the floor
    if (u < 0 || v < 0 || u >= pattern.cols || v >= pattern.rows) return 230.0;  // the margin
    const unsigned char drawn = pattern.at<unsigned char>(static_cast<int>(v), static_cast<int>(u));
    return drawn > 127 ? 230.0 : 20.0;
  });
}

// A 644 x 486 camera (f 490 px, no distortion) at `centre` looking at `target`, image y up.
inline sensor::CameraModel studio_camera(int id, const Eigen::Vector3d& centre,
                                         const Eigen::Vector3d& target) {
  sensor::CameraModel c;
  c.id = id;
  c.sensor = {644, 486, 0.01, 0.01};
  c.interior.c = 4.9;
  c.exterior = sensor::test::looking_at(centre, target);
  return c;
}

}  // namespace syncap::board::test
