#include "board/board_pose.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace syncap::board {
namespace {

std::vector<cv::Point3d> object_points(const BoardSpec& board, bool z_up,
                                       const std::vector<int>& point_ids) {
  std::vector<cv::Point3d> points = board_points(board);
  if (!point_ids.empty()) {
    std::vector<cv::Point3d> seen;
    for (const int id : point_ids) seen.push_back(points.at(static_cast<std::size_t>(id)));
    points = std::move(seen);
  }
  if (z_up) {
    for (cv::Point3d& p : points) p.y = -p.y;  // (x, -y, -z) on the plane z = 0
  }
  return points;
}

void solve(const sensor::OpenCvCamera& c, const std::vector<cv::Point3d>& object,
           const std::vector<cv::Point2d>& image, cv::Vec3d& rvec, cv::Vec3d& tvec) {
  cv::solvePnP(object, image, c.camera_matrix, c.distortion, rvec, tvec, false,
               cv::SOLVEPNP_ITERATIVE);
}

std::vector<double> residuals(const sensor::OpenCvCamera& posed,
                              const std::vector<cv::Point3d>& object,
                              const std::vector<cv::Point2d>& image) {
  std::vector<double> e;
  for (std::size_t i = 0; i < object.size(); ++i)
    e.push_back(cv::norm(sensor::project_opencv(posed, object[i]) - image[i]));
  return e;
}

// A ChArUco corner the pose misses by more than this and kRejectFactor times the median is
// dropped and the pose solved again: a marker found with a corner astray puts the chessboard
// corners beside it 2-3 px off, the rest are within 0.3 px.
constexpr double kRejectPx = 1.0;
constexpr double kRejectFactor = 4.0;

// The corners the pose keeps (all of a checkerboard's: it is found whole or not at all).
bool drop_outliers(const std::vector<double>& e, std::vector<cv::Point3d>& object,
                   std::vector<cv::Point2d>& image) {
  std::vector<double> sorted = e;
  std::ranges::sort(sorted);
  const double limit = std::max(kRejectPx, kRejectFactor * sorted[sorted.size() / 2]);
  std::vector<cv::Point3d> kept_object;
  std::vector<cv::Point2d> kept_image;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (e[i] <= limit) {
      kept_object.push_back(object[i]);
      kept_image.push_back(image[i]);
    }
  }
  if (kept_object.size() == object.size() || kept_object.size() < 6) return false;
  object = std::move(kept_object);
  image = std::move(kept_image);
  return true;
}

}  // namespace

BoardPose pose_on_board(const sensor::OpenCvCamera& intrinsics,
                        const std::vector<cv::Point2d>& corners, const BoardSpec& board, int id,
                        bool reversed, bool z_up, const std::vector<int>& point_ids) {
  std::vector<cv::Point2d> image = corners;
  if (reversed) std::ranges::reverse(image);
  std::vector<cv::Point3d> object = object_points(board, z_up, point_ids);
  if (object.size() != image.size())
    throw BoardError("pose_on_board: " + std::to_string(image.size()) + " corners for " +
                     std::to_string(object.size()) + " board points");
  sensor::OpenCvCamera posed = intrinsics;
  solve(intrinsics, object, image, posed.rvec, posed.tvec);
  std::vector<double> e = residuals(posed, object, image);
  BoardPose pose;
  pose.corners_seen = static_cast<int>(object.size());
  while (board.kind == BoardKind::kCharuco && drop_outliers(e, object, image)) {
    solve(intrinsics, object, image, posed.rvec, posed.tvec);
    e = residuals(posed, object, image);
  }
  pose.corners_used = static_cast<int>(object.size());
  pose.camera =
      sensor::camera_keeping_opencv_lens(posed, sensor::kOpenCvPixelMm, sensor::kOpenCvPixelMm, id);
  double sum_squares = 0.0;
  for (const double r : e) {
    sum_squares += r * r;
    pose.max_px = std::max(pose.max_px, r);
  }
  pose.rms_px = std::sqrt(sum_squares / (2.0 * static_cast<double>(e.size())));
  return pose;
}

bool cameras_below_board(const sensor::OpenCvCamera& intrinsics,
                         const std::vector<cv::Point2d>& corners, const BoardSpec& board,
                         const std::vector<int>& point_ids) {
  cv::Vec3d rvec, tvec;
  solve(intrinsics, object_points(board, false, point_ids), corners, rvec, tvec);
  cv::Matx33d r;
  cv::Rodrigues(rvec, r);
  return (-(r.t() * tvec))[2] < 0.0;
}

}  // namespace syncap::board
