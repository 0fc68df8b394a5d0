#include "tracking/assignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace syncap::tracking {
namespace {

double total(const std::vector<double>& cost, int cols, const std::vector<int>& choice) {
  double sum = 0;
  for (std::size_t r = 0; r < choice.size(); ++r) sum += cost[r * cols + choice[r]];
  return sum;
}

// The least total over every injective choice of columns (rows <= cols, small).
double brute_force(const std::vector<double>& cost, int rows, int cols) {
  std::vector<int> perm(cols);
  std::iota(perm.begin(), perm.end(), 0);
  double best = 1e300;
  do {
    best = std::min(best, total(cost, cols, std::vector<int>(perm.begin(), perm.begin() + rows)));
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

TEST(Assignment, BeatsGreedyByRow) {
  // Row 0's cheapest column is row 1's only good one: greedy by row pays 1 + 100.
  const std::vector<double> cost = {1, 2, 1, 100};
  AssignmentSolver solver;
  std::vector<int> choice(2);
  solver.solve(cost, 2, 2, choice);
  EXPECT_EQ(choice, (std::vector<int>{1, 0}));
}

TEST(Assignment, MatchesBruteForceOnRandomRectangularMatrices) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(0, 10);
  AssignmentSolver solver;  // reused: its buffers must not leak state between problems
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 1 + trial % 5, cols = rows + trial % 3;
    std::vector<double> cost(rows * cols);
    for (double& c : cost)
      c = trial % 2 ? value(rng) : (value(rng) < 4 ? kForbiddenCost : value(rng));
    for (int r = 0; r < rows; ++r) cost[r * cols + (r % cols)] = value(rng);  // always feasible
    std::vector<int> choice(rows);
    solver.solve(cost, rows, cols, choice);
    std::vector<int> sorted = choice;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
    EXPECT_NEAR(total(cost, cols, choice), brute_force(cost, rows, cols), 1e-9) << trial;
  }
}

TEST(Assignment, RefusesMoreRowsThanColumns) {
  AssignmentSolver solver;
  std::vector<int> choice(2);
  EXPECT_THROW(solver.solve(std::vector<double>{1, 2}, 2, 1, choice), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::tracking
