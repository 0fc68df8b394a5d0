#include "tracking/rigid_set.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "synthetic_motion.hpp"
#include "tracking/rigid_set_file.hpp"

namespace syncap::tracking {
namespace {

using Eigen::Vector3d;

// An L-frame of 5 markers over ~600 mm, all distances different (no symmetric labelling), its
// frame's origin near the markers' centroid.
RigidSet tool() {
  return {"frame",
          {{"f1", {-250, -150, 0}},
           {"f2", {350, -150, 0}},
           {"f3", {-250, 250, 0}},
           {"f4", {60, -150, 0}},
           {"f5", {0, 60, 90}}},
          3.0};
}

RigidSet wand() {
  return {"wand", {{"w1", {0, 0, 0}}, {"w2", {200, 0, 0}}, {"w3", {500, 0, 0}}}, 3.0};
}

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180 / M_PI;
}

// The set's markers placed by `pose`, with 0.3 mm noise, among 32 random markers; ids = indices.
struct Scene {
  std::vector<PointObservation> points;
  std::vector<TrackId> ids;
};
Scene scene(const RigidSet& set, const Eigen::Isometry3d& pose, std::mt19937& rng) {
  std::normal_distribution<double> noise(0, 0.3);
  std::uniform_real_distribution<double> xy(-800, 800), z(100, 1900);
  Scene s;
  for (int i = 0; i < 32; ++i) s.points.push_back(test::observed({xy(rng), xy(rng), z(rng)}, 0.3));
  for (const RigidMarker& m : set.markers) {
    s.points.insert(
        s.points.begin() + 7 * (&m - set.markers.data()),
        test::observed(pose * m.position_mm + Vector3d(noise(rng), noise(rng), noise(rng)), 0.3));
  }
  for (std::size_t i = 0; i < s.points.size(); ++i) s.ids.push_back(static_cast<TrackId>(i + 1));
  return s;
}

Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  pose.translation() = Vector3d(500 * u(rng), 500 * u(rng), 1000 + 500 * u(rng));
  return pose;
}

TEST(RigidSet, FramePoseWithinHalfMillimetreAndTenthOfDegreeRms) {
  std::mt19937 rng(5);
  RigidSetFinder finder({tool()});
  double worst_mm = 0, worst_deg = 0, sum_mm2 = 0, sum_deg2 = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Isometry3d pose = random_pose(rng);
    const Scene s = scene(tool(), pose, rng);
    const RigidSetPose& found = finder.find(s.points, s.ids)[0];
    ASSERT_TRUE(found.found) << trial;
    EXPECT_EQ(found.points, (std::vector<int>{0, 7, 14, 21, 28}));
    const double mm = (found.translation_mm - pose.translation()).norm();
    const double deg = angle_deg(found.rotation, pose.linear());
    worst_mm = std::max(worst_mm, mm);
    worst_deg = std::max(worst_deg, deg);
    sum_mm2 += mm * mm;
    sum_deg2 += deg * deg;
    EXPECT_FALSE(found.collinear);
  }
  const double rms_mm = std::sqrt(sum_mm2 / 200), rms_deg = std::sqrt(sum_deg2 / 200);
  std::printf("L-frame, 0.3 mm noise, 200 poses: RMS %.3f mm, %.4f deg; worst %.3f mm, %.4f deg\n",
              rms_mm, rms_deg, worst_mm, worst_deg);
  // 0.3 mm per axis on 5 markers ~300 mm from their centroid: ~0.23 mm and ~0.05 deg expected
  EXPECT_LT(rms_mm, 0.5);
  EXPECT_LT(rms_deg, 0.1);
}

TEST(RigidSet, WandIsFoundWithItsLineAndEnds) {
  std::mt19937 rng(6);
  RigidSetFinder finder({wand()});
  double sum_mm2 = 0, sum_deg2 = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Isometry3d pose = random_pose(rng);
    const Scene s = scene(wand(), pose, rng);
    const RigidSetPose& found = finder.find(s.points, s.ids)[0];
    ASSERT_TRUE(found.found) << trial;
    EXPECT_TRUE(found.collinear);
    EXPECT_EQ(found.points, (std::vector<int>{0, 7, 14}));
    const Vector3d axis = found.rotation * Vector3d::UnitX(),
                   truth = pose.linear() * Vector3d::UnitX();
    sum_deg2 += std::pow(std::acos(std::min(1.0, axis.dot(truth))) * 180 / M_PI, 2);
    // the roll is unknown: compare where the wand's markers are, not the full rotation
    for (const RigidMarker& m : wand().markers) {
      sum_mm2 += (found.rotation * m.position_mm + found.translation_mm - pose * m.position_mm)
                     .squaredNorm() /
                 3;
    }
  }
  const double rms_mm = std::sqrt(sum_mm2 / 200), rms_deg = std::sqrt(sum_deg2 / 200);
  std::printf("wand, 0.3 mm noise, 200 poses: RMS marker %.3f mm, axis %.4f deg\n", rms_mm,
              rms_deg);
  EXPECT_LT(rms_mm, 0.5);
  EXPECT_LT(rms_deg, 0.1);
}

