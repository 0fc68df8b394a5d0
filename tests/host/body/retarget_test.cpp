// Driving the thesis skeleton from small hand-written BVH files: name mapping across schemes,
// rest-pose alignment, constant bone lengths, axes and units, sampling, placement.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "body/hanim_model.hpp"
#include "body/retarget.hpp"
#include "synthetic_bvh.hpp"

namespace syncap::body {
namespace {

using test::JointRow;
using test::SyntheticFrame;

BvhRetargeter retarget(const std::vector<JointRow>& rows, const std::vector<SyntheticFrame>& frames,
                       RetargetOptions options = {}, bool z_up = false, double scale = 1.0) {
  if (z_up) options.up = BvhUpAxis::kZ;
  return BvhRetargeter(hanim_skeleton(),
                       parse_bvh(test::synthetic_bvh(rows, frames, z_up, scale), "synthetic.bvh"),
                       options);
}

Eigen::Vector3d at(const BvhRetargeter& r, const std::vector<Eigen::Vector3d>& p,
                   const char* name) {
  return p[static_cast<std::size_t>(r.skeleton().at(name))];
}

// A walk-like frame with every joint turned a little, reproducible from the seed.
SyntheticFrame random_frame(const std::vector<JointRow>& rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-60, 60);
  SyntheticFrame f(rows);
  f.root(angle(rng), 95 + angle(rng) / 10, angle(rng));
  for (const JointRow& row : rows) f.rotate(row.name, angle(rng), angle(rng), angle(rng));
  return f;
}

std::string mapped_to(const BvhRetargeter& r, const char* ours) {
  const int b = r.mapping().bvh_joint[static_cast<std::size_t>(r.skeleton().at(ours))];
  return b < 0 ? "" : r.bvh().joints[static_cast<std::size_t>(b)].name;
}

TEST(JointMapping, NormalizesNames) {
  EXPECT_EQ(normalized_joint_name("mixamorig:LeftUpLeg"), "leftupleg");
  EXPECT_EQ(normalized_joint_name("mixamorig1:Hips"), "hips");
  EXPECT_EQ(normalized_joint_name("mixamorig_LeftHand"), "lefthand");
  EXPECT_EQ(normalized_joint_name("Bip01 L Thigh"), "bip01lthigh");
  EXPECT_EQ(normalized_joint_name("thigh.L"), "thighl");
}

TEST(JointMapping, MixamoNames) {
  const auto rows = test::mixamo_rows();
  const BvhRetargeter r = retarget(rows, {SyntheticFrame(rows)});
  EXPECT_EQ(mapped_to(r, "HumanoidRoot"), "mixamorig:Hips");
  EXPECT_EQ(mapped_to(r, "l_hip"), "mixamorig:LeftUpLeg");
  EXPECT_EQ(mapped_to(r, "l_knee"), "mixamorig:LeftLeg");
  EXPECT_EQ(mapped_to(r, "r_ankle"), "mixamorig:RightFoot");
  EXPECT_EQ(mapped_to(r, "r_metatarsal"), "mixamorig:RightToeBase");
  EXPECT_EQ(mapped_to(r, "l_sternoclavicular"), "mixamorig:LeftShoulder");
  EXPECT_EQ(mapped_to(r, "l_shoulder"), "mixamorig:LeftArm");
  EXPECT_EQ(mapped_to(r, "r_elbow"), "mixamorig:RightForeArm");
  EXPECT_EQ(mapped_to(r, "r_wrist"), "mixamorig:RightHand");
  EXPECT_EQ(mapped_to(r, "skullbase"), "mixamorig:Head");
  // The spine by relative height; the joint carrying the clavicles onto vt1.
  EXPECT_EQ(mapped_to(r, "vt1"), "mixamorig:Spine2");
  int spine = 0;
  for (int b : r.mapping().bvh_joint)
    spine += b >= 0 &&
             r.bvh().joints[static_cast<std::size_t>(b)].name.find("Spine") != std::string::npos;
  EXPECT_EQ(spine, 3);
  EXPECT_EQ(mapped_to(r, "vc7").empty() + mapped_to(r, "vc6").empty() +
                mapped_to(r, "vc5").empty() + mapped_to(r, "vc4").empty() +
                mapped_to(r, "vc3").empty() + mapped_to(r, "vc2").empty() +
                mapped_to(r, "vc1").empty(),
            6)
      << "the neck on one cervical joint";
}

TEST(JointMapping, CmuNames) {
  const auto rows = test::cmu_rows();
  const BvhRetargeter r = retarget(rows, {SyntheticFrame(rows)});
  EXPECT_EQ(mapped_to(r, "l_hip"), "LeftUpLeg");  // not LHipJoint
  EXPECT_EQ(mapped_to(r, "r_knee"), "RightLeg");
  EXPECT_EQ(mapped_to(r, "l_sternoclavicular"), "LeftShoulder");
  EXPECT_EQ(mapped_to(r, "l_shoulder"), "LeftArm");
  EXPECT_EQ(mapped_to(r, "l_thumb1"), "LThumb");
  EXPECT_EQ(mapped_to(r, "vt1"), "Spine1");  // CMU's Spine1 carries the arms
  EXPECT_EQ(mapped_to(r, "skullbase"), "Head");
}

TEST(JointMapping, MaxStyleLeftShoulderIsTheUpperArm) {
  // 3ds Max: LeftCollar (clavicle) -> LeftShoulder (upper arm) -> LeftElbow -> LeftWrist.
  std::vector<JointRow> rows = test::cmu_rows();
  for (JointRow& row : rows) {
    for (const auto& [from, to] : {std::pair{"Shoulder", "Collar"}, std::pair{"ForeArm", "Elbow"},
                                   std::pair{"Arm", "Shoulder"}, std::pair{"Hand", "Wrist"}}) {
      for (std::string* s : {&row.name, &row.parent}) {
        const std::size_t at = s->find(from);
        if (at != std::string::npos && s->find("Index") == std::string::npos &&
            (s->substr(0, 4) == "Left" || s->substr(0, 5) == "Right") &&
            s->size() == at + std::string(from).size()) {
          s->replace(at, std::string(from).size(), to);
          break;
        }
      }
    }
  }
  const BvhRetargeter r = retarget(rows, {SyntheticFrame(rows)});
  EXPECT_EQ(mapped_to(r, "l_sternoclavicular"), "LeftCollar");
  EXPECT_EQ(mapped_to(r, "l_shoulder"), "LeftShoulder");
  EXPECT_EQ(mapped_to(r, "l_elbow"), "LeftElbow");
  EXPECT_EQ(mapped_to(r, "l_wrist"), "LeftWrist");
}

TEST(JointMapping, MissingRequiredJointsAreNamed) {
  std::vector<JointRow> rows;
  for (const JointRow& row : test::mixamo_rows("")) {
    if (row.name.find("Leg") == std::string::npos && row.name.find("Foot") == std::string::npos &&
        row.name.find("Toe") == std::string::npos) {
      rows.push_back(row);
    }
  }
  try {
    retarget(rows, {SyntheticFrame(rows)});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("synthetic.bvh: ", 0), 0u) << what;
    for (const char* joint : {"l_hip", "r_hip", "l_knee", "r_knee", "l_ankle", "r_ankle"}) {
      EXPECT_NE(what.find(joint), std::string::npos) << what;
    }
    EXPECT_EQ(what.find("l_wrist"), std::string::npos) << what;
  }
}

