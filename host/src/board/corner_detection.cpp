#include "board/corner_detection.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "board/charuco_detection.hpp"
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

std::vector<int> stretches_in_order(const int* preferred) {
  std::vector<int> order(std::begin(kStretches), std::end(kStretches));
  if (preferred != nullptr && std::ranges::find(order, *preferred) != order.end()) {
    std::erase(order, *preferred);
    order.insert(order.begin(), *preferred);
  }
  return order;
}

std::optional<std::vector<cv::Point2d>> find_board_corners(const cv::Mat& grey,
                                                           const BoardSpec& board, int* preferred) {
  for (const int stretch : stretches_in_order(preferred)) {
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

namespace {

// Every detection's corners by board point.
using Detection = std::vector<std::pair<int, cv::Point2d>>;

std::optional<Detection> detect_board(const cv::Mat& grey, const BoardSpec& board, int* stretch,
                                      const std::vector<cv::Point2d>* first,
                                      const sensor::OpenCvCamera* lens) {
  Detection detection;
  if (board.kind == BoardKind::kCharuco) {
    const auto found = find_charuco_corners(grey, board, stretch, lens);
    if (!found) return std::nullopt;
    for (std::size_t i = 0; i < found->ids.size(); ++i)
      detection.emplace_back(found->ids[i], found->pixels[i]);
    return detection;
  }
  auto corners = find_board_corners(grey, board, stretch);
  if (!corners) return std::nullopt;
  if (first != nullptr) *corners = in_order_of(*first, std::move(*corners));
  for (std::size_t i = 0; i < corners->size(); ++i)
    detection.emplace_back(static_cast<int>(i), (*corners)[i]);
  return detection;
}

std::string not_found_message(const fs::path& clip, const BoardSpec& board, int frames) {
  if (board.kind == BoardKind::kCharuco) {
    return util::printf_string(
        "%s: no frame of %d shows %d corners of the %dx%d-square ChArUco board (check --board: "
        "the squares, not the inner corners; the marker size; the dictionary)",
        clip.string().c_str(), frames, kMinCharucoCorners, board.inner_corners.width + 1,
        board.inner_corners.height + 1);
  }
  return util::printf_string(
      "%s: no frame of %d shows the whole %dx%d board (check --board: the inner corners, "
      "not the squares)",
      clip.string().c_str(), frames, board.inner_corners.width, board.inner_corners.height);
}

// Per board point seen in at least half the detections: the median and the squared distances.
void median_corners(const std::vector<Detection>& detections, std::size_t points, BoardView& view) {
  std::vector<std::vector<cv::Point2d>> by_point(points);
  for (const Detection& d : detections) {
    for (const auto& [id, p] : d) by_point[static_cast<std::size_t>(id)].push_back(p);
  }
  double sum_squares = 0.0;
  std::size_t count = 0;
  for (std::size_t id = 0; id < points; ++id) {
    const std::vector<cv::Point2d>& seen = by_point[id];
    if (seen.empty() || 2 * seen.size() < detections.size()) continue;
    std::vector<double> xs, ys;
    for (const cv::Point2d& p : seen) {
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
    const cv::Point2d m(median(xs), median(ys));
    view.corners.push_back(m);
    view.point_ids.push_back(static_cast<int>(id));
    for (const cv::Point2d& p : seen) sum_squares += std::pow(cv::norm(p - m), 2);
    count += seen.size();
  }
  view.spread_px = count == 0 ? 0.0 : std::sqrt(sum_squares / static_cast<double>(count));
}

}  // namespace

BoardView observe_board(const fs::path& clip, const BoardSpec& board, int max_frames, int step,
                        const sensor::OpenCvCamera* lens) {
  FrameReader reader(clip);
  BoardView view;
  std::vector<Detection> detections;
  std::vector<cv::Point2d> first;  // a checkerboard's first detection, in its order
  int stretch = kStretches[0];
  for (cv::Mat grey = reader.next(); !grey.empty() && view.frames_read < max_frames * step;
       grey = reader.next()) {
    view.image_size = grey.size();
    if (view.frames_read++ % step != 0) continue;
    auto d = detect_board(grey, board, &stretch, first.empty() ? nullptr : &first, lens);
    if (!d) continue;
    if (first.empty() && board.kind == BoardKind::kCheckerboard) {
      for (const auto& corner : *d) first.push_back(corner.second);
    }
    detections.push_back(std::move(*d));
  }
  if (view.frames_read == 0) throw BoardError(clip.string() + ": no frames");
  if (detections.empty()) throw BoardError(not_found_message(clip, board, view.frames_read));
  view.frames_found = static_cast<int>(detections.size());
  median_corners(detections, board_points(board).size(), view);
  if (static_cast<int>(view.corners.size()) < kMinCharucoCorners)
    throw BoardError(util::printf_string(
        "%s: the board's corners move from frame to frame (%zu corners seen in half the %d "
        "frames with the board; it must not move)",
        clip.string().c_str(), view.corners.size(), view.frames_found));
  return view;
}

}  // namespace syncap::board
