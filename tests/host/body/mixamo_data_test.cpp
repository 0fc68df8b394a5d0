// The real motion (../shared/data/motion/mixamo-free.bvh, 69 frames of a Mixamo walk): parse
// it, map it, and drive the thesis body through every frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "body/hanim_model.hpp"
#include "body/retarget.hpp"
#include "syncap_test_data.hpp"

namespace syncap::body {
namespace {

constexpr const char* kFootNodes[] = {"l_ankle",      "l_subtalar",     "l_midtarsal",
                                      "l_metatarsal", "l_forefoot_tip", "l_calcaneus_posterior",
                                      "r_ankle",      "r_subtalar",     "r_midtarsal",
                                      "r_metatarsal", "r_forefoot_tip", "r_calcaneus_posterior"};

bool is_foot(const std::string& name) {
  return std::any_of(std::begin(kFootNodes), std::end(kFootNodes),
                     [&](const char* f) { return name == f; });
}

TEST(MixamoMotion, ParsesAndMapsEveryRequiredJoint) {
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  const Bvh bvh = load_bvh(path);
  EXPECT_EQ(bvh.frame_count, 69);
  EXPECT_EQ(bvh.channel_count, 168);
  EXPECT_NEAR(bvh.frame_time_s, 1.0 / 30, 1e-6);
  const BvhRetargeter r(hanim_skeleton(), bvh);
  int mapped = 0;
  for (int b : r.mapping().bvh_joint) mapped += b >= 0;
  for (const std::string& name : required_joints()) {
    EXPECT_GE(r.mapping().bvh_joint[static_cast<std::size_t>(r.skeleton().at(name))], 0) << name;
  }
  EXPECT_EQ(r.unit_mm(), 10);  // Mixamo writes cm
  std::cout << "mixamo: " << bvh.frame_count << " frames, " << r.duration_s() << " s, "
            << bvh.joints.size() << " BVH joints (end sites included), " << mapped
            << " of our joints driven, root scale " << r.root_scale() << " mm per cm\n";
}

TEST(MixamoMotion, DrivesTheBodyThroughEveryFrame) {
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  const BvhRetargeter r(hanim_skeleton(), load_bvh(path));
  const Skeleton& s = r.skeleton();
  const int ankles[] = {s.at("l_ankle"), s.at("r_ankle")};
  const double rest_ankle = s.rest_root_height_mm() + s.node(ankles[0]).rest_mm.z();
  double worst_bone = 0, lowest_ankle = 1e9, tallest = 0, lowest_node = 1e9;
  int upright = 0, lowest_is_foot = 0;
  std::vector<double> frame_lowest;
  for (int k = 0; k < r.bvh().frame_count; ++k) {
    const BodyFrame f = body_frame(s, r.pose_at_frame(k));
    const auto& p = f.positions_mm;
    for (std::size_t i = 1; i < s.size(); ++i) {
      const double length = (p[i] - p[static_cast<std::size_t>(s.nodes()[i].parent)]).norm();
      worst_bone = std::max(worst_bone, std::abs(length - s.bone_length_mm(static_cast<int>(i))));
    }
    for (int a : ankles) lowest_ankle = std::min(lowest_ankle, p[static_cast<std::size_t>(a)].z());
    const auto low = std::min_element(p.begin(), p.end(),
                                      [](const auto& a, const auto& b) { return a.z() < b.z(); });
    lowest_node = std::min(lowest_node, low->z());
    lowest_is_foot += is_foot(s.nodes()[static_cast<std::size_t>(low - p.begin())].name);
    upright += p[static_cast<std::size_t>(s.at("skullbase"))].z() >
               p[static_cast<std::size_t>(s.at("HumanoidRoot"))].z() + 400;
    tallest = std::max(tallest, p[static_cast<std::size_t>(s.at("skull_tip"))].z());
    double sole = 1e9;
    for (const Ellipsoid& e : f.ellipsoids) sole = std::min(sole, e.lowest_z_mm());
    frame_lowest.push_back(sole);
  }
  std::sort(frame_lowest.begin(), frame_lowest.end());
  const double median_sole = frame_lowest[frame_lowest.size() / 2];
  const int frames = r.bvh().frame_count;
  std::cout << "mixamo: worst bone length error " << worst_bone << " mm; lowest ankle "
            << lowest_ankle << " mm (rest " << rest_ankle << "); lowest joint " << lowest_node
            << " mm; lowest point per frame: median " << median_sole << ", min "
            << frame_lowest.front() << ", max " << frame_lowest.back() << " mm; upright " << upright
            << "/" << frames << "; lowest joint on a foot " << lowest_is_foot << "/" << frames
            << "; head top up to " << tallest << " mm\n";

  EXPECT_LT(worst_bone, 1e-9);
  // Feet at the floor: the stance ankle at standing height, the soles touching on most frames,
  // and the lowest joint a foot's, never more than a few cm below the floor (at toe-off our
  // foot, 11% longer than Mixamo's, swings its toes 30 mm into the floor: no IK here).
  EXPECT_NEAR(lowest_ankle, rest_ankle, 1e-6);
  EXPECT_GT(lowest_node, -50);
  EXPECT_LT(std::abs(median_sole), 30);
  EXPECT_GT(frame_lowest.front(), -60);
  EXPECT_EQ(lowest_is_foot, frames);
  EXPECT_GE(upright, frames * 95 / 100);
  EXPECT_GT(tallest, 1700);
  EXPECT_LT(tallest, 1900);
}

TEST(MixamoMotion, WithoutGroundingTheFileFloorAlreadyFits) {
  // The proportional root scale alone (our leg over Mixamo's) puts the stance ankles within a
  // few cm of standing height above the file's own floor.
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  RetargetOptions raw;
  raw.ground = false;
  const BvhRetargeter r(hanim_skeleton(), load_bvh(path), raw);
  const Skeleton& s = r.skeleton();
  double lowest_ankle = 1e9;
  for (int k = 0; k < r.bvh().frame_count; ++k) {
    const auto p = node_positions(s, r.pose_at_frame(k));
    for (const char* a : {"l_ankle", "r_ankle"}) {
      lowest_ankle = std::min(lowest_ankle, p[static_cast<std::size_t>(s.at(a))].z());
    }
  }
  const double rest_ankle = s.rest_root_height_mm() + s.node(s.at("l_ankle")).rest_mm.z();
  std::cout << "mixamo: ungrounded lowest ankle " << lowest_ankle << " mm\n";
  EXPECT_NEAR(lowest_ankle, rest_ankle, 30);
}

TEST(MixamoMotion, PlacedInTheRingScenarioVolume) {
  SYNCAP_REQUIRE_DATA(path, "motion/mixamo-free.bvh");
  RetargetOptions options;
  options.volume = CaptureVolume{};  // -1 .. 1 m, 0 .. 2 m, as hil/scenarios/ring-6cam-person
  const BvhRetargeter r(hanim_skeleton(), load_bvh(path), options);
  for (double t = 0; t <= r.duration_s(); t += 0.01) {
    const Pose pose = r.pose_at(t);
    EXPECT_LE(pose.root_mm.head<2>().cwiseAbs().maxCoeff(), 700 + 1e-6) << t;
  }
  std::cout << "mixamo: in the 2 m volume, horizontal scale " << r.horizontal_scale() << ", offset "
            << r.offset_mm().transpose() << " mm\n";
}

}  // namespace
}  // namespace syncap::body