TEST(Retarget, TPoseRestFrameGivesOurBonesInItsPosture) {
  const auto rows = test::mixamo_rows();
  const BvhRetargeter r = retarget(rows, {SyntheticFrame(rows).root(0, 98, 0)});
  const auto p = node_positions(r.skeleton(), r.pose_at(0));
  const double arm = r.skeleton().bone_length_mm(r.skeleton().at("l_elbow")) +
                     r.skeleton().bone_length_mm(r.skeleton().at("l_wrist"));
  // Arms straight out sideways (our arms hang at rest; the BVH's rest is a T-pose).
  EXPECT_LT((at(r, p, "l_wrist") - at(r, p, "l_shoulder") - Eigen::Vector3d(arm, 0, 0)).norm(),
            1e-9);
  EXPECT_LT((at(r, p, "r_wrist") - at(r, p, "r_shoulder") + Eigen::Vector3d(arm, 0, 0)).norm(),
            1e-9);
  // Legs and trunk as at rest: our pelvis, not the BVH's.
  const Pose rest = Pose::rest(r.skeleton());
  const auto q = node_positions(r.skeleton(), rest);
  for (const char* name : {"l_hip", "l_knee", "l_ankle", "r_metatarsal", "vt1", "skullbase"}) {
    EXPECT_LT(
        (at(r, p, name) - at(r, p, "HumanoidRoot") - (at(r, q, name) - at(r, q, "HumanoidRoot")))
            .norm(),
        1e-9)
        << name;
  }
  // Grounded: the ankles as high above the floor as at rest.
  EXPECT_NEAR(at(r, p, "l_ankle").z(), at(r, q, "l_ankle").z(), 1e-9);
}

