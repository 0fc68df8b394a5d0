// The arrow-form inverse of the normal matrix (host/src/estimators/covariance.hpp) against a
// dense inverse of the same matrix, with held values masked out.
#include "estimators/covariance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace syncap::estimators {
namespace {

// A random well-conditioned arrow system: 5 camera values, groups of 3, 6 and 3 values, built
// from random Jacobian rows (each touching the cameras and at most one group), and the same N
// as a dense matrix.
struct RandomArrow {
  std::vector<bool> camera_free{true, true, false, true, true};
  std::vector<std::vector<bool>> group_free{
      {true, true, true}, {true, false, true, true, true, true}, {true, true, true}};
  Eigen::MatrixXd dense;
  ArrowNormalEquations normal{camera_free, group_free};

  RandomArrow() {
    std::mt19937 rng(11);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const int cameras = 5, total = 5 + 3 + 6 + 3;
    const int group_start[] = {5, 8, 14};
    dense = Eigen::MatrixXd::Zero(total, total);
    for (int g = 0; g < 3; ++g) {
      const int size = static_cast<int>(group_free[g].size());
      for (int row = 0; row < 4 * size; ++row) {
        Eigen::MatrixXd j(2, cameras + size);
        for (int k = 0; k < j.size(); ++k) j.data()[k] = gauss(rng);
        // Very different scales, as k3 beside X0.
        j.col(1) *= 1e4;
        j.col(cameras) *= 1e-3;
        normal.add(j, {0, 1, 2, 3, 4}, g);
        Eigen::MatrixXd full = Eigen::MatrixXd::Zero(2, total);
        full.leftCols(cameras) = j.leftCols(cameras);
        full.middleCols(group_start[g], size) = j.rightCols(size);
        dense += full.transpose() * full;
      }
    }
  }

  std::vector<bool> all_free() const {
    std::vector<bool> free = camera_free;
    for (const auto& g : group_free) free.insert(free.end(), g.begin(), g.end());
    return free;
  }
};

TEST(ArrowCovariance, EqualsTheDenseInverseWithHeldValuesMaskedOut) {
  RandomArrow arrow;
  const Eigen::MatrixXd expected = masked_inverse(arrow.dense, arrow.all_free(), "dense");
  const ArrowCofactors q = invert(arrow.normal);
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LT((q.camera_camera - expected.topLeftCorner(5, 5)).cwiseAbs().maxCoeff(), 1e-10 * scale);
  const int start[] = {5, 8, 14};
  for (int g = 0; g < 3; ++g) {
    const int size = static_cast<int>(arrow.group_free[g].size());
    EXPECT_LT(
        (q.group_group[g] - expected.block(start[g], start[g], size, size)).cwiseAbs().maxCoeff(),
        1e-10 * scale)
        << "group " << g;
    EXPECT_LT((q.camera_group[g] - expected.block(0, start[g], 5, size)).cwiseAbs().maxCoeff(),
              1e-10 * scale)
        << "group " << g;
  }
  // Held values have zero cofactors.
  EXPECT_EQ(q.camera_camera.row(2).norm(), 0.0);
  EXPECT_EQ(q.group_group[1].col(1).norm(), 0.0);

  // solve() is N^-1 times a right-hand side.
  Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(17, -1.0, 1.0);
  Eigen::MatrixXd camera_solution;
  std::vector<Eigen::MatrixXd> group_solution;
  q.solve(rhs.head(5), {rhs.segment(5, 3), rhs.segment(8, 6), rhs.segment(14, 3)}, &camera_solution,
          &group_solution);
  const Eigen::VectorXd expected_solution = expected * rhs;
  EXPECT_LT((camera_solution - expected_solution.head(5)).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((group_solution[1] - expected_solution.segment(8, 6)).cwiseAbs().maxCoeff(),
            1e-9 * scale);
}

TEST(ArrowCovariance, ASingularGroupIsNamed) {
  RandomArrow arrow;
  arrow.normal.group_group[2].row(1).setZero();
  arrow.normal.group_group[2].col(1).setZero();
  try {
    invert(arrow.normal);
    FAIL() << "no error";
  } catch (const SingularNormalEquations& e) {
    EXPECT_NE(std::string(e.what()).find("point group 2: value 1 is not determined"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace syncap::estimators
