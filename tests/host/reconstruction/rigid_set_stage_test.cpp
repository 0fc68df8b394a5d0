// The rigid set stage finds a triangle tool among a frame's tracked markers and gives its pose;
// predictions are no measurements; the JSON line carries the pose.
#include "reconstruction/rigid_set_stage.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "io/frame_json.hpp"

namespace syncap::reconstruction {
namespace {

tracking::RigidSet tool() {
  tracking::RigidSet set;
  set.name = "tool";
  set.markers = {{"a", {0, 0, 0}}, {"b", {120, 0, 0}}, {"c", {0, 70, 0}}};
  return set;
}

pipeline::Marker3d marker(int id, const Eigen::Vector3d& p, bool predicted = false) {
  pipeline::Marker3d m;
  m.id = id;
  m.position = p;
  m.covariance = Eigen::Matrix3d::Identity() * 0.01;
  m.camera_ids = {0, 1, 2};
  m.predicted = predicted;
  return m;
}

TEST(RigidSetStage, FindsTheToolAmongOtherMarkersWithItsPose) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
  const Eigen::Vector3d translation(250, -100, 1200);
  pipeline::FrameWork w;
  w.markers.push_back(marker(1, {-400, 300, 900}));  // another marker
  const auto& set = tool();
  for (std::size_t m = 0; m < set.markers.size(); ++m) {
    w.markers.push_back(
        marker(10 + static_cast<int>(m), rotation * set.markers[m].position_mm + translation));
  }
  w.markers.push_back(marker(2, {500, 500, 500}));
  RigidSetStage stage({set});
  stage.process(w);
  ASSERT_EQ(w.rigid_bodies.size(), 1u);
  const pipeline::RigidBody& b = w.rigid_bodies[0];
  EXPECT_EQ(b.name, "tool");
  ASSERT_TRUE(b.found);
  EXPECT_LT((b.rotation - rotation).norm(), 1e-9);
  EXPECT_LT((b.translation_mm - translation).norm(), 1e-9);
  EXPECT_EQ(b.marker_ids, (std::vector<int>{10, 11, 12}));
  EXPECT_FALSE(b.collinear);
  EXPECT_EQ(stage.summary(), "rigid set tool: found in 1 of 1 frames\n");

  const nlohmann::json line = nlohmann::json::parse(io::frame_line(w, true));
  ASSERT_EQ(line["rigid_sets"].size(), 1u);
  EXPECT_EQ(line["rigid_sets"][0]["name"], "tool");
  EXPECT_NEAR(line["rigid_sets"][0]["translation"][2].get<double>(), 1200, 1e-3);
  EXPECT_EQ(line["rigid_sets"][0]["rotation"].size(), 9u);
}

TEST(RigidSetStage, ThePredictionsOfHiddenMarkersDoNotMakeASet) {
  pipeline::FrameWork w;
  const auto& set = tool();
  for (std::size_t m = 0; m < set.markers.size(); ++m)
    w.markers.push_back(marker(static_cast<int>(m), set.markers[m].position_mm, m == 2));
  RigidSetStage stage({set});
  stage.process(w);
  ASSERT_EQ(w.rigid_bodies.size(), 1u);
  EXPECT_FALSE(w.rigid_bodies[0].found);
  EXPECT_EQ(nlohmann::json::parse(io::frame_line(w, true))["rigid_sets"][0],
            nlohmann::json::parse(R"({"name":"tool","found":false})"));
}

}  // namespace
}  // namespace syncap::reconstruction