// A rest figure whose left leg stands 8 degrees out (MakeHuman's stand apart) with its foot flat:
// with align_legs the BVH's straight rest legs hang straight down and the foot stays flat;
// without, the leg keeps its spread.
TEST(Retarget, AlignLegsStraightensARestLegThatStandsApart) {
  const Skeleton thesis = hanim_skeleton();
  std::vector<Eigen::Vector3d> rest;
  for (const Node& n : thesis.nodes()) rest.push_back(n.rest_mm);
  const int hip = thesis.at("l_hip"), knee = thesis.at("l_knee"), ankle = thesis.at("l_ankle");
  const Eigen::AngleAxisd out(-8.0 * std::numbers::pi / 180, Eigen::Vector3d::UnitY());  // to +X
  const Eigen::Vector3d ankle_shift =
      out * (rest[size_t(ankle)] - rest[size_t(hip)]) - (rest[size_t(ankle)] - rest[size_t(hip)]);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (int(i) == knee) rest[i] = rest[size_t(hip)] + out * (rest[i] - rest[size_t(hip)]);
    if (int(i) == ankle || thesis.is_ancestor(ankle, int(i))) rest[i] += ankle_shift;
  }
  const Skeleton apart = thesis.with_rest(rest, thesis.rest_root_height_mm());
  const auto rows = test::mixamo_rows();
  const Bvh bvh = parse_bvh(
      test::synthetic_bvh(rows, {SyntheticFrame(rows).root(0, 98, 0)}, false, 1.0), "t.bvh");
  for (bool align : {true, false}) {
    RetargetOptions options;
    options.align_legs = align;
    const BvhRetargeter r(apart, bvh, options);
    const auto p = node_positions(apart, r.pose_at(0));
    const Eigen::Vector3d leg = p[size_t(ankle)] - p[size_t(hip)];
    const Eigen::Vector3d foot = at(r, p, "l_forefoot_tip") - p[size_t(ankle)];
    const Eigen::Vector3d rest_foot =
        rest[size_t(apart.at("l_forefoot_tip"))] - rest[size_t(ankle)];
    if (align) {
      EXPECT_NEAR(leg.x(), 0.0, 1e-6) << "the leg hangs straight";
      EXPECT_LT((foot - rest_foot).norm(), 1e-6) << "the foot stays flat";
    } else {
      EXPECT_GT(leg.x(), 40.0) << "the leg keeps its spread";
    }
  }
}

TEST(Retarget, BoneLengthsStayOursUnderAnyMotion) {
  for (const auto& rows : {test::mixamo_rows(), test::cmu_rows()}) {
    std::vector<SyntheticFrame> frames;
    for (unsigned k = 0; k < 10; ++k) frames.push_back(random_frame(rows, k + 1));
    const BvhRetargeter r = retarget(rows, frames);
    const Skeleton& s = r.skeleton();
    for (double t = 0; t <= r.duration_s(); t += 0.013) {
      const auto p = node_positions(s, r.pose_at(t));
      for (std::size_t i = 1; i < s.size(); ++i) {
        const auto parent = static_cast<std::size_t>(s.nodes()[i].parent);
        EXPECT_NEAR((p[i] - p[parent]).norm(), s.bone_length_mm(static_cast<int>(i)), 1e-9);
      }
    }
  }
}

