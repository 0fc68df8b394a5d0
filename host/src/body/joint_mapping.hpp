// Which BVH joint drives which joint of our skeleton. Limbs, head and fingers are matched by
// name, across the common naming schemes (Mixamo "mixamorig:LeftUpLeg", CMU "LeftUpLeg",
// 3ds Max "LeftHip", ASF-style "lfemur", suffixed "UpLeg_L"); the spine and neck by relative
// height, because the schemes disagree on what "Spine1" or "Neck" is (docs/design/body-model.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "body/bvh.hpp"
#include "body/skeleton.hpp"

namespace syncap::body {

struct JointMapping {
  std::vector<int> bvh_joint;  // per skeleton node: the BVH joint driving it, -1 when none
};

// The joints every motion must drive: root, hips, knees, ankles, shoulders, elbows, wrists, head.
const std::vector<std::string>& required_joints();

// Lower case, letters and digits only, without a namespace ("mixamorig:Hips" -> "hips").
std::string normalized_joint_name(std::string_view name);

// Throws std::runtime_error "<file>: ..." naming every required joint it found no BVH joint for,
// or a mapped joint that is not below its mapped ancestor in the BVH tree.
JointMapping map_joints(const Skeleton& skeleton, const Bvh& bvh);

}  // namespace syncap::body
