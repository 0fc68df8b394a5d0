#include "board/charuco_detection.hpp"

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "board/corner_detection.hpp"

namespace syncap::board {
namespace {

cv::Ptr<cv::aruco::CharucoBoard> charuco_board(const BoardSpec& board) {
  return cv::aruco::CharucoBoard::create(
      board.inner_corners.width + 1, board.inner_corners.height + 1,
      static_cast<float>(board.square_mm), static_cast<float>(board.marker_mm),
      cv::aruco::getPredefinedDictionary(board.dictionary));
}

// The markers of one stretch of the image, their corners in the image's own pixels.
struct Markers {
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
};

Markers detect_markers(const cv::Mat& grey, int stretch,
                       const cv::Ptr<cv::aruco::CharucoBoard>& board) {
  cv::Mat image = grey;
  if (stretch > 1) cv::resize(grey, image, {}, 1.0, stretch, cv::INTER_CUBIC);
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  Markers m;
  cv::aruco::detectMarkers(image, board->dictionary, m.corners, m.ids, parameters);
  // cv::resize maps pixel centres: v_stretched + 0.5 = stretch (v + 0.5).
  for (auto& marker : m.corners) {
    for (cv::Point2f& p : marker) p.y = (p.y + 0.5f) / static_cast<float>(stretch) - 0.5f;
  }
  return m;
}

// Pixels without the lens (the pinhole's pixels), and back.
std::vector<cv::Point2f> undistorted(const std::vector<cv::Point2f>& pixels,
                                     const sensor::OpenCvCamera* lens) {
  if (lens == nullptr || pixels.empty()) return pixels;
  std::vector<cv::Point2f> out;
  cv::undistortPoints(pixels, out, lens->camera_matrix, lens->distortion, cv::noArray(),
                      lens->camera_matrix);
  return out;
}

std::vector<cv::Point2f> distorted(const std::vector<cv::Point2f>& pinhole,
                                   const sensor::OpenCvCamera* lens) {
  if (lens == nullptr || pinhole.empty()) return pinhole;
  const cv::Matx33d k_inv = lens->camera_matrix.inv();
  std::vector<cv::Point3f> rays;
  for (const cv::Point2f& p : pinhole) {
    const cv::Vec3d r = k_inv * cv::Vec3d(p.x, p.y, 1.0);
    rays.emplace_back(static_cast<float>(r[0] / r[2]), static_cast<float>(r[1] / r[2]), 1.0f);
  }
  std::vector<cv::Point2f> out;
  cv::projectPoints(rays, cv::Vec3d::all(0), cv::Vec3d::all(0), lens->camera_matrix,
                    lens->distortion, out);
  return out;
}

// Each corner refined on the image (cornerSubPix: the saddle of the two black squares that meet
// there), its window no wider than the gap between the square's edge and its marker, whose own
// edges would pull it. The marker corners the homography stands on are 0.4-0.5 px off in both
// coordinates on rendered boards (OpenCV 4.6's contour corners), and so are its predictions; the
// saddle is not. A corner whose refinement went astray (1-2 px, on squares of 10 px) is left to
// the pose's outlier test (board_pose.cpp).
void refine(const cv::Mat& grey, const BoardSpec& board, std::vector<cv::Point2f>& corners) {
  const double gap = 0.5 * (board.square_mm - board.marker_mm) / board.square_mm;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    double nearest = 1e9;
    for (std::size_t j = 0; j < corners.size(); ++j) {
      if (j != i) nearest = std::min(nearest, cv::norm(corners[i] - corners[j]));
    }
    const int half = std::clamp(static_cast<int>(std::lround(nearest * gap)), 2, 5);
    std::vector<cv::Point2f> one{corners[i]};
    cv::cornerSubPix(grey, one, {half, half}, {-1, -1},
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
    corners[i] = one[0];
  }
}

// The chessboard corners where the plane of all found marker corners puts them (a least-squares
// homography), then refined. OpenCV's own interpolation takes the two markers beside each corner
// and refines with a window that on squares of 10-25 px reaches the markers' edges: 0.4-4 px
// off on rendered boards.
BoardCorners corners_from_markers(const Markers& m, const BoardSpec& board_spec,
                                  const cv::Ptr<cv::aruco::CharucoBoard>& board,
                                  const cv::Mat& grey, const sensor::OpenCvCamera* lens) {
  BoardCorners found;
  if (m.ids.size() < 2) return found;
  // Which corners: those OpenCV's interpolation accepts (beside found markers, not extrapolated).
  std::vector<cv::Point2f> interpolated;
  std::vector<int> ids;
  cv::aruco::interpolateCornersCharuco(m.corners, m.ids, grey, board, interpolated, ids);
  if (static_cast<int>(ids.size()) < kMinCharucoCorners ||
      cv::aruco::testCharucoCornersCollinear(board, ids))
    return found;
  std::vector<cv::Point2f> plane, image;
  for (std::size_t j = 0; j < m.ids.size(); ++j) {
    const std::vector<cv::Point3f>& object = board->objPoints[static_cast<std::size_t>(m.ids[j])];
    for (int q = 0; q < 4; ++q) {
      plane.emplace_back(object[static_cast<std::size_t>(q)].x,
                         object[static_cast<std::size_t>(q)].y);
      image.push_back(m.corners[j][static_cast<std::size_t>(q)]);
    }
  }
  const cv::Mat h = cv::findHomography(plane, undistorted(image, lens), 0);
  if (h.empty()) return found;
  std::vector<cv::Point2f> on_board, predicted;
  for (const int id : ids) {
    const cv::Point3f& c = board->chessboardCorners[static_cast<std::size_t>(id)];
    on_board.emplace_back(c.x, c.y);
  }
  cv::perspectiveTransform(on_board, predicted, h);
  predicted = distorted(predicted, lens);
  refine(grey, board_spec, predicted);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    found.pixels.emplace_back(predicted[i].x, predicted[i].y);
    found.ids.push_back(ids[i]);
  }
  return found;
}

}  // namespace

std::optional<BoardCorners> find_charuco_corners(const cv::Mat& grey, const BoardSpec& board,
                                                 int* preferred, const sensor::OpenCvCamera* lens) {
  const cv::Ptr<cv::aruco::CharucoBoard> charuco = charuco_board(board);
  const std::size_t all = board_points(board).size();
  BoardCorners best;
  int best_stretch = 0;
  for (const int stretch : stretches_in_order(preferred)) {
    BoardCorners found =
        corners_from_markers(detect_markers(grey, stretch, charuco), board, charuco, grey, lens);
    if (found.ids.size() > best.ids.size()) {
      best = std::move(found);
      best_stretch = stretch;
    }
    // Most of the board: a further stretch would find a corner or two more, at the cost of
    // another detection.
    if (4 * best.ids.size() >= 3 * all) break;
  }
  if (best.ids.empty()) return std::nullopt;
  if (preferred != nullptr) *preferred = best_stretch;
  return best;
}

}  // namespace syncap::board
