// The BVH export: the file's layout (hierarchy, channels, Y up in metres, a row per frame), the
// Euler angles that rebuild each rotation, and the input it refuses, each named.
#include "io/bvh_writer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "export_test_paths.hpp"
#include "io/export_error.hpp"

namespace syncap::io {
namespace {

using testing::fresh_path;

Eigen::Matrix3d zxy(const Eigen::Vector3d& a) {
  return (Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

// A root with a leg of two joints: hip 100 mm left and 50 mm down of the root, knee 400 below.
BvhMotion leg(int frames) {
  BvhMotion m;
  m.joints = {{"root", -1, {0, 0, 0}, Eigen::Vector3d::Zero()},
              {"l_hip", 0, {100, 0, -50}, Eigen::Vector3d::Zero()},
              {"l_knee", 1, {0, 0, -400}, {0, -80, -400}}};
  m.rate_hz = 50;
  for (int f = 0; f < frames; ++f)
    m.frames.push_back(
        {{0, 0, 900},
         {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()}});
  return m;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(BvhWriter, TheAnglesRebuildEveryRotation) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-3.1, 3.1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d r =
        Eigen::Quaterniond::UnitRandom().toRotationMatrix() * zxy({angle(rng), 0.1, 0.2});
    EXPECT_LT((zxy(zxy_angles(r)) - r).norm(), 1e-12) << i;
  }
  // At gimbal lock (x = 90 degrees) z and y turn about the same axis: still the same rotation.
  const Eigen::Matrix3d locked = zxy({0.4, M_PI / 2, -0.3});
  EXPECT_LT((zxy(zxy_angles(locked)) - locked).norm(), 1e-9);
}

TEST(BvhWriter, WritesTheHierarchyYUpInMetresAndARowPerFrame) {
  const std::string path = fresh_path(".bvh");
  BvhMotion m = leg(2);
  // Frame 1: the knee bent 90 degrees about the figure's left-right axis (our X, BVH's X).
  m.frames[1].rotations[2] =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  write_bvh(path, m);
  const std::string text = read(path);
  EXPECT_NE(text.find("ROOT root\n{\n  OFFSET 0.000000 0.000000 0.000000\n  CHANNELS 6 Xposition "
                      "Yposition Zposition Zrotation Xrotation Yrotation\n"),
            std::string::npos)
      << text;
  // Our (100, 0, -50) mm is BVH's (0.1, -0.05, 0) m: Z up becomes Y up.
  EXPECT_NE(text.find("  JOINT l_hip\n  {\n    OFFSET 0.100000 -0.050000 0.000000\n"),
            std::string::npos)
      << text;
  // The knee's end site (0, -80, -400) mm: back (our +Y) is BVH's -Z.
  EXPECT_NE(text.find("End Site\n      {\n        OFFSET 0.000000 -0.400000 0.080000\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("MOTION\nFrames: 2\nFrame Time: 0.02\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n0.000000 0.900000 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000 "
                      "0.000000 0.000000 90.000000 0.000000\n"),
            std::string::npos)
      << text;
}

TEST(BvhWriter, RefusesWhatItCannotWriteAndNamesIt) {
  const std::string path = fresh_path(".bvh");
  const auto problem = [&path](const BvhMotion& m) {
    try {
      write_bvh(path, m);
    } catch (const ExportError& e) {
      EXPECT_EQ(e.path(), path);
      return e.problem();
    }
    return std::string("written");
  };
  BvhMotion m = leg(1);
  m.joints[2].name = "l knee";
  EXPECT_NE(problem(m).find("joint 2 'l knee'"), std::string::npos);
  m = leg(1);
  m.joints[2].name = "l_hip";
  EXPECT_NE(problem(m).find("repeated"), std::string::npos);
  m = leg(1);
  m.joints[1].parent = 2;
  EXPECT_NE(problem(m).find("joint 1 'l_hip': its parent comes after it"), std::string::npos);
  m = leg(1);
  m.frames[0].rotations.pop_back();
  EXPECT_EQ(problem(m), "frame 0: 2 rotations for 3 joints");
  m = leg(1);
  m.frames[0].root_mm.x() = NAN;
  EXPECT_EQ(problem(m), "frame 0: root not finite");
  m = leg(0);
  EXPECT_EQ(problem(m), "no frame");
  m = leg(1);
  m.rate_hz = 0;
  EXPECT_EQ(problem(m), "the frame rate is not positive");
  EXPECT_FALSE(std::filesystem::exists(path));  // nothing written for any of them
}

}  // namespace
}  // namespace syncap::io
