#include "io/bvh_writer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <set>

#include "io/atomic_file.hpp"
#include "io/export_error.hpp"

namespace syncap::io {
namespace {

// Our world (X left, Y back, Z up) onto BVH's (X left, Y up, Z front).
Eigen::Matrix3d to_y_up() {
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return m;
}

void check_joints(const std::string& path, const std::vector<BvhJoint>& joints) {
  if (joints.empty()) throw ExportError(path, "no joint");
  std::set<std::string> names;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const BvhJoint& joint = joints[j];
    const std::string which = "joint " + std::to_string(j) + " '" + joint.name + "'";
    if (joint.name.empty() || std::any_of(joint.name.begin(), joint.name.end(),
                                          [](unsigned char c) { return std::isspace(c) != 0; }))
      throw ExportError(path, which + ": a name must be non-empty, without white space");
    if (!names.insert(joint.name).second) throw ExportError(path, which + ": name repeated");
    if ((j == 0) != (joint.parent < 0))
      throw ExportError(path, which + ": the first joint, and only it, is the root");
    if (j > 0 && joint.parent >= static_cast<int>(j))
      throw ExportError(path, which + ": its parent comes after it");
    if (!joint.offset_mm.allFinite() || !joint.end_site_mm.allFinite())
      throw ExportError(path, which + ": an offset is not finite");
  }
}

void check_frames(const std::string& path, const BvhMotion& motion) {
  if (!(motion.rate_hz > 0) || !std::isfinite(motion.rate_hz))
    throw ExportError(path, "the frame rate is not positive");
  if (motion.frames.empty()) throw ExportError(path, "no frame");
  for (std::size_t f = 0; f < motion.frames.size(); ++f) {
    const BvhFrame& frame = motion.frames[f];
    const std::string which = "frame " + std::to_string(f);
    if (frame.rotations.size() != motion.joints.size())
      throw ExportError(path, which + ": " + std::to_string(frame.rotations.size()) +
                                  " rotations for " + std::to_string(motion.joints.size()) +
                                  " joints");
    if (!frame.root_mm.allFinite()) throw ExportError(path, which + ": root not finite");
    for (const Eigen::Matrix3d& r : frame.rotations)
      if (!r.allFinite()) throw ExportError(path, which + ": a rotation is not finite");
  }
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", value == 0 ? 0.0 : value);  // no "-0.000000"
  return text;
}

std::string triple(const Eigen::Vector3d& v) {
  return number(v.x()) + " " + number(v.y()) + " " + number(v.z());
}

struct HierarchyWriter {
  const std::vector<BvhJoint>& joints;
  std::vector<std::vector<int>> children;
  double scale;
  std::vector<int> order;  // joints as written: the motion's channel order

  void write(std::ostream& out, int j, int depth) {
    const std::string indent(static_cast<std::size_t>(2 * depth), ' ');
    const BvhJoint& joint = joints[static_cast<std::size_t>(j)];
    order.push_back(j);
    out << indent << (j == 0 ? "ROOT " : "JOINT ") << joint.name << "\n" << indent << "{\n";
    out << indent << "  OFFSET " << triple(scale * (to_y_up() * joint.offset_mm)) << "\n";
    out << indent << "  CHANNELS " << (j == 0 ? "6 Xposition Yposition Zposition " : "3 ")
        << "Zrotation Xrotation Yrotation\n";
    for (const int child : children[static_cast<std::size_t>(j)]) write(out, child, depth + 1);
    if (children[static_cast<std::size_t>(j)].empty()) {
      out << indent << "  End Site\n" << indent << "  {\n";
      out << indent << "    OFFSET " << triple(scale * (to_y_up() * joint.end_site_mm)) << "\n";
      out << indent << "  }\n";
    }
    out << indent << "}\n";
  }
};

void write_motion(std::ostream& out, const BvhMotion& motion, const std::vector<int>& order,
                  double scale) {
  const Eigen::Matrix3d m = to_y_up();
  out << "MOTION\nFrames: " << motion.frames.size() << "\n";
  char frame_time[32];
  std::snprintf(frame_time, sizeof frame_time, "%.9g", 1.0 / motion.rate_hz);
  out << "Frame Time: " << frame_time << "\n";
  for (const BvhFrame& frame : motion.frames) {
    std::string row = triple(scale * (m * frame.root_mm));
    for (const int j : order) {
      const Eigen::Vector3d a =
          zxy_angles(m * frame.rotations[static_cast<std::size_t>(j)] * m.transpose()) * 180.0 /
          std::numbers::pi;
      row += " " + triple(a);
    }
    out << row << "\n";
  }
}

}  // namespace

Eigen::Vector3d zxy_angles(const Eigen::Matrix3d& r) {
  // R = Rz Rx Ry: R(2,1) = sin x, R(0,1) = -sin z cos x, R(1,1) = cos z cos x,
  // R(2,0) = -cos x sin y, R(2,2) = cos x cos y.
  const double x = std::asin(std::clamp(r(2, 1), -1.0, 1.0));
  if (std::abs(r(2, 1)) > 1.0 - 1e-12) {  // gimbal lock: z and y turn about the same axis
    return {std::atan2(r(1, 0), r(0, 0)), x, 0.0};
  }
  return {std::atan2(-r(0, 1), r(1, 1)), x, std::atan2(-r(2, 0), r(2, 2))};
}

void write_bvh(const std::string& path, const BvhMotion& motion, const BvhWriteOptions& options) {
  check_joints(path, motion.joints);
  check_frames(path, motion);
  HierarchyWriter hierarchy{
      motion.joints, std::vector<std::vector<int>>(motion.joints.size()), options.units_per_mm, {}};
  for (std::size_t j = 1; j < motion.joints.size(); ++j)
    hierarchy.children[static_cast<std::size_t>(motion.joints[j].parent)].push_back(
        static_cast<int>(j));
  write_file_atomically(path, [&](std::ostream& out) {
    out << "HIERARCHY\n";
    hierarchy.write(out, 0, 0);
    write_motion(out, motion, hierarchy.order, options.units_per_mm);
  });
}

}  // namespace syncap::io