TEST(Retarget, KneeBendsBackwardAndRootTurnsAboutUp) {
  const auto rows = test::mixamo_rows();
  // BVH: the left knee turned +90 degrees about x: the shank (0, -1, 0) goes to (0, 0, -1),
  // backwards for a figure facing +Z. Ours faces -Y, so backwards is +Y.
  const BvhRetargeter knee =
      retarget(rows, {SyntheticFrame(rows).root(0, 98, 0).rotate("mixamorig:LeftLeg", 0, 0, 90)});
  auto p = node_positions(knee.skeleton(), knee.pose_at(0));
  const double shank = knee.skeleton().bone_length_mm(knee.skeleton().at("l_ankle"));
  EXPECT_LT((at(knee, p, "l_ankle") - at(knee, p, "l_knee") - Eigen::Vector3d(0, shank, 0)).norm(),
            1e-9);
  // The root turned 90 degrees about the BVH's up (Y): the figure's left, +X, goes to -Z in the
  // BVH, +Y in ours; its front, +Z, goes to +X in both: the figure now faces +X.
  const BvhRetargeter yaw =
      retarget(rows, {SyntheticFrame(rows).root(0, 98, 0).rotate("mixamorig:Hips", 0, 90, 0)});
  p = node_positions(yaw.skeleton(), yaw.pose_at(0));
  const Eigen::Vector3d across = at(yaw, p, "l_hip") - at(yaw, p, "r_hip");
  EXPECT_LT((across.normalized() - Eigen::Vector3d(0, 1, 0)).norm(), 1e-9);
  EXPECT_GT(at(yaw, p, "l_forefoot_tip").x(), at(yaw, p, "l_ankle").x() + 100);
}

TEST(Retarget, SameMotionWrittenZUpOrInMetresGivesTheSamePoses) {
  const auto rows = test::mixamo_rows();
  std::vector<SyntheticFrame> frames;
  for (unsigned k = 0; k < 4; ++k) frames.push_back(random_frame(rows, 40 + k));
  const BvhRetargeter y_up = retarget(rows, frames);
  const BvhRetargeter z_up = retarget(rows, frames, {}, true);
  const BvhRetargeter metres = retarget(rows, frames, {}, false, 0.01);
  EXPECT_EQ(y_up.unit_mm(), 10);
  EXPECT_EQ(z_up.unit_mm(), 10);
  EXPECT_EQ(metres.unit_mm(), 1000);
  for (double t : {0.0, 0.05, 0.1}) {
    const auto a = node_positions(y_up.skeleton(), y_up.pose_at(t));
    const auto b = node_positions(z_up.skeleton(), z_up.pose_at(t));
    const auto c = node_positions(metres.skeleton(), metres.pose_at(t));
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_LT((a[i] - b[i]).norm(), 1e-6) << i;
      EXPECT_LT((a[i] - c[i]).norm(), 1e-6) << i;
    }
  }
}

TEST(Retarget, RootPathInFileUnitsWhenAsked) {
  const auto rows = test::mixamo_rows();
  const std::vector<SyntheticFrame> frames = {SyntheticFrame(rows).root(0, 98, 0),
                                              SyntheticFrame(rows).root(0, 98, 150)};
  RetargetOptions metric;
  metric.proportional_root = false;
  const BvhRetargeter r = retarget(rows, frames, metric);
  EXPECT_EQ(r.root_scale(), 10);
  // 150 cm forward (+Z in the BVH) is 1500 mm towards -Y in ours.
  EXPECT_NEAR(
      (r.pose_at(0.04).root_mm - r.pose_at(0).root_mm - Eigen::Vector3d(0, -1500, 0)).norm(), 0,
      1e-9);
  const BvhRetargeter proportional = retarget(rows, frames);
  // Our leg (thigh 386.32 + shank 406.34 mm) over the BVH's (LeftLeg and LeftFoot offsets).
  const Skeleton& s = proportional.skeleton();
  const double ours = s.bone_length_mm(s.at("l_knee")) + s.bone_length_mm(s.at("l_ankle"));
  EXPECT_NEAR(ours, 792.6629, 1e-4);
  EXPECT_NEAR(proportional.root_scale(), ours / (std::hypot(40, 2) + std::hypot(42, 3)), 1e-12);
}

