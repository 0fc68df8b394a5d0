#include "board/corner_detection.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "hull/views_io.hpp"
#include "util/printf_string.hpp"

namespace syncap::board {
namespace {

namespace fs = std::filesystem;

constexpr int kDetectorFlags = cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY;

double median(std::vector<double> v) {
  std::ranges::nth_element(v, v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2));
  return v[v.size() / 2];
}

// The same corners in the order closest to `reference` (a symmetric board's detections may come
// in either).
std::vector<cv::Point2d> in_order_of(const std::vector<cv::Point2d>& reference,
                                     std::vector<cv::Point2d> corners) {
  double same = 0.0, reversed = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    same += cv::norm(corners[i] - reference[i]);
    reversed += cv::norm(corners[corners.size() - 1 - i] - reference[i]);
  }
  if (reversed < same) std::ranges::reverse(corners);
  return corners;
}

// The frames of a clip: a video file, or the images of a folder in name order.
class FrameReader {
 public:
  explicit FrameReader(const fs::path& clip) {
    if (fs::is_directory(clip)) {
      try {
        files_ = hull::mask_files(clip);  // the images of the folder in name order
      } catch (const hull::HullError& e) {
        throw BoardError(e.what());
      }
    } else if (!video_.open(clip.string())) {
      throw BoardError(clip.string() +
                       ": cannot open the board clip (a video file or an image "
                       "folder)");
    }
  }
  // The next frame in grey; empty at the end.
  cv::Mat next() {
    cv::Mat frame;
    if (video_.isOpened()) {
      video_.read(frame);
    } else if (index_ < files_.size()) {
      frame = cv::imread(files_[index_++].string(), cv::IMREAD_COLOR);
      if (frame.empty()) throw BoardError(files_[index_ - 1].string() + ": not a readable image");
    }
    if (frame.empty()) return frame;
    cv::Mat grey;
    cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
    return grey;
  }

 private:
  cv::VideoCapture video_;
  std::vector<fs::path> files_;
  std::size_t index_ = 0;
};

// The image's mean grey in the cell between inner corners (i, j) and (i + 1, j + 1).
double cell_grey(const cv::Mat& grey, const std::vector<cv::Point2d>& c, int cols, int i, int j) {
  const std::size_t a = static_cast<std::size_t>(j * cols + i);
  const cv::Point2d centre = 0.25 * (c[a] + c[a + 1] + c[a + cols] + c[a + cols + 1]);
  // A quarter of the cell's smaller diagonal around its centre.
  const double r =
      0.125 * std::min(cv::norm(c[a] - c[a + cols + 1]), cv::norm(c[a + 1] - c[a + cols]));
  const cv::Rect box(
      cv::Point(static_cast<int>(std::lround(centre.x - r)),
                static_cast<int>(std::lround(centre.y - r))),
      cv::Size(std::max(1, static_cast<int>(2 * r)), std::max(1, static_cast<int>(2 * r))));
  return cv::mean(grey(box & cv::Rect(0, 0, grey.cols, grey.rows)))[0];
}

// The detector's order made the board's own (board_spec.hpp): seen from its front, the COLS
// axis turns onto the ROWS axis clockwise in the image (a detection mirrored within its rows is
// turned back), and on a board that a half turn does not map onto itself the cell between the
// first four corners is the dark one (the detector starts at either end).
void canonical_order(const cv::Mat& grey, const BoardSpec& board, std::vector<cv::Point2d>& c) {
  const int cols = board.inner_corners.width, rows = board.inner_corners.height;
  const cv::Point2d along = c[1] - c[0], across = c[static_cast<std::size_t>(cols)] - c[0];
  if (along.x * across.y - along.y * across.x < 0.0) {
    for (int j = 0; j < rows; ++j) std::reverse(c.begin() + j * cols, c.begin() + (j + 1) * cols);
  }
  if (has_half_turn_symmetry(board)) return;
  if (cell_grey(grey, c, cols, 0, 0) > cell_grey(grey, c, cols, 1, 0)) std::ranges::reverse(c);
}

}  // namespace

std::optional<std::vector<cv::Point2d>> find_board_corners(const cv::Mat& grey,
                                                           const BoardSpec& board, int* preferred) {
  std::vector<int> order(std::begin(kStretches), std::end(kStretches));
  if (preferred != nullptr && std::ranges::find(order, *preferred) != order.end()) {
    std::erase(order, *preferred);
    order.insert(order.begin(), *preferred);
  }
  for (const int stretch : order) {
    cv::Mat image = grey;
    if (stretch > 1) cv::resize(grey, image, {}, 1.0, stretch, cv::INTER_CUBIC);
    std::vector<cv::Point2f> found;
    if (!cv::findChessboardCornersSB(image, board.inner_corners, found, kDetectorFlags)) continue;
    std::vector<cv::Point2d> corners;
    // cv::resize maps pixel centres: v_stretched + 0.5 = stretch (v + 0.5).
    for (const cv::Point2f& p : found) corners.emplace_back(p.x, (p.y + 0.5) / stretch - 0.5);
    if (preferred != nullptr) *preferred = stretch;
    canonical_order(grey, board, corners);
    return corners;
  }
  return std::nullopt;
}

BoardView observe_board(const fs::path& clip, const BoardSpec& board, int max_frames, int step) {
  FrameReader reader(clip);
  BoardView view;
  std::vector<std::vector<cv::Point2d>> detections;
  int stretch = kStretches[0];
  for (cv::Mat grey = reader.next(); !grey.empty() && view.frames_read < max_frames * step;
       grey = reader.next()) {
    view.image_size = grey.size();
    if (view.frames_read++ % step != 0) continue;
    if (auto corners = find_board_corners(grey, board, &stretch)) {
      detections.push_back(detections.empty() ? std::move(*corners)
                                              : in_order_of(detections.front(), *corners));
    }
  }
  if (view.frames_read == 0) throw BoardError(clip.string() + ": no frames");
  if (detections.empty()) {
    throw BoardError(util::printf_string(
        "%s: no frame of %d shows the whole %dx%d board (check --board: the inner corners, "
        "not the squares)",
        clip.string().c_str(), view.frames_read, board.inner_corners.width,
        board.inner_corners.height));
  }
  view.frames_found = static_cast<int>(detections.size());
  const std::size_t n = detections.front().size();
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double> xs, ys;
    for (const auto& d : detections) {
      xs.push_back(d[i].x);
      ys.push_back(d[i].y);
    }
    view.corners.emplace_back(median(xs), median(ys));
    for (const auto& d : detections) sum_squares += std::pow(cv::norm(d[i] - view.corners[i]), 2);
  }
  view.spread_px = std::sqrt(sum_squares / static_cast<double>(n * detections.size()));
  return view;
}

}  // namespace syncap::board
