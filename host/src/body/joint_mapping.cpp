#include "body/joint_mapping.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "body/bvh_kinematics.hpp"

namespace syncap::body {
namespace {

struct Alias {
  std::string joint;  // ours
  std::string name;   // normalized BVH name
};

// Names of a side joint: "left"/"l" before or after each base ("leftupleg", "lupleg",
// "uplegleft", "uplegl").
void add_side(std::vector<Alias>& aliases, const std::string& joint,
              const std::vector<std::string>& bases) {
  for (const auto& [ours, side] : {std::pair{"l_", "left"}, std::pair{"r_", "right"}}) {
    const std::string word = side;
    const std::string letter = word.substr(0, 1);
    for (const std::string& base : bases) {
      for (const std::string& name : {word + base, letter + base, base + word, base + letter}) {
        aliases.push_back({ours + joint, name});
      }
    }
  }
}

// In priority order: the first alias that finds an unclaimed BVH joint wins.
const std::vector<Alias>& aliases() {
  static const std::vector<Alias> table = [] {
    std::vector<Alias> a = {{"HumanoidRoot", "hips"},
                            {"HumanoidRoot", "hip"},
                            {"HumanoidRoot", "pelvis"},
                            {"skullbase", "head"}};
    add_side(a, "hip", {"upleg", "thigh", "upperleg", "femur", "hip"});
    add_side(a, "knee", {"leg", "lowleg", "lowerleg", "shin", "calf", "tibia", "knee"});
    add_side(a, "ankle", {"foot", "ankle"});
    add_side(a, "metatarsal", {"toebase", "toe", "toes"});
    add_side(a, "sternoclavicular", {"collar", "clavicle"});
    add_side(a, "shoulder", {"arm", "uparm", "upperarm", "humerus"});
    add_side(a, "elbow", {"forearm", "lowarm", "lowerarm", "radius", "elbow"});
    add_side(a, "wrist", {"hand", "wrist"});
    for (const std::string finger : {"thumb", "index", "middle", "ring", "pinky"}) {
      for (const std::string k : {"1", "2", "3"}) {
        add_side(a, finger + k, {"hand" + finger + k, finger + k});
      }
      add_side(a, finger + "1", {finger});
    }
    // "LeftShoulder" is the clavicle for Mixamo and CMU (whose upper arm is "LeftArm") but the
    // upper arm for 3ds Max (whose clavicle is "LeftCollar"): whichever is still free.
    add_side(a, "shoulder", {"shoulder"});
    add_side(a, "sternoclavicular", {"shoulder"});
    return a;
  }();
  return table;
}

void map_by_name(const Skeleton& skeleton, const Bvh& bvh, std::vector<int>& driver) {
  std::vector<bool> claimed(bvh.joints.size(), false);
  std::vector<std::string> names;
  for (const BvhJoint& j : bvh.joints) names.push_back(normalized_joint_name(j.name));
  for (const Alias& alias : aliases()) {
    const int ours = skeleton.find(alias.joint);
    if (ours < 0 || driver[static_cast<std::size_t>(ours)] >= 0) continue;
    for (std::size_t b = 0; b < bvh.joints.size(); ++b) {
      if (!claimed[b] && !bvh.joints[b].end_site && names[b] == alias.name) {
        driver[static_cast<std::size_t>(ours)] = static_cast<int>(b);
        claimed[b] = true;
        break;
      }
    }
  }
  // A root by any other name is still the root.
  const int root = skeleton.find("HumanoidRoot");
  if (root >= 0 && driver[static_cast<std::size_t>(root)] < 0 && !claimed[0]) {
    driver[static_cast<std::size_t>(root)] = 0;
  }
}

// Path from `from` (exclusive) down to `to` (exclusive) in the BVH tree; empty when `to` is not
// below `from`.
std::vector<int> bvh_path(const Bvh& bvh, int from, int to) {
  std::vector<int> up;
  for (int j = bvh.joints[static_cast<std::size_t>(to)].parent; j >= 0 && j != from;
       j = bvh.joints[static_cast<std::size_t>(j)].parent) {
    up.push_back(j);
  }
  std::reverse(up.begin(), up.end());
  return up;
}

// Relative distance along a chain of points, 0 at the first and 1 at the last.
std::vector<double> chain_fractions(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> f(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i)
    f[i] = f[i - 1] + (points[i] - points[i - 1]).norm();
  if (f.back() > 0) {
    for (double& x : f) x /= f.back();
  }
  return f;
}

// Maps the BVH joints strictly between bvh_from and bvh_to onto our joints strictly between
// ours_from and ours_to, in order, each to the one at the nearest relative distance along its
// chain.
void spread_chain(const Skeleton& skeleton, const Bvh& bvh,
                  const std::vector<Eigen::Vector3d>& rest, int bvh_from, int bvh_to, int ours_from,
                  int ours_to, std::vector<int>& driver) {
  const std::vector<int> theirs = bvh_path(bvh, bvh_from, bvh_to);
  std::vector<int> ours;
  for (int j = skeleton.node(ours_to).parent; j >= 0 && j != ours_from;
       j = skeleton.node(j).parent) {
    if (skeleton.bone_length_mm(j) > 0) ours.push_back(j);  // skip HumanoidRoot2, a duplicate
  }
  std::reverse(ours.begin(), ours.end());
  if (theirs.empty() || ours.size() < theirs.size()) return;

  std::vector<Eigen::Vector3d> bvh_points{rest[static_cast<std::size_t>(bvh_from)]};
  for (int j : theirs) bvh_points.push_back(rest[static_cast<std::size_t>(j)]);
  bvh_points.push_back(rest[static_cast<std::size_t>(bvh_to)]);
  std::vector<Eigen::Vector3d> our_points{skeleton.node(ours_from).rest_mm};
  for (int j : ours) our_points.push_back(skeleton.node(j).rest_mm);
  our_points.push_back(skeleton.node(ours_to).rest_mm);
  const auto bvh_f = chain_fractions(bvh_points);
  const auto our_f = chain_fractions(our_points);

  std::size_t next = 0;  // first of ours still free
  for (std::size_t i = 0; i < theirs.size(); ++i) {
    const std::size_t last = ours.size() - (theirs.size() - i);  // leave room for the rest
    std::size_t best = next;
    for (std::size_t k = next; k <= last; ++k) {
      if (std::abs(our_f[k + 1] - bvh_f[i + 1]) < std::abs(our_f[best + 1] - bvh_f[i + 1]))
        best = k;
    }
    driver[static_cast<std::size_t>(ours[best])] = theirs[i];
    next = best + 1;
  }
}

int driver_of(const std::vector<int>& driver, const Skeleton& skeleton, const char* name) {
  const int i = skeleton.find(name);
  return i < 0 ? -1 : driver[static_cast<std::size_t>(i)];
}

// The spine joint of the BVH that carries the arms: the first joint on the root-head path
// above the left arm.
int arm_carrier(const Bvh& bvh, int root, int head, int arm) {
  const std::vector<int> spine = bvh_path(bvh, root, head);
  for (int j = bvh.joints[static_cast<std::size_t>(arm)].parent; j >= 0;
       j = bvh.joints[static_cast<std::size_t>(j)].parent) {
    if (std::find(spine.begin(), spine.end(), j) != spine.end()) return j;
  }
  return -1;
}

// Spine and neck: the BVH joint carrying the clavicles goes to vt1 (ours carries them), those
// below it spread over vl5..vt2 and those above over vc7..vc1.
void map_spine(const Skeleton& skeleton, const Bvh& bvh, std::vector<int>& driver) {
  const int root = driver_of(driver, skeleton, "HumanoidRoot");
  const int head = driver_of(driver, skeleton, "skullbase");
  if (root < 0 || head < 0 || bvh_path(bvh, root, head).empty()) return;
  const auto rest = bvh_forward_kinematics(bvh, bvh_rest_pose(bvh)).position;
  const int ours_root = skeleton.at("HumanoidRoot");
  const int ours_head = skeleton.at("skullbase");
  const int ours_vt1 = skeleton.find("vt1");
  int arm = driver_of(driver, skeleton, "l_sternoclavicular");
  if (arm < 0) arm = driver_of(driver, skeleton, "l_shoulder");
  const int carrier = arm < 0 || ours_vt1 < 0 ? -1 : arm_carrier(bvh, root, head, arm);
  if (carrier < 0) {
    spread_chain(skeleton, bvh, rest, root, head, ours_root, ours_head, driver);
    return;
  }
  driver[static_cast<std::size_t>(ours_vt1)] = carrier;
  spread_chain(skeleton, bvh, rest, root, carrier, ours_root, ours_vt1, driver);
  spread_chain(skeleton, bvh, rest, carrier, head, ours_vt1, ours_head, driver);
}

bool bvh_is_below(const Bvh& bvh, int ancestor, int j) {
  for (int p = bvh.joints[static_cast<std::size_t>(j)].parent; p >= 0;
       p = bvh.joints[static_cast<std::size_t>(p)].parent) {
    if (p == ancestor) return true;
  }
  return false;
}

void check(const Skeleton& skeleton, const Bvh& bvh, const std::vector<int>& driver) {
  std::string missing;
  for (const std::string& name : required_joints()) {
    const int i = skeleton.find(name);
    if (i >= 0 && driver[static_cast<std::size_t>(i)] < 0) {
      missing += (missing.empty() ? "" : ", ") + name;
    }
  }
  if (!missing.empty()) {
    throw std::runtime_error(bvh.source + ": no BVH joint found for " + missing +
                             " (docs/design/body-model.md lists the names understood)");
  }
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    if (driver[i] < 0) continue;
    for (int p = skeleton.node(static_cast<int>(i)).parent; p >= 0; p = skeleton.node(p).parent) {
      const int above = driver[static_cast<std::size_t>(p)];
      if (above < 0) continue;
      if (!bvh_is_below(bvh, above, driver[i])) {
        throw std::runtime_error(bvh.source + ": " +
                                 bvh.joints[static_cast<std::size_t>(driver[i])].name + " (for " +
                                 skeleton.node(static_cast<int>(i)).name + ") is not below " +
                                 bvh.joints[static_cast<std::size_t>(above)].name + " (for " +
                                 skeleton.node(p).name + ") in the BVH hierarchy");
      }
      break;
    }
  }
}

}  // namespace

