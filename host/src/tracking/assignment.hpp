// Minimum-cost assignment of rows to columns (the tracker's tracks to points): the shortest
// augmenting path form of the Hungarian method (Jonker-Volgenant style, with dual potentials),
// O(rows^2 cols). The tracker only solves the small groups of tracks and points that compete
// for each other, so its matrices are a few rows wide.
#pragma once

#include <span>
#include <vector>

namespace syncap::tracking {

// A cost at least this large forbids the pair (the solver needs finite costs).
inline constexpr double kForbiddenCost = 1e12;

// Reusable buffers: a solver kept across frames allocates only while its largest problem grows.
class AssignmentSolver {
 public:
  // cost: rows x cols, row-major, rows <= cols, every row with at least one allowed column.
  // row_to_col[r] gets the column of row r; the sum of their costs is the least possible.
  void solve(std::span<const double> cost, int rows, int cols, std::span<int> row_to_col);

 private:
  std::vector<double> row_potential_, col_potential_, min_slack_;
  std::vector<int> row_of_col_, previous_col_;
  std::vector<char> col_used_;
  void augment_row(std::span<const double> cost, int row, int cols);
};

}  // namespace syncap::tracking
