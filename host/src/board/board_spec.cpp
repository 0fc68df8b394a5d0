#include "board/board_spec.hpp"

#include <cstdio>

namespace syncap::board {

std::optional<BoardSpec> parse_board_spec(const std::string& text) {
  int cols = 0, rows = 0, used = 0;
  double square = 0.0;
  if (std::sscanf(text.c_str(), "%dx%dx%lf%n", &cols, &rows, &square, &used) != 3 ||
      used != static_cast<int>(text.size()) || cols < 3 || rows < 3 || cols > 100 || rows > 100 ||
      !(square > 0.0 && square < 1e5))
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
  return board.inner_corners.width % 2 == 0 && board.inner_corners.height % 2 == 0;
}

}  // namespace syncap::board
