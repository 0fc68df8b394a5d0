// The skinned human driven by the real captured motion (../shared/data/motion): the retargeter
// of the ellipsoid body drives the subject's own skeleton (MakeHuman's A-pose rest, its own bone
// lengths), and the skin follows.
#include <gtest/gtest.h>

#include <algorithm>

#include "body/bvh.hpp"
#include "body/hanim_model.hpp"
#include "body/retarget.hpp"
#include "body_source.hpp"
#include "scenario.hpp"
#include "skinned_body.hpp"
#include "syncap_test_data.hpp"

namespace syncap::sim {
namespace {

// Over the whole clip, for every subject: the feet meet the floor (the lowest skin point within
// a few centimetres of z = 0: grounding puts the stance ankle at the rest figure's height), the
// bones keep the subject's lengths, and the skin stays within the subject's reach of its root.
TEST(SkinnedBodyData, TheRealMotionMovesEverySubjectsSkinOnTheFloor) {
  SYNCAP_REQUIRE_DATA(bvh_file, "motion/mixamo-free.bvh");
  const SkinnedHumanAsset asset = load_skinned_human(default_skinned_human_file());
  const body::Bvh bvh = body::load_bvh(bvh_file);
  for (const char* name : {"short-female", "average-male", "tall-male", "heavy-male"}) {
    const SkinnedSubject subject = make_subject(asset, name);
    body::RetargetOptions options;
    options.loop = true;
    options.align_legs = true;
    const body::BvhRetargeter retargeter(subject.skeleton, bvh, options);
    const auto& k = subject.skeleton;
    const int knee = k.at("l_knee"), ankle = k.at("l_ankle");
    double lowest_min = 1e9, lowest_max = -1e9;
    for (double t = 0; t < retargeter.duration_s(); t += 0.1) {
      const body::Pose pose = retargeter.pose_at(t);
      const Mesh mesh = pose_subject(subject, pose);
      double lowest = 1e9, reach = 0;
      for (const auto& v : mesh.vertices_mm) {
        lowest = std::min(lowest, v.z());
        reach = std::max(reach, (v - pose.root_mm).norm());
      }
      lowest_min = std::min(lowest_min, lowest);
      lowest_max = std::max(lowest_max, lowest);
      EXPECT_LT(reach, subject.height_mm) << name << " t " << t;
      const auto p = body::node_positions(k, pose);
      EXPECT_NEAR((p[size_t(ankle)] - p[size_t(knee)]).norm(), k.bone_length_mm(ankle), 1e-6);
    }
    RecordProperty(std::string(name) + "_lowest_skin_mm",
                   std::to_string(lowest_min) + ".." + std::to_string(lowest_max));
    EXPECT_GT(lowest_min, -40) << name;
    EXPECT_LT(lowest_max, 120) << name;
    std::cout << name << ": height " << subject.height_mm << " mm, lowest skin point " << lowest_min
              << " .. " << lowest_max << " mm over the clip\n";
  }
}

// A scenario's person of model mesh is the subject's posed skin with the subject's joints (the
// truth), and no ellipsoids.
TEST(SkinnedBodyData, AMeshPersonGivesItsSkinAndItsOwnJoints) {
  SYNCAP_REQUIRE_DATA(bvh_file, "motion/mixamo-free.bvh");
  Scenario sc = parse_scenario(R"(
cameras: {count: 2}
phases:
  - {type: person, frames: 3, bvh: /dev/null, model: mesh, subject: short-female}
)",
                               "mesh.yaml");
  sc.phases[0].person.bvh = bvh_file;
  const BodySource body = open_bvh_body(sc.phases[0].person, sc);
  const BodyFrame frame = body(0.5);
  EXPECT_TRUE(frame.ellipsoids.empty());
  EXPECT_EQ(frame.subject, "short-female");
  EXPECT_EQ(frame.mesh.triangles.size(), 26756u);
  ASSERT_EQ(frame.joints.size(), body::hanim_skeleton().size());
  const SkinnedSubject subject =
      make_subject(load_skinned_human(default_skinned_human_file()), "short-female");
  auto joint = [&](const std::string& name) {
    for (const auto& [n, p] : frame.joints)
      if (n == name) return p;
    return Eigen::Vector3d(Eigen::Vector3d::Constant(1e9));
  };
  // The subject's own thigh, not the thesis figure's.
  const double thigh = (joint("l_knee") - joint("l_hip")).norm();
  EXPECT_NEAR(thigh, subject.skeleton.bone_length_mm(subject.skeleton.at("l_knee")), 1e-6);
  EXPECT_LT(thigh, 380);  // the thesis figure's is 386 mm
  sc.phases[0].person.subject = "giant";
  try {
    open_bvh_body(sc.phases[0].person, sc);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.yaml: person.subject:"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace syncap::sim
