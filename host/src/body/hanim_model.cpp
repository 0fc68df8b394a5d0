#include "body/hanim_model.hpp"

#include <array>
#include <string>
#include <vector>

namespace syncap::body {
namespace {

struct Row {
  const char* name;
  const char* parent;              // "" for the root
  std::array<double, 3> hanim_mm;  // x left, y up, z front, as printed
  int line;                        // in thesis.txt; 0 for our sites
};

// Thesis Table 5.1 (rows on lines 4650-4714, caption 4716) and Table 5.2 (rows 4719-4742,
// caption 4744), row by row, numbers as printed; `line` is the row's line in thesis.txt. The
// extraction printed "l hip" for the H-Anim name l_hip. Table 5.1 starts with "GlobalPosition 1 1
// 1" (line 4650): the model's global placement (unit scale), not a joint; Pose::root_mm and the
// root orientation play its part. The tables give no parents; they are those of the H-Anim standard
// (ISO/IEC 19774, thesis lines 4333-4334; the figure of the joints, Fig. 5.22, line 4604), with the
// thesis' extra HumanoidRoot2 (same centre as HumanoidRoot) taken as the parent of both the pelvis
// (sacroiliac) and the spine (vl5).
constexpr Row kThesisRows[] = {
    {"HumanoidRoot", "", {0, 0, 0}, 4651},
    {"HumanoidRoot2", "HumanoidRoot", {0, 0, 0}, 4652},
    {"sacroiliac", "HumanoidRoot2", {0, -11.353028, 20.271}, 4653},
    {"l_hip", "sacroiliac", {102.797997, -182.709961, -33.514}, 4654},
    {"l_knee", "l_hip", {102.797997, -569.030175, -33.514}, 4655},
    {"l_ankle", "l_knee", {102.797997, -975.372833, -33.514}, 4656},
    {"l_subtalar", "l_ankle", {94.699998, -1011.770832, -18.550003}, 4657},
    {"l_midtarsal", "l_subtalar", {105.093995, -1027.209831, 66.648998}, 4658},
    {"l_metatarsal", "l_midtarsal", {114.680993, -1036.507834, 130.149002}, 4659},
    {"r_hip", "sacroiliac", {-102.797997, -182.709961, -33.514}, 4660},
    {"r_knee", "r_hip", {-102.797997, -569.030175, -33.514}, 4661},
    {"r_ankle", "r_knee", {-102.797997, -975.372833, -33.514}, 4662},
    {"r_subtalar", "r_ankle", {-94.699998, -1011.770832, -18.550003}, 4663},
    {"r_midtarsal", "r_subtalar", {-105.093995, -1027.209831, 66.648998}, 4664},
    {"r_metatarsal", "r_midtarsal", {-114.680993, -1036.507834, 130.149002}, 4665},
    {"vl5", "HumanoidRoot2", {0, -6.353028, 20.271}, 4666},
    {"vl4", "vl5", {0, 0.646972, 20.271}, 4667},
    {"vl3", "vl4", {0, 8.646972, 20.271}, 4668},
    {"vl2", "vl3", {0, 27.617065, 20.757}, 4669},
    {"vl1", "vl2", {0, 48.067016, 20.76}, 4670},
    {"vt12", "vl1", {0, 70.447021, 20.765999}, 4671},
    {"vt11", "vt12", {0, 95.447021, 19.415001}, 4672},
    {"vt10", "vt11", {0, 120.447021, 18.237}, 4673},
    {"vt9", "vt10", {0, 148.937011, 15.533999}, 4674},
    {"vt8", "vt9", {0, 175.687011, 10.184999}, 4675},
    {"vt7", "vt8", {0, 201.347046, 4.452}, 4676},
    {"vt6", "vt7", {0, 226.907104, 0.946}, 4677},
    {"vt5", "vt6", {0, 249.73706, -1.661}, 4678},
    {"vt4", "vt5", {0, 271.727051, -3.284}, 4679},
    {"vt3", "vt4", {0, 292.24707, -3.631}, 4680},
    {"vt2", "vt3", {0, 312.437134, -1.559}, 4681},
    {"vt1", "vt2", {0, 334.867065, 1.567}, 4682},
    {"vc7", "vt1", {0, 363.347046, 5.905}, 4683},
    {"vc6", "vc7", {0, 395.197021, 12.195001}, 4684},
    {"vc5", "vc6", {0, 424.927002, 20.012001}, 4685},
    {"vc4", "vc5", {0, 454.877075, 27.991001}, 4686},
    {"vc3", "vc4", {0, 487.476928, 32.085003}, 4687},
    {"vc2", "vc3", {0, 521.906982, 31.364002}, 4688},
    {"vc1", "vc2", {0, 561.666992, 27.073}, 4689},
    {"skullbase", "vc1", {0, 600.25708, 18.445}, 4690},
    {"l_sternoclavicular", "vt1", {33, 380.357055, 90.099998}, 4691},
    {"l_acromioclavicular", "l_sternoclavicular", {159.599991, 402.256958, 48}, 4692},
    {"l_shoulder", "l_acromioclavicular", {177.399979, 401.557007, -12.000002}, 4693},
    {"l_elbow", "l_shoulder", {177.399979, 104.25044, -12.000002}, 4694},
    {"l_wrist", "l_elbow", {177.399979, -162.900004, -12.000002}, 4695},
    {"l_thumb1", "l_wrist", {153.650986, -186.350016, 19.384001}, 4696},
    {"l_thumb2", "l_thumb1", {150.554978, -211.032023, 55.043003}, 4697},
    {"l_thumb3", "l_thumb2", {148.000977, -231.39506, 84.461994}, 4698},
    {"l_index0", "l_wrist", {168.448975, -188.767069, 4.719996}, 4699},
    {"l_index1", "l_index0", {158.996979, -255.930033, 27.722996}, 4700},
    {"l_index2", "l_index1", {158.996979, -297.114054, 27.722996}, 4701},
    {"l_index3", "l_index2", {158.996979, -319.764994, 27.722996}, 4702},
    {"l_middle0", "l_wrist", {173.152985, -189.774027, -5.064002}, 4703},
    {"l_middle1", "l_middle0", {164.320969, -259.567057, 5.486996}, 4704},
    {"l_middle2", "l_middle1", {164.320969, -308.206034, 5.486996}, 4705},
    {"l_middle3", "l_middle2", {164.320969, -337.390055, 5.486996}, 4706},
    {"l_ring0", "l_wrist", {174.851975, -189.433024, -13.292002}, 4707},
    {"l_ring1", "l_ring0", {164.83899, -257.780069, -13.292002}, 4708},
    {"l_ring2", "l_ring1", {164.83899, -296.87504, -13.292002}, 4709},
    {"l_ring3", "l_ring2", {164.83899, -323.290018, -13.292002}, 4710},
    {"l_pinky0", "l_wrist", {174.260971, -188.673075, -21.018002}, 4711},
    {"l_pinky1", "l_pinky0", {164.23198, -249.84202, -33.082003}, 4712},
    {"l_pinky2", "l_pinky1", {164.23198, -278.366007, -33.082003}, 4713},
    {"l_pinky3", "l_pinky2", {164.23198, -297.639017, -33.082003}, 4714},
    {"r_sternoclavicular", "vt1", {-33, 380.357055, 90.099998}, 4719},
    {"r_acromioclavicular", "r_sternoclavicular", {-159.599991, 402.256958, 48}, 4720},
    {"r_shoulder", "r_acromioclavicular", {-177.399979, 401.557007, -12.000002}, 4721},
    {"r_elbow", "r_shoulder", {-177.399979, 104.25044, -12.000002}, 4722},
    {"r_wrist", "r_elbow", {-177.399979, -162.900004, -12.000002}, 4723},
    {"r_thumb1", "r_wrist", {-153.650986, -186.350016, 19.384001}, 4724},
    {"r_thumb2", "r_thumb1", {-150.554978, -211.032023, 55.043003}, 4725},
    {"r_thumb3", "r_thumb2", {-148.000977, -231.39506, 84.461994}, 4726},
    {"r_index0", "r_wrist", {-168.448975, -188.767069, 4.719996}, 4727},
    {"r_index1", "r_index0", {-158.996979, -255.930033, 27.722996}, 4728},
    {"r_index2", "r_index1", {-158.996979, -297.114054, 27.722996}, 4729},
    {"r_index3", "r_index2", {-158.996979, -319.764994, 27.722996}, 4730},
    {"r_middle0", "r_wrist", {-173.152985, -189.774027, -5.064002}, 4731},
    {"r_middle1", "r_middle0", {-164.320969, -259.567057, 5.486996}, 4732},
    {"r_middle2", "r_middle1", {-164.320969, -308.206034, 5.486996}, 4733},
    {"r_middle3", "r_middle2", {-164.320969, -337.390055, 5.486996}, 4734},
    {"r_ring0", "r_wrist", {-174.851975, -189.433024, -13.292002}, 4735},
    {"r_ring1", "r_ring0", {-164.83899, -257.780069, -13.292002}, 4736},
    {"r_ring2", "r_ring1", {-164.83899, -296.87504, -13.292002}, 4737},
    {"r_ring3", "r_ring2", {-164.83899, -323.290018, -13.292002}, 4738},
    {"r_pinky0", "r_wrist", {-174.260971, -188.673075, -21.018002}, 4739},
    {"r_pinky1", "r_pinky0", {-164.23198, -249.84202, -33.082003}, 4740},
    {"r_pinky2", "r_pinky1", {-164.23198, -278.366007, -33.082003}, 4741},
    {"r_pinky3", "r_pinky2", {-164.23198, -297.639017, -33.082003}, 4742},
};

// End sites the thesis does not give (H-Anim names: segment name + "_tip", landmark names).
// Anthropometric defaults in the same frame: the head's vertex 160 mm above skullbase, which
// makes the figure 1820 mm tall on the floor kHanimFloorY; the heel 60 mm behind the ankle,
// 30 mm above the floor; the toe tip 60 mm in front of the toe joint, 25 mm above the floor.
constexpr Row kSiteRows[] = {
    {"skull_tip", "skullbase", {0, 760.25708, 18.445}, 0},
    {"l_calcaneus_posterior", "l_subtalar", {102.797997, -1030, -93.514}, 0},
    {"l_forefoot_tip", "l_metatarsal", {114.680993, -1035, 190.149002}, 0},
    {"r_calcaneus_posterior", "r_subtalar", {-102.797997, -1030, -93.514}, 0},
    {"r_forefoot_tip", "r_metatarsal", {-114.680993, -1035, 190.149002}, 0},
};

// One ellipsoid per body segment: the thesis attaches "one ellipsoid to each bone ... [its]
// center lies in the middle of the bone" (lines 4549-4553), cylindrically symmetric; ours are
// flattened where a body is (trunk, head, hand, foot). Radii in mm along the segment, then across
// (Segment explains the two cross axes: depth then width for standing segments, height then
// depth or width for lying ones). Table 5.4 (lines 4786-4802) gives one shape: the upper arm
// (l_shoulder to l_elbow, 297.30657 mm) with width 60, used here as its cross radius. The rest
// are anthropometric defaults for an adult of 1.8 m; the semi-axis along a limb is a little more
// than half the bone so that neighbours overlap at the joint.
std::vector<SegmentSpec> segment_specs() {
  std::vector<SegmentSpec> specs = {
      {"pelvis", "l_hip", "r_hip", "sacroiliac", {170, 125, 110}},
      {"abdomen", "vl5", "vt10", "vl5", {95, 105, 140}},
      {"thorax", "vt10", "vt1", "vt10", {150, 110, 160}},
      {"neck", "vc7", "skullbase", "vc7", {125, 60, 60}},
      {"skull", "skullbase", "skull_tip", "skullbase", {110, 100, 80}},
  };
  for (const std::string side : {"l_", "r_"}) {
    auto add = [&](const char* name, const char* from, const char* to, const char* attached,
                   Eigen::Vector3d radii) {
      specs.push_back({side + name, side + from, side + to, side + attached, radii});
    };
    add("clavicle", "sternoclavicular", "acromioclavicular", "sternoclavicular", {75, 40, 45});
    add("scapula", "acromioclavicular", "shoulder", "acromioclavicular", {50, 55, 55});
    add("upperarm", "shoulder", "elbow", "shoulder", {165, 60, 60});
    add("forearm", "elbow", "wrist", "elbow", {145, 45, 45});
    add("hand", "wrist", "middle3", "wrist", {100, 45, 22});
    add("thigh", "hip", "knee", "hip", {210, 80, 80});
    add("calf", "knee", "ankle", "knee", {215, 55, 55});
    add("foot", "calcaneus_posterior", "forefoot_tip", "ankle", {142, 28, 45});
  }
  return specs;
}

Node make_node(const Row& row, NodeKind kind, const std::vector<Node>& before) {
  Node n;
  n.name = row.name;
  n.kind = kind;
  n.source_mm = Eigen::Vector3d(row.hanim_mm[0], row.hanim_mm[1], row.hanim_mm[2]);
  n.rest_mm = hanim_to_world() * n.source_mm;
  n.source_line = row.line;
  const std::string parent = row.parent;
  for (std::size_t i = 0; i < before.size() && !parent.empty(); ++i) {
    if (before[i].name == parent) n.parent = static_cast<int>(i);
  }
  return n;
}

}  // namespace

Eigen::Matrix3d hanim_to_world() {
  Eigen::Matrix3d m;
  m << 1, 0, 0,  //
      0, 0, -1,  //
      0, 1, 0;
  return m;
}

Skeleton hanim_skeleton() {
  std::vector<Node> nodes;
  for (const Row& row : kThesisRows) nodes.push_back(make_node(row, NodeKind::kJoint, nodes));
  for (const Row& row : kSiteRows) nodes.push_back(make_node(row, NodeKind::kSite, nodes));
  const Eigen::Vector3d front = hanim_to_world() * Eigen::Vector3d::UnitZ();
  return Skeleton(std::move(nodes), segment_specs(), front, -kHanimFloorY);
}

}  // namespace syncap::body
