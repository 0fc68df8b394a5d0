// The board calibration's parts on rendered boards of known truth: the spec, the corners of a
// board lying on the floor at a grazing angle (squares 3 px high), each camera's pose on it in the
// world frame with z up, and a symmetric board's half turn told from a person's masks.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "board/board_pose.hpp"
#include "board/board_spec.hpp"
#include "board/corner_detection.hpp"
#include "board/half_turn.hpp"
#include "board_scene.hpp"
#include "hull/reprojection.hpp"
#include "hull_scenes.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::board {
namespace {

// The board's corners where a camera sees them, in the world frame with z up (the board frame
// turned half about x, as board_pose.hpp).
std::vector<cv::Point2d> true_corners(const sensor::CameraModel& camera, const BoardSpec& b) {
  std::vector<cv::Point2d> corners;
  for (const cv::Point3d& p : board_points(b)) {
    const sensor::Projection q = camera.project({p.x, -p.y, 0.0});
    corners.emplace_back(q.pixel.x(), q.pixel.y());
  }
  return corners;
}

double worst_distance(const std::vector<cv::Point2d>& a, const std::vector<cv::Point2d>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, cv::norm(a[i] - b[i]));
  return worst;
}

TEST(BoardSpec, ParsesCornersAndSquareAndKnowsItsSymmetry) {
  const auto b = parse_board_spec("8x6x115");
  ASSERT_TRUE(b);
  EXPECT_EQ(b->inner_corners, cv::Size(8, 6));
  EXPECT_EQ(b->square_mm, 115.0);
  EXPECT_TRUE(has_half_turn_symmetry(*b));
  EXPECT_FALSE(has_half_turn_symmetry(*parse_board_spec("7x6x30")));
  for (const char* bad : {"8x6", "8x6x", "2x6x10", "8x6x-1", "8x6x115mm", "axbxc"})
    EXPECT_FALSE(parse_board_spec(bad)) << bad;
  const std::vector<cv::Point3d> points = board_points(*b);
  ASSERT_EQ(points.size(), 48u);
  EXPECT_EQ(points[1], cv::Point3d(115, 0, 0));  // along the COLS corners first
  EXPECT_EQ(points[8], cv::Point3d(0, 115, 0));
}

TEST(CornerDetection, FindsABoardOnTheFloorAtAGrazingAngle) {
  const BoardSpec b{{7, 6}, 115.0};
  // 5.2 m away, 1.3 m up: 14 degrees above the board, its squares 11 px wide and 3 px high.
  const sensor::CameraModel camera = test::studio_camera(0, {400, -5000, 1300}, {400, -290, 0});
  const cv::Mat image = test::render_board(camera, b);
  int stretch = 1;
  const auto found = find_board_corners(image, b, &stretch);
  ASSERT_TRUE(found);
  EXPECT_GT(stretch, 1);  // the plain image alone did not do
  std::vector<cv::Point2d> reversed = *found;
  std::ranges::reverse(reversed);
  const std::vector<cv::Point2d> truth = true_corners(camera, b);
  const double error = std::min(worst_distance(*found, truth), worst_distance(reversed, truth));
  EXPECT_LT(error, 0.25);  // measured 0.19 px at worst, on squares 3 px high
  RecordProperty("worst_corner_error_px", std::to_string(error));
  RecordProperty("stretch", stretch);
}

TEST(CornerDetection, ABlankImageHasNoBoard) {
  EXPECT_FALSE(find_board_corners(cv::Mat(486, 644, CV_8UC1, cv::Scalar(110)), {{8, 6}, 115}));
}

TEST(BoardPose, RecoversTheCameraInTheBoardsFrameWithZUp) {
  const BoardSpec b{{7, 6}, 115.0};
  const sensor::CameraModel truth = test::studio_camera(3, {-2400, -2800, 1400}, {350, -290, 0});
  const std::vector<cv::Point2d> corners = true_corners(truth, b);
  sensor::OpenCvCamera intrinsics = sensor::opencv_from_camera(truth);
  intrinsics.rvec = intrinsics.tvec = cv::Vec3d::all(0);
  EXPECT_TRUE(cameras_below_board(intrinsics, corners, b));  // the board's own z points down
  const BoardPose pose = pose_on_board(intrinsics, corners, b, 3, false, true);
  EXPECT_EQ(pose.camera.id, 3);
  EXPECT_LT(pose.rms_px, 1e-6);
  EXPECT_LT((pose.camera.projection_centre() - truth.projection_centre()).norm(), 1e-3);
  // The other order: the same camera turned half about the board's centre.
  const BoardPose turned = pose_on_board(intrinsics, corners, b, 3, true, true);
  const Eigen::Vector3d centre(3 * 115.0, -2.5 * 115.0, 0.0);
  const Eigen::Vector3d a = truth.projection_centre() - centre,
                        c = turned.camera.projection_centre() - centre;
  EXPECT_NEAR(c.x(), -a.x(), 1e-3);
  EXPECT_NEAR(c.y(), -a.y(), 1e-3);
  EXPECT_NEAR(c.z(), a.z(), 1e-3);
}

// Four cameras round a symmetric board, a person-sized ellipsoid standing 0.8 m off its centre:
// each camera's two poses (its corners in either order, shuffled as a detector would give them),
// and the masks of the person. The turns chosen are the true ones.
TEST(HalfTurn, ThePersonsMasksTellTheCamerasTurns) {
  const BoardSpec b{{8, 6}, 115.0};
  const Eigen::Vector3d board_centre(3.5 * 115.0, -2.5 * 115.0, 0.0);
  const hull::Mesh person =
      hull::test::ellipsoid_mesh({250, 180, 850}, board_centre + Eigen::Vector3d(800, 300, 850));
  std::mt19937 rng(7);
  std::vector<std::array<BoardPose, 2>> poses;
  std::vector<cv::Mat> masks;
  std::vector<bool> truly_reversed;
  for (int i = 0; i < 4; ++i) {
    const double azimuth = 0.4 + 1.57 * i;
    const sensor::CameraModel truth = test::studio_camera(
        i, board_centre + Eigen::Vector3d(4500 * std::cos(azimuth), 4500 * std::sin(azimuth), 1400),
        board_centre + Eigen::Vector3d(0, 0, 600));
    sensor::OpenCvCamera intrinsics = sensor::opencv_from_camera(truth);
    const std::vector<cv::Point2d> corners = true_corners(truth, b);
    const bool reversed = i > 0 && (rng() % 2 == 1);
    const BoardPose right = pose_on_board(intrinsics, corners, b, i, false, true);
    const BoardPose wrong = pose_on_board(intrinsics, corners, b, i, true, true);
    poses.push_back(reversed ? std::array{wrong, right} : std::array{right, wrong});
    truly_reversed.push_back(reversed);
    masks.push_back(hull::render_mask(person, truth));
  }
  const HalfTurn turn = resolve_half_turn(poses, masks);
  EXPECT_EQ(turn.reversed, truly_reversed);
  EXPECT_GT(turn.mean_iou, 0.95);
  EXPECT_LT(turn.runner_up_iou, turn.mean_iou - 0.1);
  ASSERT_EQ(turn.camera_margins.size(), 3u);
  EXPECT_GT(turn.margin, 0.3);
  EXPECT_EQ(turn.hulls_built, 8);
}

}  // namespace
}  // namespace syncap::board
