// Writes the exports that check_exports.py reads back with independent readers (ezc3d, c3d):
// <dir>/small.{c3d,trc} (3 markers, one with a long label, 50 frames at 100 Hz from frame 1234),
// <dir>/wide.{c3d,trc} (300 markers: LABELS and LABELS2, 4 frames), <dir>/long.c3d (70000
// frames of 2 markers: past the header's 65535), <dir>/leg.bvh (a root and a leg of two joints,
// 10 frames at 50 Hz: the root rising 1 mm and the knee bending 1 degree a frame).
#include <Eigen/Geometry>
#include <cmath>
#include <exception>
#include <iostream>
#include <string>

#include "io/bvh_writer.hpp"
#include "io/c3d_writer.hpp"
#include "io/trc_writer.hpp"
#include "synthetic_trajectories.hpp"

namespace {

void write_both(const std::string& stem, const syncap::tracking::MarkerTrajectories& trajectories) {
  syncap::io::write_c3d(stem + ".c3d", trajectories);
  syncap::io::write_trc(stem + ".trc", trajectories);
}

syncap::io::BvhMotion leg_motion() {
  syncap::io::BvhMotion m;
  m.joints = {{"root", -1, {0, 0, 0}, Eigen::Vector3d::Zero()},
              {"l_hip", 0, {100, 0, -50}, Eigen::Vector3d::Zero()},
              {"l_knee", 1, {0, 0, -400}, {0, -80, -400}}};
  m.rate_hz = 50;
  for (int f = 0; f < 10; ++f) {
    const Eigen::Matrix3d knee =
        Eigen::AngleAxisd(f * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
    m.frames.push_back(
        {{0, 0, 900.0 + f}, {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity(), knee}});
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " <output folder>\n";
    return 2;
  }
  const std::string dir = argv[1];
  using syncap::io::testing::synthetic_trajectories;
  try {
    auto small = synthetic_trajectories(50, 3, 100.0, 1234);
    small.labels[1] = "RigidSetLeftWrist_with_a_long_name";
    write_both(dir + "/small", small);
    write_both(dir + "/wide", synthetic_trajectories(4, 300, 250.0, 0));
    syncap::io::write_c3d(dir + "/long.c3d", synthetic_trajectories(70000, 2, 120.0, 7));
    syncap::io::write_bvh(dir + "/leg.bvh", leg_motion());
  } catch (const std::exception& e) {
    std::cerr << "export failed: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote small, wide, long and leg exports to " << dir << "\n";
  return 0;
}
