#include "skinned_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "body/hanim_model.hpp"

namespace syncap::sim {
namespace {

const SkinnedHumanAsset& asset() {
  static const SkinnedHumanAsset a = load_skinned_human(default_skinned_human_file());
  return a;
}

// The volume the skin encloses (divergence theorem over its triangles), litres.
double volume_litres(const std::vector<Eigen::Vector3d>& v,
                     const std::vector<Eigen::Vector3i>& triangles) {
  double six_v = 0;
  for (const auto& t : triangles)
    six_v += v[size_t(t.x())].dot(v[size_t(t.y())].cross(v[size_t(t.z())]));
  return std::abs(six_v) / 6.0 * 1e-6;
}

TEST(SkinnedBody, LoadsTheMakeHumanAsset) {
  const SkinnedHumanAsset& a = asset();
  EXPECT_EQ(a.skinned, 13380);
  EXPECT_EQ(a.triangles.size(), 26756u);
  EXPECT_EQ(a.node_places.size(), body::hanim_skeleton().size());
  EXPECT_EQ(a.weights.size(), 13380u);
  EXPECT_EQ(a.subjects.size(), 5u);
}

TEST(SkinnedBody, SubjectsDifferInHeightAndBuild) {
  const SkinnedSubject shorter = make_subject(asset(), "short-female");
  const SkinnedSubject average = make_subject(asset(), "average-male");
  const SkinnedSubject taller = make_subject(asset(), "tall-male");
  const SkinnedSubject heavy = make_subject(asset(), "heavy-male");
  EXPECT_GT(shorter.height_mm, 1450);
  EXPECT_LT(shorter.height_mm, average.height_mm - 100);
  EXPECT_LT(average.height_mm, taller.height_mm - 100);
  EXPECT_LT(taller.height_mm, 2050);
  // An adult man's body is 60-90 litres; the heavy one holds clearly more than the average one.
  const double v_average = volume_litres(average.rest_mm, average.triangles);
  const double v_heavy = volume_litres(heavy.rest_mm, heavy.triangles);
  EXPECT_GT(v_average, 50);
  EXPECT_LT(v_average, 100);
  EXPECT_GT(v_heavy, 1.2 * v_average);
}

TEST(SkinnedBody, JointsLieInsideTheLimbsOnTheRightSides) {
  const SkinnedSubject s = make_subject(asset(), "average-male");
  const auto& k = s.skeleton;
  auto at = [&](const char* n) { return k.node(k.at(n)).rest_mm; };
  EXPECT_GT(at("l_hip").x(), 50);  // +X is the figure's left
  EXPECT_LT(at("r_hip").x(), -50);
  EXPECT_GT(at("l_shoulder").z(), at("l_elbow").z());
  EXPECT_GT(at("l_elbow").z(), at("l_wrist").z());
  EXPECT_GT(at("l_hip").z(), at("l_knee").z() + 300);
  EXPECT_GT(at("l_knee").z(), at("l_ankle").z() + 300);
  EXPECT_GT(at("skull_tip").z(), at("skullbase").z() + 100);
  // The knee's centre is within a knee's radius of the skin, not outside the leg.
  double nearest = 1e9;
  for (const auto& v : s.rest_mm) nearest = std::min(nearest, (v - at("l_knee")).norm());
  EXPECT_GT(nearest, 20);
  EXPECT_LT(nearest, 80);
  // The rest figure stands on the floor.
  double lowest = 1e9;
  for (const auto& v : s.rest_mm) lowest = std::min(lowest, v.z());
  EXPECT_NEAR(lowest + k.rest_root_height_mm(), 0.0, 1e-9);
}

TEST(SkinnedBody, RestPoseGivesTheRestMeshStandingOnTheFloor) {
  const SkinnedSubject s = make_subject(asset(), "heavy-female");
  const body::Pose rest = body::Pose::rest(s.skeleton);
  const Mesh mesh = pose_subject(s, rest);
  ASSERT_EQ(mesh.vertices_mm.size(), s.rest_mm.size());
  for (std::size_t i = 0; i < s.rest_mm.size(); i += 97)
    EXPECT_LT((mesh.vertices_mm[i] - (s.rest_mm[i] + rest.root_mm)).norm(), 1e-3) << i;
  EXPECT_EQ(mesh.texture_mm, s.rest_mm);
  // The normals point out of the body: at the top of the head, up.
  std::size_t top = 0;
  for (std::size_t i = 0; i < s.rest_mm.size(); ++i)
    if (s.rest_mm[i].z() > s.rest_mm[top].z()) top = i;
  EXPECT_GT(mesh.normals[top].z(), 0.9);
}

TEST(SkinnedBody, ABentKneeTurnsTheCalfAboutTheKneeAndLeavesTheThigh) {
  const SkinnedSubject s = make_subject(asset(), "average-male");
  const int knee = s.skeleton.at("l_knee"), hip = s.skeleton.at("l_hip");
  std::vector<Eigen::Quaterniond> local(s.skeleton.size(), Eigen::Quaterniond::Identity());
  local[size_t(knee)] = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d root(0, 0, s.skeleton.rest_root_height_mm());
  const Mesh bent = pose_subject(s, body::Pose::from_local(s.skeleton, root, local));
  const Eigen::Vector3d knee_at = root + s.skeleton.node(knee).rest_mm;
  int calf = 0, thigh = 0;
  for (std::size_t i = 0; i < s.rest_mm.size(); ++i) {
    const SkinWeights& w = s.weights[i];
    if (w.weight[0] < 0.9999f) continue;
    const Eigen::Vector3d rest = s.rest_mm[i] + root;
    if (w.node[0] == knee) {
      ++calf;
      EXPECT_NEAR((bent.vertices_mm[i] - knee_at).norm(), (rest - knee_at).norm(), 0.05);
      EXPECT_GT((bent.vertices_mm[i] - rest).norm(), 1.0) << "a calf vertex did not move";
    } else if (w.node[0] == hip) {
      ++thigh;
      EXPECT_LT((bent.vertices_mm[i] - rest).norm(), 0.05);
    }
  }
  EXPECT_GT(calf, 30);  // the weights blend smoothly: 40 calf and 81 thigh vertices are rigid
  EXPECT_GT(thigh, 30);
}

TEST(SkinnedBody, UnknownSubjectNamesTheKnownOnes) {
  try {
    make_subject(asset(), "giant");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("giant"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("tall-male"), std::string::npos);
  }
}

TEST(SkinnedBody, ABrokenFileIsNamedWithItsLine) {
  const auto file = std::filesystem::temp_directory_path() / "syncap_broken_human.txt";
  std::ofstream(file) << "syncap-skinned-human 1\nvertices 3 skinned 3\n0 0 0\n1 0 0\n0 1 0\n"
                         "triangles 1\n0 1 7\n";
  try {
    load_skinned_human(file);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ":7:"), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace syncap::sim
