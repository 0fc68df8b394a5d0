// The thesis body model: rest positions of Tables 5.1-5.2, bones that keep their lengths under
// any pose, ellipsoids along their bones.
#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <set>

#include "body/hanim_model.hpp"
#include "body/pose.hpp"

namespace syncap::body {
namespace {

constexpr double kExact = 1e-9;  // mm: what summing a chain of rest offsets may lose

Eigen::Vector3d thesis_frame(const Eigen::Vector3d& world) {
  return hanim_to_world().transpose() * world;
}

std::vector<Eigen::Quaterniond> random_rotations(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Eigen::Quaterniond> q;
  for (std::size_t i = 0; i < n; ++i)
    q.emplace_back(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)).normalized());
  return q;
}

TEST(HanimSkeleton, HasTheJointsOfTables51And52InOrder) {
  const Skeleton s = hanim_skeleton();
  int joints = 0;
  std::set<std::string> names;
  for (const Node& n : s.nodes()) {
    EXPECT_TRUE(names.insert(n.name).second) << n.name;
    if (n.kind != NodeKind::kJoint) continue;
    // Table 5.1 rows are lines 4651-4714, Table 5.2 rows 4719-4742, one joint per line.
    const int expected_line = joints < 64 ? 4651 + joints : 4719 + (joints - 64);
    EXPECT_EQ(n.source_line, expected_line) << n.name;
    ++joints;
  }
  EXPECT_EQ(joints, 88);
  EXPECT_EQ(s.size(), 93u);  // and five end sites
  EXPECT_EQ(s.segments().size(), 21u);
  EXPECT_EQ(s.node(0).name, "HumanoidRoot");
  EXPECT_EQ(s.node(s.node(s.at("l_sternoclavicular")).parent).name, "vt1");
  EXPECT_EQ(s.node(s.node(s.at("skullbase")).parent).name, "vc1");
  EXPECT_EQ(s.node(s.node(s.at("l_index1")).parent).name, "l_index0");
  EXPECT_EQ(s.node(s.node(s.at("l_thumb1")).parent).name, "l_wrist");
}

TEST(HanimSkeleton, RestPoseReproducesTheThesisTables) {
  const Skeleton s = hanim_skeleton();
  // A few rows copied by hand from thesis.txt (line: name x y z).
  struct Row {
    const char* name;
    double x, y, z;
  };
  const Row rows[] = {
      {"sacroiliac", 0, -11.353028, 20.271},                    // 4653
      {"l_ankle", 102.797997, -975.372833, -33.514},            // 4656
      {"r_metatarsal", -114.680993, -1036.507834, 130.149002},  // 4665
      {"vt1", 0, 334.867065, 1.567},                            // 4682
      {"skullbase", 0, 600.25708, 18.445},                      // 4690
      {"l_elbow", 177.399979, 104.25044, -12.000002},           // 4694
      {"r_acromioclavicular", -159.599991, 402.256958, 48},     // 4720
      {"r_pinky3", -164.23198, -297.639017, -33.082003},        // 4742
  };
  for (const Row& r : rows) {
    EXPECT_EQ(s.node(s.at(r.name)).source_mm, Eigen::Vector3d(r.x, r.y, r.z)) << r.name;
  }
  const Pose rest = Pose::rest(s);
  const auto p = node_positions(s, rest);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Node& n = s.nodes()[i];
    EXPECT_EQ(n.rest_mm, hanim_to_world() * n.source_mm) << n.name;  // exact: a permutation
    const Eigen::Vector3d back = thesis_frame(p[i] - rest.root_mm);
    EXPECT_LT((back - n.source_mm).norm(), kExact) << n.name;
  }
}

TEST(HanimSkeleton, RestFigureStandsOnTheFloorFacingMinusY) {
  const Skeleton s = hanim_skeleton();
  const BodyFrame f = body_frame(s, Pose::rest(s));
  const auto z = [&](const char* name) {
    return f.positions_mm[static_cast<std::size_t>(s.at(name))].z();
  };
  EXPECT_DOUBLE_EQ(s.rest_root_height_mm(), 1060.0);
  EXPECT_NEAR(z("l_ankle"), 84.627167, 1e-9);
  EXPECT_NEAR(z("skull_tip"), 1820.25708, 1e-9);  // the figure's height
  double lowest = 1e9;
  for (const Ellipsoid& e : f.ellipsoids) lowest = std::min(lowest, e.lowest_z_mm());
  EXPECT_NEAR(lowest, 0.0, 2.0);  // the soles
  // Toes in front (-Y), the left hip at +X.
  EXPECT_LT(f.positions_mm[static_cast<std::size_t>(s.at("l_forefoot_tip"))].y(), -150);
  EXPECT_GT(f.positions_mm[static_cast<std::size_t>(s.at("l_hip"))].x(), 100);
}

