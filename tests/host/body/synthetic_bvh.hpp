// Small BVH files written by the tests: a Mixamo-like and a CMU-like T-pose skeleton in cm,
// Y up (or the same figure written Z up), with frames set joint by joint.
#pragma once

#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace syncap::body::test {

struct JointRow {
  std::string name;
  std::string parent;     // "" for the root
  double x, y, z;         // offset, cm, Y up, the figure facing +Z with its left at +X
  bool end_site = false;  // a leaf: an End Site follows, 0.3 of its own offset further on
};

// The rows in the order a BVH file lists them: each joint's subtree right after it.
inline std::vector<JointRow> depth_first(const std::vector<JointRow>& rows,
                                         const std::string& parent = "") {
  std::vector<JointRow> out;
  for (const JointRow& row : rows) {
    if (row.parent != parent) continue;
    out.push_back(row);
    for (const JointRow& below : depth_first(rows, row.name)) out.push_back(below);
  }
  return out;
}

inline std::vector<JointRow> mixamo_rows(const std::string& p = "mixamorig:") {
  std::vector<JointRow> rows = {
      {p + "Hips", "", 0, 0, 0},
      {p + "Spine", p + "Hips", 0, 10, -1},
      {p + "Spine1", p + "Spine", 0, 12, -1},
      {p + "Spine2", p + "Spine1", 0, 13, -1},
      {p + "Neck", p + "Spine2", 0, 15, 1},
      {p + "Head", p + "Neck", 0, 10, 3, true},
  };
  for (const auto& [side, s] : {std::pair{"Left", 1.0}, std::pair{"Right", -1.0}}) {
    const std::string n = p + side;
    rows.push_back({n + "Shoulder", p + "Spine2", s * 6, 9, 1});
    rows.push_back({n + "Arm", n + "Shoulder", s * 12, 0, -2});
    rows.push_back({n + "ForeArm", n + "Arm", s * 27, 0, 0});
    rows.push_back({n + "Hand", n + "ForeArm", s * 27, 0, 0, true});
    rows.push_back({n + "UpLeg", p + "Hips", s * 9, -7, 0});
    rows.push_back({n + "Leg", n + "UpLeg", 0, -40, -2});
    rows.push_back({n + "Foot", n + "Leg", 0, -42, -3});
    rows.push_back({n + "ToeBase", n + "Foot", 0, -10, 12, true});
  }
  return depth_first(rows);
}

inline std::vector<JointRow> cmu_rows() {
  std::vector<JointRow> rows = {
      {"Hips", "", 0, 0, 0},
      {"LowerBack", "Hips", 0, 2, 0},
      {"Spine", "LowerBack", 0, 12, 0},
      {"Spine1", "Spine", 0, 12, 0},
      {"Neck", "Spine1", 0, 9, 0},
      {"Neck1", "Neck", 0, 6, 0},
      {"Head", "Neck1", 0, 8, 0, true},
  };
  for (const auto& [side, l, s] : {std::tuple{"Left", "L", 1.0}, std::tuple{"Right", "R", -1.0}}) {
    const std::string n = side;
    rows.push_back({std::string(l) + "HipJoint", "Hips", 0, 0, 0});
    rows.push_back({n + "UpLeg", std::string(l) + "HipJoint", s * 9, -7, 0});
    rows.push_back({n + "Leg", n + "UpLeg", 0, -40, 0});
    rows.push_back({n + "Foot", n + "Leg", 0, -42, 0});
    rows.push_back({n + "ToeBase", n + "Foot", 0, -8, 12, true});
    rows.push_back({n + "Shoulder", "Spine1", s * 6, 9, 0});
    rows.push_back({n + "Arm", n + "Shoulder", s * 12, 0, 0});
    rows.push_back({n + "ForeArm", n + "Arm", s * 27, 0, 0});
    rows.push_back({n + "Hand", n + "ForeArm", s * 27, 0, 0});
    rows.push_back({n + "FingerBase", n + "Hand", s * 5, 0, 0});
    rows.push_back({n + "HandIndex1", n + "FingerBase", s * 4, 0, 0, true});
    rows.push_back({std::string(l) + "Thumb", n + "Hand", s * 3, 0, 3, true});
  }
  return depth_first(rows);
}

// One frame: root position (cm) and per joint Z, Y, X rotations in degrees (Y-up axes).
class SyntheticFrame {
 public:
  explicit SyntheticFrame(const std::vector<JointRow>& rows) : rows_(rows) {}
  SyntheticFrame& root(double x, double y, double z) {
    root_ = {x, y, z};
    return *this;
  }
  SyntheticFrame& rotate(const std::string& joint, double z, double y, double x) {
    rotation_[joint] = {z, y, x};
    return *this;
  }
  // Values in file order; `z_up` writes the same motion for a Z-up file (see synthetic_bvh).
  std::vector<double> values(bool z_up) const {
    std::vector<double> v = z_up ? std::vector<double>{root_[0], -root_[2], root_[1]} : root_;
    for (const JointRow& row : rows_) {
      auto it = rotation_.find(row.name);
      const std::vector<double> r =
          it == rotation_.end() ? std::vector<double>{0, 0, 0} : it->second;
      if (z_up) {
        v.insert(v.end(), {-r[0], r[1], r[2]});
      } else {
        v.insert(v.end(), r.begin(), r.end());
      }
    }
    return v;
  }

 private:
  std::vector<JointRow> rows_;
  std::vector<double> root_{0, 0, 0};
  std::map<std::string, std::vector<double>> rotation_;
};

// The BVH text. Y up: rotations "Zrotation Yrotation Xrotation" (R = Rz Ry Rx). Z up: the same
// figure turned by (x, y, z) -> (x, -z, y), whose rotation Rz(a) Ry(b) Rx(c) becomes
// R-y(a) Rz(b) Rx(c): channels "Yrotation Zrotation Xrotation" with values (-a, b, c).
inline std::string synthetic_bvh(const std::vector<JointRow>& rows,
                                 const std::vector<SyntheticFrame>& frames, bool z_up = false,
                                 double scale = 1.0) {
  std::ostringstream out;
  auto offset = [&](double x, double y, double z) {
    out << "OFFSET " << scale * x << " " << (z_up ? -scale * z : scale * y) << " "
        << (z_up ? scale * y : scale * z) << "\n";
  };
  const char* rotations = z_up ? "Yrotation Zrotation Xrotation" : "Zrotation Yrotation Xrotation";
  out << "HIERARCHY\n";
  std::vector<std::string> open;  // the chain of open joints
  auto close_to = [&](const std::string& parent) {
    while (!open.empty() && open.back() != parent) {
      out << "}\n";
      open.pop_back();
    }
  };
  for (const JointRow& row : rows) {
    close_to(row.parent);
    out << (row.parent.empty() ? "ROOT " : "JOINT ") << row.name << "\n{\n";
    offset(row.x, row.y, row.z);
    out << "CHANNELS " << (row.parent.empty() ? "6 Xposition Yposition Zposition " : "3 ")
        << rotations << "\n";
    if (row.end_site) {
      out << "End Site\n{\n";
      offset(0.3 * row.x, 0.3 * row.y, 0.3 * row.z);
      out << "}\n";
    }
    open.push_back(row.name);
  }
  close_to("");
  out << "MOTION\nFrames: " << frames.size() << "\nFrame Time: 0.04\n";
  for (const SyntheticFrame& f : frames) {
    const std::vector<double> v = f.values(z_up);
    for (std::size_t i = 0; i < v.size(); ++i) {
      out << (i ? " " : "") << (i < 3 ? scale * v[i] : v[i]);
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace syncap::body::test
