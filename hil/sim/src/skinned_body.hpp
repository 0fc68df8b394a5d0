// The skinned human: a triangle mesh with skin weights on our H-Anim skeleton, from MakeHuman's
// CC0 assets (hil/assets/makehuman/README.md says what human.txt holds and where it comes from).
// A subject is the base mesh plus its shape targets; its skeleton is hanim_skeleton()'s tree with
// every node placed in that mesh, so the joints' truth follows the subject's own proportions.
// Posing is linear blend skinning with the node orientations of a body::Pose.
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "body/pose.hpp"
#include "body/skeleton.hpp"
#include "render.hpp"

namespace syncap::sim {

// Up to four (node, weight) pairs per skin vertex, weights summing to 1.
struct SkinWeights {
  std::array<int, 4> node{};
  std::array<float, 4> weight{};
  int count = 0;
};

// human.txt as read: the base shape, its targets and subjects.
struct SkinnedHumanAsset {
  std::vector<Eigen::Vector3d> vertices_mm;  // skin first, then the joint helpers
  int skinned = 0;                           // how many are skin
  std::vector<Eigen::Vector3i> triangles;
  // Per node of hanim_skeleton(), in its order: the vertices whose weighted sum places it.
  std::vector<std::vector<std::pair<int, double>>> node_places;
  std::vector<SkinWeights> weights;  // per skin vertex
  std::map<std::string, std::vector<std::pair<int, Eigen::Vector3d>>> targets;
  std::map<std::string, std::vector<std::pair<std::string, double>>> subjects;
};

// Reads human.txt; throws std::runtime_error naming the file and line of what is broken.
SkinnedHumanAsset load_skinned_human(const std::filesystem::path& file);

// The asset of the source tree (hil/assets/makehuman/human.txt).
std::filesystem::path default_skinned_human_file();

// One subject at rest: its skin relative to its root (as Node::rest_mm is), its skeleton.
struct SkinnedSubject {
  std::string name;
  std::vector<Eigen::Vector3d> rest_mm;  // skin vertices, relative to the root at rest
  std::vector<Eigen::Vector3i> triangles;
  std::vector<SkinWeights> weights;
  std::vector<int> triangle_part;  // the node moving a triangle's first vertex most
  body::Skeleton skeleton;
  double height_mm = 0;  // floor to the top of the head at rest
};

// Throws std::invalid_argument naming the subject and the ones there are when it is unknown.
SkinnedSubject make_subject(const SkinnedHumanAsset& asset, const std::string& subject);

// The posed mesh: every skin vertex moved by its nodes, p_n + O_n (v - rest_n), weighted; smooth
// normals from the posed triangles. texture_mm is the rest skin, so the clothes move with it.
Mesh pose_subject(const SkinnedSubject& subject, const body::Pose& pose);

}  // namespace syncap::sim
