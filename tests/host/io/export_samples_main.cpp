// Writes the exports that check_exports.py reads back with independent readers (ezc3d, c3d):
// <dir>/small.{c3d,trc} (3 markers, one with a long label, 50 frames at 100 Hz from frame 1234),
// <dir>/wide.{c3d,trc} (300 markers: LABELS and LABELS2, 4 frames), <dir>/long.c3d (70000
// frames of 2 markers: past the header's 65535).
#include <exception>
#include <iostream>
#include <string>

#include "io/c3d_writer.hpp"
#include "io/trc_writer.hpp"
#include "synthetic_trajectories.hpp"

namespace {

void write_both(const std::string& stem, const syncap::io::MarkerTrajectories& trajectories) {
  syncap::io::write_c3d(stem + ".c3d", trajectories);
  syncap::io::write_trc(stem + ".trc", trajectories);
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
  } catch (const std::exception& e) {
    std::cerr << "export failed: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote small, wide and long exports to " << dir << "\n";
  return 0;
}
