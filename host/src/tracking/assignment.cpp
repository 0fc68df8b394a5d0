#include "tracking/assignment.hpp"

#include <limits>
#include <stdexcept>

namespace syncap::tracking {

// Column 0 is a virtual column that holds the row being added; real columns are 1..cols and rows
// 1..rows (the classic formulation; its potentials keep every reduced cost >= 0).
void AssignmentSolver::augment_row(std::span<const double> cost, int row, int cols) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  row_of_col_[0] = row;
  int col = 0;
  min_slack_.assign(cols + 1, kInfinity);
  col_used_.assign(cols + 1, 0);
  do {
    col_used_[col] = 1;
    const int r = row_of_col_[col];
    double delta = kInfinity;
    int next = 0;
    for (int j = 1; j <= cols; ++j) {
      if (col_used_[j]) continue;
      const double slack = cost[(r - 1) * cols + (j - 1)] - row_potential_[r] - col_potential_[j];
      if (slack < min_slack_[j]) {
        min_slack_[j] = slack;
        previous_col_[j] = col;
      }
      if (min_slack_[j] < delta) {
        delta = min_slack_[j];
        next = j;
      }
    }
    for (int j = 0; j <= cols; ++j) {
      if (col_used_[j]) {
        row_potential_[row_of_col_[j]] += delta;
        col_potential_[j] -= delta;
      } else {
        min_slack_[j] -= delta;
      }
    }
    col = next;
  } while (row_of_col_[col] != 0);
  do {  // flip the augmenting path back to the virtual column
    const int before = previous_col_[col];
    row_of_col_[col] = row_of_col_[before];
    col = before;
  } while (col != 0);
}

void AssignmentSolver::solve(std::span<const double> cost, int rows, int cols,
                             std::span<int> row_to_col) {
  if (rows > cols || cost.size() < static_cast<std::size_t>(rows) * cols ||
      row_to_col.size() < static_cast<std::size_t>(rows)) {
    throw std::invalid_argument("AssignmentSolver::solve: needs rows <= cols and a full matrix");
  }
  row_potential_.assign(rows + 1, 0.0);
  col_potential_.assign(cols + 1, 0.0);
  row_of_col_.assign(cols + 1, 0);
  previous_col_.assign(cols + 1, 0);
  for (int r = 1; r <= rows; ++r) augment_row(cost, r, cols);
  for (int j = 1; j <= cols; ++j) {
    if (row_of_col_[j] != 0) row_to_col[row_of_col_[j] - 1] = j - 1;
  }
}

}  // namespace syncap::tracking