TEST(RigidSet, KeepsTheSameTracksAndIgnoresPointsWithoutId) {
  std::mt19937 rng(7);
  RigidSetFinder finder({tool()});
  Scene s = scene(tool(), random_pose(rng), rng);
  const std::vector<TrackId> first = finder.find(s.points, s.ids)[0].ids;
  s.ids[7] = kNoTrack;  // marker t2's point has no track: the set is not found
  EXPECT_FALSE(finder.find(s.points, s.ids)[0].found);
  s.ids[7] = 8;
  EXPECT_EQ(finder.find(s.points, s.ids)[0].ids, first);
}

TEST(RigidSet, NotFoundWhenDistancesDisagree) {
  std::mt19937 rng(8);
  RigidSetFinder finder({tool()});
  Scene s = scene(tool(), random_pose(rng), rng);
  s.points[14].position_mm += Vector3d(10, 0, 0);
  EXPECT_FALSE(finder.find(s.points, s.ids)[0].found);
}

TEST(RigidSetFile, ReadsSets) {
  const auto sets = parse_rigid_sets(
      "rigid_sets:\n"
      "  - name: wand\n"
      "    tolerance_mm: 2\n"
      "    markers:\n"
      "      - {name: a, position: [0, 0, 0]}\n"
      "      - {name: b, position: [200, 0, 0]}\n"
      "      - {name: c, position: [500, 0, 0]}\n",
      "sets.yaml");
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].name, "wand");
  EXPECT_EQ(sets[0].tolerance_mm, 2);
  EXPECT_EQ(sets[0].markers[2].name, "c");
  EXPECT_EQ(sets[0].markers[2].position_mm, Vector3d(500, 0, 0));
  EXPECT_TRUE(is_collinear(sets[0]));
}

std::string error_of(const std::string& text) {
  try {
    parse_rigid_sets(text, "sets.yaml");
  } catch (const TrackingFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RigidSetFile, BadFilesNameFileAndLine) {
  const std::string head = "rigid_sets:\n  - name: wand\n    markers:\n";
  const std::string a = "      - {name: a, position: [0, 0, 0]}\n";
  const std::string b = "      - {name: b, position: [200, 0, 0]}\n";
  EXPECT_EQ(error_of(head + a + b), "sets.yaml:4: set 'wand' needs a list of at least 3 markers");
  EXPECT_EQ(error_of(head + a + b + "      - {name: c, position: [1, x, 0]}\n"),
            "sets.yaml:6: marker 'c' y is not a finite number");
  EXPECT_EQ(error_of(head + a + b + "      - {name: c, position: [1, 0]}\n"),
            "sets.yaml:6: marker 'c': position must be [x, y, z] in mm");
  EXPECT_EQ(error_of(head + a + b + "      - {name: a, position: [900, 0, 0]}\n"),
            "sets.yaml:6: set 'wand': marker name 'a' used twice");
  EXPECT_EQ(error_of(head + a + b + "      - {name: c, position: [1, 0, 0]}\n"),
            "sets.yaml:6: set 'wand': markers 'a' and 'c' closer than twice the tolerance");
  EXPECT_EQ(error_of(head + a + b + "      - {name: c, position: [900, 0, 0], size: 3}\n"),
            "sets.yaml:6: unknown key 'size' in a marker of set 'wand'");
  EXPECT_EQ(error_of("sets: []\n"), "sets.yaml:1: expected a map with the key 'rigid_sets'");
  EXPECT_EQ(error_of("rigid_sets: [\n"), "sets.yaml:2: end of sequence flow not found");
  EXPECT_EQ(error_of("rigid_sets:\n  - markers: []\n"), "sets.yaml:2: a rigid set without a name");
}

TEST(RigidSetFile, UnreadableFileNamed) {
  try {
    read_rigid_sets("/nonexistent/sets.yaml");
    FAIL();
  } catch (const TrackingFileError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/sets.yaml:0: cannot be read");
    EXPECT_EQ(e.path(), "/nonexistent/sets.yaml");
  }
}

}  // namespace
}  // namespace syncap::tracking
