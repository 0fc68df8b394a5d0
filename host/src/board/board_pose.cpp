#include "board/board_pose.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>

namespace syncap::board {
namespace {

std::vector<cv::Point3d> object_points(const BoardSpec& board, bool z_up) {
  std::vector<cv::Point3d> points = board_points(board);
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

}  // namespace

BoardPose pose_on_board(const sensor::OpenCvCamera& intrinsics,
                        const std::vector<cv::Point2d>& corners, const BoardSpec& board, int id,
                        bool reversed, bool z_up) {
  std::vector<cv::Point2d> image = corners;
  if (reversed) std::ranges::reverse(image);
  const std::vector<cv::Point3d> object = object_points(board, z_up);
  sensor::OpenCvCamera posed = intrinsics;
  solve(intrinsics, object, image, posed.rvec, posed.tvec);
  BoardPose pose;
  pose.camera =
      sensor::camera_keeping_opencv_lens(posed, sensor::kOpenCvPixelMm, sensor::kOpenCvPixelMm, id);
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < object.size(); ++i) {
    const double e = cv::norm(sensor::project_opencv(posed, object[i]) - image[i]);
    sum_squares += e * e;
    pose.max_px = std::max(pose.max_px, e);
  }
  pose.rms_px = std::sqrt(sum_squares / (2.0 * static_cast<double>(object.size())));
  return pose;
}

bool cameras_below_board(const sensor::OpenCvCamera& intrinsics,
                         const std::vector<cv::Point2d>& corners, const BoardSpec& board) {
  cv::Vec3d rvec, tvec;
  solve(intrinsics, board_points(board), corners, rvec, tvec);
  cv::Matx33d r;
  cv::Rodrigues(rvec, r);
  return (-(r.t() * tvec))[2] < 0.0;
}

}  // namespace syncap::board