TEST(HanimSkeleton, UpperArmMatchesTable54) {
  // Table 5.4 (lines 4786-4800): "Transforml elbow, Parent: lshoulder, Trans: 297.30657,
  // Width: 60".
  const Skeleton s = hanim_skeleton();
  EXPECT_NEAR(s.bone_length_mm(s.at("l_elbow")), 297.30657, 1e-5);
  EXPECT_NEAR(s.bone_length_mm(s.at("r_elbow")), 297.30657, 1e-5);
  for (const Segment& seg : s.segments()) {
    if (seg.name == "l_upperarm") {
      EXPECT_EQ(seg.radii_mm.tail<2>(), Eigen::Vector2d(60, 60));
    }
  }
}

TEST(Pose, BoneLengthsStayUnderAnyPose) {
  const Skeleton s = hanim_skeleton();
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Pose pose = Pose::from_local(s, Eigen::Vector3d(seed * 100.0, -50, 900),
                                       random_rotations(s.size(), seed));
    const auto p = node_positions(s, pose);
    for (std::size_t i = 1; i < s.size(); ++i) {
      const auto parent = static_cast<std::size_t>(s.nodes()[i].parent);
      EXPECT_NEAR((p[i] - p[parent]).norm(), s.bone_length_mm(static_cast<int>(i)), kExact)
          << s.nodes()[i].name << " seed " << seed;
    }
  }
}

TEST(Pose, FromIdentityLocalRotationsIsTheRestPose) {
  const Skeleton s = hanim_skeleton();
  const Pose rest = Pose::rest(s);
  const Pose local = Pose::from_local(
      s, rest.root_mm, std::vector<Eigen::Quaterniond>(s.size(), Eigen::Quaterniond::Identity()));
  EXPECT_EQ(node_positions(s, local), node_positions(s, rest));
}

TEST(Pose, EllipsoidLongAxesAlignWithTheirBones) {
  const Skeleton s = hanim_skeleton();
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Pose pose =
        Pose::from_local(s, Eigen::Vector3d::Zero(), random_rotations(s.size(), seed));
    const BodyFrame f = body_frame(s, pose);
    ASSERT_EQ(f.ellipsoids.size(), s.segments().size());
    for (std::size_t k = 0; k < f.ellipsoids.size(); ++k) {
      const Segment& seg = s.segments()[k];
      const Ellipsoid& e = f.ellipsoids[k];
      const Eigen::Vector3d a = f.positions_mm[static_cast<std::size_t>(seg.from)];
      const Eigen::Vector3d b = f.positions_mm[static_cast<std::size_t>(seg.to)];
      EXPECT_LT((e.centre_mm - 0.5 * (a + b)).norm(), kExact) << seg.name;
      EXPECT_LT((e.axes.col(0) - (b - a).normalized()).norm(), 1e-9) << seg.name;
      EXPECT_LT((e.axes.transpose() * e.axes - Eigen::Matrix3d::Identity()).norm(), 1e-9);
      EXPECT_NEAR(e.axes.determinant(), 1.0, 1e-9);
      EXPECT_EQ(e.radii_mm, seg.radii_mm);
    }
  }
}

TEST(Pose, RestEllipsoidsReachBothEndsOfTheirBones) {
  const Skeleton s = hanim_skeleton();
  for (const Segment& seg : s.segments()) {
    const double length = (s.node(seg.to).rest_mm - s.node(seg.from).rest_mm).norm();
    EXPECT_GE(seg.radii_mm[0], 0.5 * length) << seg.name;
    EXPECT_LT(seg.radii_mm[0], 0.5 * length + 70) << seg.name;  // overlap, not more
  }
}

TEST(Ellipsoid, LowestPointOfATurnedEllipsoid) {
  Ellipsoid e;
  e.centre_mm = Eigen::Vector3d(0, 0, 100);
  e.radii_mm = Eigen::Vector3d(50, 20, 10);
  EXPECT_DOUBLE_EQ(e.lowest_z_mm(), 90);
  e.axes = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NEAR(e.lowest_z_mm(), 50, 1e-12);  // the long axis now vertical
}

}  // namespace
}  // namespace syncap::body
