// BVH forward kinematics against positions computed by hand, and sampling between frames.
#include <gtest/gtest.h>

#include <numbers>

#include "body/bvh_kinematics.hpp"

namespace syncap::body {
namespace {

// Root "A" with 6 channels (rotations Z then X), child "B" 10 up with Z then X, end 5 up.
Bvh two_joints(const std::string& frames, int count,
               const char* b_channels = "Zrotation Xrotation") {
  const std::string text =
      std::string("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\n") +
      "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n" +
      "JOINT B\n{\nOFFSET 0 10 0\nCHANNELS 3 " + b_channels + " Yrotation\n" +
      "End Site\n{\nOFFSET 0 5 0\n}\n}\n}\nMOTION\nFrames: " + std::to_string(count) +
      "\nFrame Time: 0.5\n" + frames;
  return parse_bvh(text, "two.bvh");
}

BvhWorldPose at_frame(const Bvh& bvh, int k) {
  return bvh_forward_kinematics(bvh, bvh_frame_pose(bvh, k));
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  EXPECT_LT((a - b).norm(), 1e-12) << a.transpose() << " vs " << b.transpose();
}

TEST(BvhKinematics, RestPoseFollowsTheOffsets) {
  const Bvh bvh = two_joints("0 0 0 0 0 0 0 0 0\n", 1);
  const BvhWorldPose w = at_frame(bvh, 0);
  expect_near(w.position[1], {0, 10, 0});
  expect_near(w.position[2], {0, 15, 0});
}

TEST(BvhKinematics, HandComputedTwoJointChain) {
  // Root at (1, 2, 3) turned 90 degrees about Z: B = root + Rz(90) (0, 10, 0) = (-9, 2, 3).
  // B turned 90 degrees about X: end = B + Rz(90) Rx(90) (0, 5, 0) = B + Rz(90) (0, 0, 5)
  // = (-9, 2, 8).
  const Bvh bvh = two_joints("1 2 3 90 0 0 0 90 0\n", 1);
  const BvhWorldPose w = at_frame(bvh, 0);
  expect_near(w.position[0], {1, 2, 3});
  expect_near(w.position[1], {-9, 2, 3});
  expect_near(w.position[2], {-9, 2, 8});
}

TEST(BvhKinematics, RotationChannelsComposeIntrinsicallyInFileOrder) {
  // "Zrotation Xrotation": R = Rz(90) Rx(90); (0, 5, 0) -> Rx: (0, 0, 5) -> Rz: (0, 0, 5).
  const Bvh zx = two_joints("0 0 0 0 0 0 90 90 0\n", 1, "Zrotation Xrotation");
  expect_near(at_frame(zx, 0).position[2], {0, 10, 5});
  // "Xrotation Zrotation" with the same values: R = Rx(90) Rz(90); (0, 5, 0) -> Rz: (-5, 0, 0)
  // -> Rx: (-5, 0, 0).
  const Bvh xz = two_joints("0 0 0 0 0 0 90 90 0\n", 1, "Xrotation Zrotation");
  expect_near(at_frame(xz, 0).position[2], {-5, 10, 0});
}

TEST(BvhKinematics, ThreeAxesInRootOrder) {
  // Root "Zrotation Xrotation Yrotation" = Rz(90) Rx(90) Ry(90): (0, 10, 0) -> Ry: (0, 10, 0)
  // -> Rx: (0, 0, 10) -> Rz: (0, 0, 10).
  const Bvh bvh = two_joints("0 0 0 90 90 90 0 0 0\n", 1);
  expect_near(at_frame(bvh, 0).position[1], {0, 0, 10});
  const Eigen::Quaterniond expected =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()) *
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(at_frame(bvh, 0).rotation[0].angularDistance(expected), 0, 1e-12);
}

TEST(BvhKinematics, SamplingAtFrameTimesGivesTheFrames) {
  const Bvh bvh =
      two_joints("0 0 0 0 0 0 0 0 0\n10 20 30 40 50 60 70 80 90\n-5 0 5 -30 10 0 5 5 5\n", 3);
  for (int k = 0; k < bvh.frame_count; ++k) {
    const BvhLocalPose frame = bvh_frame_pose(bvh, k);
    const BvhLocalPose sampled = bvh_sample_pose(bvh, k * bvh.frame_time_s);
    for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
      EXPECT_NEAR(frame.rotation[j].angularDistance(sampled.rotation[j]), 0, 1e-12);
      EXPECT_LT((frame.translation[j] - sampled.translation[j]).norm(), 1e-12);
    }
  }
}

TEST(BvhKinematics, SamplingBetweenFramesSlerpsAndLerps) {
  const Bvh bvh = two_joints("0 0 0 0 0 0 0 0 0\n10 20 30 90 0 0 0 0 0\n", 2);
  const BvhLocalPose mid = bvh_sample_pose(bvh, 0.25);
  EXPECT_LT((mid.translation[0] - Eigen::Vector3d(5, 10, 15)).norm(), 1e-12);
  const Eigen::Quaterniond half(Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(mid.rotation[0].angularDistance(half), 0, 1e-12);
  // Outside the clip: its ends.
  EXPECT_LT((bvh_sample_pose(bvh, -1).translation[0]).norm(), 1e-12);
  EXPECT_LT((bvh_sample_pose(bvh, 9).translation[0] - Eigen::Vector3d(10, 20, 30)).norm(), 1e-12);
}

TEST(BvhKinematics, UnitGuessedFromTheFigureHeight) {
  EXPECT_EQ(guess_unit_mm(178), 10);     // cm (Mixamo)
  EXPECT_EQ(guess_unit_mm(1.78), 1000);  // m
  EXPECT_EQ(guess_unit_mm(1750), 1);     // mm
  EXPECT_EQ(guess_unit_mm(68), 25.4);    // inches
  const Bvh bvh = two_joints("0 0 0 0 0 0 0 0 0\n", 1);
  EXPECT_DOUBLE_EQ(bvh_rest_height(bvh, 1), 15);
}

}  // namespace
}  // namespace syncap::body
