#include "board/board_spec.hpp"

#include <opencv2/aruco/dictionary.hpp>

#include <cstdio>
#include <map>

namespace syncap::board {
namespace {

bool plausible_size(int cols, int rows, double square) {
  return cols >= 3 && rows >= 3 && cols <= 100 && rows <= 100 && square > 0.0 && square < 1e5;
}

std::optional<int> dictionary_named(const std::string& name) {
  namespace aruco = cv::aruco;
  static const std::map<std::string, int> kNames{{"4x4_50", aruco::DICT_4X4_50},
                                                 {"4x4_100", aruco::DICT_4X4_100},
                                                 {"4x4_250", aruco::DICT_4X4_250},
                                                 {"4x4_1000", aruco::DICT_4X4_1000},
                                                 {"5x5_50", aruco::DICT_5X5_50},
                                                 {"5x5_100", aruco::DICT_5X5_100},
                                                 {"5x5_250", aruco::DICT_5X5_250},
                                                 {"5x5_1000", aruco::DICT_5X5_1000},
                                                 {"6x6_50", aruco::DICT_6X6_50},
                                                 {"6x6_100", aruco::DICT_6X6_100},
                                                 {"6x6_250", aruco::DICT_6X6_250},
                                                 {"6x6_1000", aruco::DICT_6X6_1000},
                                                 {"7x7_50", aruco::DICT_7X7_50},
                                                 {"7x7_100", aruco::DICT_7X7_100},
                                                 {"7x7_250", aruco::DICT_7X7_250},
                                                 {"7x7_1000", aruco::DICT_7X7_1000},
                                                 {"aruco_original", aruco::DICT_ARUCO_ORIGINAL}};
  const auto it = kNames.find(name);
  if (it == kNames.end()) return std::nullopt;
  return it->second;
}

// "SXxSYxSQUARExMARKER[:DICT]" after "charuco:".
std::optional<BoardSpec> parse_charuco(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string sizes = text.substr(0, colon);
  int squares_x = 0, squares_y = 0, used = 0;
  double square = 0.0, marker = 0.0;
  if (std::sscanf(sizes.c_str(), "%dx%dx%lfx%lf%n", &squares_x, &squares_y, &square, &marker,
                  &used) != 4 ||
      used != static_cast<int>(sizes.size()) ||
      !plausible_size(squares_x - 1, squares_y - 1, square) || !(marker > 0.0 && marker < square))
    return std::nullopt;
  const auto dictionary =
      colon == std::string::npos ? std::optional<int>(0) : dictionary_named(text.substr(colon + 1));
  if (!dictionary) return std::nullopt;
  BoardSpec spec{{squares_x - 1, squares_y - 1}, square, BoardKind::kCharuco, marker, *dictionary};
  // The board's markers must exist in the dictionary: one per white square.
  const int markers = squares_x * squares_y / 2;
  if (markers > cv::aruco::getPredefinedDictionary(spec.dictionary)->bytesList.rows)
    return std::nullopt;
  return spec;
}

}  // namespace

std::optional<BoardSpec> parse_board_spec(const std::string& text) {
  constexpr std::string_view kCharucoPrefix = "charuco:";
  if (text.starts_with(kCharucoPrefix)) return parse_charuco(text.substr(kCharucoPrefix.size()));
  int cols = 0, rows = 0, used = 0;
  double square = 0.0;
  if (std::sscanf(text.c_str(), "%dx%dx%lf%n", &cols, &rows, &square, &used) != 3 ||
      used != static_cast<int>(text.size()) || !plausible_size(cols, rows, square))
    return std::nullopt;
  return BoardSpec{{cols, rows}, square};
}

std::vector<cv::Point3d> board_points(const BoardSpec& board) {
  std::vector<cv::Point3d> points;
  for (int j = 0; j < board.inner_corners.height; ++j) {
    for (int i = 0; i < board.inner_corners.width; ++i)
      points.emplace_back(i * board.square_mm, j * board.square_mm, 0.0);
  }
  return points;
}

bool has_half_turn_symmetry(const BoardSpec& board) {
  // A half turn maps corner (i, j) to (COLS-1-i, ROWS-1-j) and the square to the lower right of
  // a corner onto the square to its upper left: the same colour exactly when both counts are even
  // (odd square counts per side).
  return board.kind == BoardKind::kCheckerboard && board.inner_corners.width % 2 == 0 &&
         board.inner_corners.height % 2 == 0;
}

}  // namespace syncap::board
