// The fitted motion as the exports take it: the BVH skeleton's offsets rebuild the fitted
// figure's joints, and a BVH file written from fitted poses, read back by the body library's own
// BVH reader and moved by its forward kinematics, puts every joint where the fit put it.
#include "fitting/motion_export.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "body/bvh.hpp"
#include "body/bvh_kinematics.hpp"
#include "body/hanim_model.hpp"
#include "body_scenes.hpp"
#include "io/bvh_writer.hpp"

namespace syncap::fitting {
namespace {

class MotionExportTest : public ::testing::Test {
 protected:
  const PoseParameters parameters_{body::hanim_skeleton()};
  std::mt19937 rng_{8};
};

TEST_F(MotionExportTest, TheSkeletonsOffsetsRebuildTheRestJoints) {
  const std::vector<io::BvhJoint> joints = bvh_joints(parameters_);
  ASSERT_EQ(joints.size(), 1 + kFittedJoints.size());
  EXPECT_EQ(joints[0].name, parameters_.skeleton().node(0).name);
  std::vector<Eigen::Vector3d> at(joints.size(), Eigen::Vector3d::Zero());
  for (std::size_t j = 1; j < joints.size(); ++j) {
    ASSERT_GE(joints[j].parent, 0);
    ASSERT_LT(joints[j].parent, static_cast<int>(j));
    EXPECT_EQ(joints[j].name, kFittedJoints[j - 1]);
    at[j] = at[static_cast<std::size_t>(joints[j].parent)] + joints[j].offset_mm;
    const int node = parameters_.fitted_nodes()[j - 1];
    EXPECT_LT((at[j] - parameters_.skeleton().node(node).rest_mm).norm(), 1e-9) << joints[j].name;
  }
  // The limbs' and the head's last joints end at a site well beyond them (hands, feet, skull).
  for (const char* leaf : {"l_wrist", "r_wrist", "l_ankle", "r_ankle", "skullbase"}) {
    for (const io::BvhJoint& joint : joints)
      if (joint.name == leaf) {
        EXPECT_GT(joint.end_site_mm.norm(), 70.0) << leaf;
      }
  }
}

TEST_F(MotionExportTest, ABvhFileReadBackPutsEveryJointWhereTheFitPutIt) {
  std::vector<std::optional<PoseVector>> frames;
  for (int f = 0; f < 3; ++f) frames.push_back(test::random_pose(rng_, 0.4));
  frames.insert(frames.begin() + 1, std::nullopt);  // a frame without a fit repeats the last
  const auto file = std::filesystem::path(::testing::TempDir()) / "motion_export_test.bvh";
  io::write_bvh(file.string(), bvh_motion(parameters_, frames, 30.0));
  const tracking::MarkerTrajectories joints = joint_trajectories(parameters_, frames, 30.0, 100);
  ASSERT_EQ(joints.samples.size(), frames.size());
  EXPECT_FALSE(joints.samples[1][0].has_value());  // the trajectories leave the gap

  const body::Bvh bvh = body::load_bvh(file);
  ASSERT_EQ(bvh.frame_count, 4);
  EXPECT_NEAR(bvh.frame_time_s, 1.0 / 30.0, 1e-9);
  // The file is Y up in metres: back to our Z up in mm.
  Eigen::Matrix3d to_ours;
  to_ours << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  for (int f = 0; f < 4; ++f) {
    const std::size_t fit_row = f == 1 ? 0 : static_cast<std::size_t>(f);
    const body::BvhWorldPose pose = body::bvh_forward_kinematics(bvh, body::bvh_frame_pose(bvh, f));
    for (std::size_t j = 0; j < joints.labels.size(); ++j) {
      const int read = bvh.find(joints.labels[j]);
      ASSERT_GE(read, 0) << joints.labels[j];
      const Eigen::Vector3d ours =
          1000.0 * (to_ours * pose.position[static_cast<std::size_t>(read)]);
      EXPECT_LT((ours - joints.samples[fit_row][j]->position_mm).norm(), 0.01)
          << "frame " << f << " " << joints.labels[j];
    }
  }
}

TEST_F(MotionExportTest, NoPoseAtAllIsRefused) {
  const std::vector<std::optional<PoseVector>> none(3);
  EXPECT_THROW(bvh_motion(parameters_, none, 30.0), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::fitting
