// The pose parameters: they describe exactly the poses body::body_frame draws (the templated
// kinematics against the library's quaternion one), and name a skeleton that cannot be fitted.
#include "fitting/pose_parameters.hpp"

#include <gtest/gtest.h>

#include <random>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"

namespace syncap::fitting {
namespace {

TEST(PoseParameters, TheTemplatedKinematicsDrawWhatTheBodyLibraryDraws) {
  const PoseParameters parameters(body::hanim_skeleton());
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const PoseVector x = test::random_pose(rng, 0.8);
    const body::BodyFrame body = body::body_frame(parameters.skeleton(), parameters.pose(x.data()));
    std::vector<PosedEllipsoid<double>> ellipsoids;
    parameters.ellipsoids(x.data(), ellipsoids);
    ASSERT_EQ(ellipsoids.size(), body.ellipsoids.size());
    for (std::size_t s = 0; s < ellipsoids.size(); ++s) {
      EXPECT_LT((ellipsoids[s].centre - body.ellipsoids[s].centre_mm).norm(), 1e-9) << s;
      EXPECT_LT((ellipsoids[s].axes - body.ellipsoids[s].axes).norm(), 1e-9) << s;
    }
    std::vector<Eigen::Matrix3d> rotations;
    std::vector<Eigen::Vector3d> positions;
    parameters.nodes(x.data(), rotations, positions);
    for (std::size_t i = 0; i < positions.size(); ++i)
      EXPECT_LT((positions[i] - body.positions_mm[i]).norm(), 1e-9) << i;
  }
}

TEST(PoseParameters, TheRestParametersAreTheRestFigure) {
  const PoseParameters parameters(body::hanim_skeleton());
  const PoseVector rest = parameters.rest();
  const auto fitted = body::node_positions(parameters.skeleton(), parameters.pose(rest.data()));
  const auto expected =
      body::node_positions(parameters.skeleton(), body::Pose::rest(parameters.skeleton()));
  for (std::size_t i = 0; i < fitted.size(); ++i)
    EXPECT_LT((fitted[i] - expected[i]).norm(), 1e-9) << i;
}

// A pose the parameters can say exactly comes back from nearest() as the same pose.
TEST(PoseParameters, TheNearestParametersOfTheirOwnPoseAreThatPose) {
  const PoseParameters parameters(body::hanim_skeleton());
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const PoseVector x = test::random_pose(rng, 0.8);
    const PoseVector back = parameters.nearest(parameters.pose(x.data()));
    EXPECT_LT(test::joint_rms_mm(parameters, x, back), 1e-9) << trial;
  }
}

TEST(PoseParameters, ASkeletonWithoutAFittedJointIsNamed) {
  const body::Skeleton lone({body::Node{"HumanoidRoot", -1, body::NodeKind::kJoint, {}, {}, 0}}, {},
                            {0, -1, 0}, 1000.0);
  try {
    const PoseParameters parameters(lone);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no joint 'vl5'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace syncap::fitting