const std::vector<std::string>& required_joints() {
  static const std::vector<std::string> names = {
      "HumanoidRoot", "l_hip",      "r_hip",      "l_knee",  "r_knee",  "l_ankle", "r_ankle",
      "skullbase",    "l_shoulder", "r_shoulder", "l_elbow", "r_elbow", "l_wrist", "r_wrist"};
  return names;
}

std::string normalized_joint_name(std::string_view name) {
  const std::size_t colon = name.rfind(':');
  if (colon != std::string_view::npos) name.remove_prefix(colon + 1);
  std::string out;
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  // "mixamorig_Hips", "mixamorig1_Hips": a namespace written without the colon.
  if (out.rfind("mixamorig", 0) == 0) {
    std::size_t k = 9;
    while (k < out.size() && std::isdigit(static_cast<unsigned char>(out[k]))) ++k;
    out.erase(0, k);
  }
  return out;
}

JointMapping map_joints(const Skeleton& skeleton, const Bvh& bvh) {
  JointMapping mapping;
  mapping.bvh_joint.assign(skeleton.size(), -1);
  if (bvh.joints.empty()) throw std::runtime_error(bvh.source + ": no joints");
  map_by_name(skeleton, bvh, mapping.bvh_joint);
  map_spine(skeleton, bvh, mapping.bvh_joint);
  check(skeleton, bvh, mapping.bvh_joint);
  return mapping;
}

}  // namespace syncap::body
