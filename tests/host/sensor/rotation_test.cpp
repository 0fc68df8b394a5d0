#include "sensor/rotation.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

namespace syncap::sensor {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Rotation, IsTheProductKappaPhiOmegaOfTheElementaryRotations) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const double omega = angle(rng), phi = angle(rng), kappa = angle(rng);
    const Eigen::Matrix3d product = to_eigen(rotation_kappa(kappa)) * to_eigen(rotation_phi(phi)) *
                                    to_eigen(rotation_omega(omega));
    const Eigen::Matrix3d r = rotation_matrix(omega, phi, kappa);
    EXPECT_LT((r - product).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
  }
}

TEST(Rotation, ElementaryRotationsTurnCounterClockwiseAboutTheirAxis) {
  // Seen from the positive axis, a positive angle turns the next axis towards the one after.
  const double q = kPi / 2;
  EXPECT_LT(
      (to_eigen(rotation_omega(q)) * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(),
      1e-15);
  EXPECT_LT(
      (to_eigen(rotation_phi(q)) * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(),
      1e-15);
  EXPECT_LT(
      (to_eigen(rotation_kappa(q)) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(),
      1e-15);
}

TEST(Rotation, AnglesAreRecoveredFromTheMatrix) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> half(-kPi / 2 + 1e-6, kPi / 2 - 1e-6);
  for (int i = 0; i < 200; ++i) {
    const double omega = angle(rng), phi = half(rng), kappa = angle(rng);
    const RotationAngles a = angles_from_rotation(rotation_matrix(omega, phi, kappa));
    EXPECT_NEAR(a.omega, omega, 1e-9);
    EXPECT_NEAR(a.phi, phi, 1e-9);
    EXPECT_NEAR(a.kappa, kappa, 1e-9);
  }
}

TEST(Rotation, GimbalLockStillReproducesTheMatrix) {
  for (const double phi : {kPi / 2, -kPi / 2}) {
    const Eigen::Matrix3d r = rotation_matrix(0.3, phi, -0.2);
    const RotationAngles a = angles_from_rotation(r);
    EXPECT_EQ(a.kappa, 0.0);
    EXPECT_LT((rotation_matrix(a.omega, a.phi, a.kappa) - r).cwiseAbs().maxCoeff(), 1e-12);
  }
}

}  // namespace
}  // namespace syncap::sensor