TEST(Retarget, SamplingAtFrameTimesGivesTheFrames) {
  const auto rows = test::mixamo_rows();
  std::vector<SyntheticFrame> frames;
  for (unsigned k = 0; k < 5; ++k) frames.push_back(random_frame(rows, 70 + k));
  const BvhRetargeter r = retarget(rows, frames);
  for (int k = 0; k < 5; ++k) {
    const Pose sampled = r.pose_at(k * r.bvh().frame_time_s);
    const Pose frame = r.pose_at_frame(k);
    EXPECT_LT((sampled.root_mm - frame.root_mm).norm(), 1e-9);
    for (std::size_t i = 0; i < frame.orientation.size(); ++i) {
      EXPECT_NEAR(sampled.orientation[i].angularDistance(frame.orientation[i]), 0, 1e-9);
    }
  }
  // Half way: the root half way (the hip centre moves linearly only with the pelvis still).
  const std::vector<SyntheticFrame> slide = {SyntheticFrame(rows).root(0, 98, 0),
                                             SyntheticFrame(rows).root(20, 98, 40)};
  const BvhRetargeter s = retarget(rows, slide);
  EXPECT_LT(
      (s.pose_at(0.02).root_mm - 0.5 * (s.pose_at_frame(0).root_mm + s.pose_at_frame(1).root_mm))
          .norm(),
      1e-9);
}

TEST(Retarget, LoopWrapsTime) {
  const auto rows = test::mixamo_rows();
  std::vector<SyntheticFrame> frames;
  for (unsigned k = 0; k < 4; ++k) frames.push_back(random_frame(rows, 90 + k));
  RetargetOptions loop;
  loop.loop = true;
  const BvhRetargeter r = retarget(rows, frames, loop);
  const Pose a = r.pose_at(0.05);
  const Pose b = r.pose_at(0.05 + 3 * r.duration_s());
  EXPECT_LT((a.root_mm - b.root_mm).norm(), 1e-9);
}

TEST(Retarget, PlacedInsideACaptureVolume) {
  const auto rows = test::mixamo_rows();
  // A 6 m walk along the BVH's +Z, offset 10 m sideways.
  std::vector<SyntheticFrame> frames;
  for (int k = 0; k <= 10; ++k) frames.push_back(SyntheticFrame(rows).root(1000, 98, 60.0 * k));
  RetargetOptions options;
  options.volume =
      CaptureVolume{Eigen::Vector3d(-1000, -1000, 50), Eigen::Vector3d(1000, 1000, 2050)};
  const BvhRetargeter r = retarget(rows, frames, options);
  EXPECT_LT(r.horizontal_scale(), 0.3);
  Eigen::Vector2d low(1e9, 1e9), high(-1e9, -1e9);
  double lowest_ankle = 1e9;
  for (int k = 0; k <= 10; ++k) {
    const Pose pose = r.pose_at_frame(k);
    low = low.cwiseMin(pose.root_mm.head<2>());
    high = high.cwiseMax(pose.root_mm.head<2>());
    lowest_ankle = std::min(lowest_ankle, at(r, node_positions(r.skeleton(), pose), "l_ankle").z());
  }
  EXPECT_NEAR(low.y(), -700, 1e-6);  // 300 mm margin from the walls
  EXPECT_NEAR(high.y(), 700, 1e-6);
  EXPECT_NEAR(low.x() + high.x(), 0, 1e-6);  // centred
  const Skeleton s = hanim_skeleton();
  EXPECT_NEAR(lowest_ankle, 50 + s.rest_root_height_mm() + s.node(s.at("l_ankle")).rest_mm.z(),
              1e-6);

  options.volume = CaptureVolume{Eigen::Vector3d(-200, -200, 0), Eigen::Vector3d(200, 200, 2000)};
  EXPECT_THROW(retarget(rows, frames, options), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::body
