#include "skinned_body.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "body/hanim_model.hpp"

#ifndef SYNCAP_SOURCE_DIR
#define SYNCAP_SOURCE_DIR "."
#endif

namespace syncap::sim {
namespace {

// Reads human.txt line by line; every error names the file and the line.
class AssetReader {
 public:
  explicit AssetReader(const std::filesystem::path& file) : file_(file), in_(file) {
    if (!in_) throw std::runtime_error(file.string() + ": cannot be opened");
  }

  // The next line that is not a comment, as a stream; fails at the end of the file.
  std::istringstream next(const char* what) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      if (!line.empty() && line[0] != '#') return std::istringstream(line);
    }
    fail(std::string("ends where ") + what + " was expected");
  }
  bool more() {
    while (in_.peek() == '#' || in_.peek() == '\n') {
      std::string skip;
      std::getline(in_, skip);
      ++line_;
    }
    return in_.peek() != std::char_traits<char>::eof();
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error(file_.string() + ":" + std::to_string(line_) + ": " + why);
  }
  // A header "word N": returns N.
  int header(std::istringstream& s, const char* word) {
    std::string got;
    int count = -1;
    if (!(s >> got >> count) || got != word || count < 0)
      fail(std::string("expected \"") + word + " COUNT\"");
    return count;
  }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
  int line_ = 0;
};

void read_vertices(AssetReader& r, SkinnedHumanAsset& a) {
  auto head = r.next("the vertices");
  const int count = r.header(head, "vertices");
  std::string word;
  if (!(head >> word >> a.skinned) || word != "skinned" || a.skinned > count)
    r.fail("expected \"vertices N skinned M\" with M <= N");
  for (int i = 0; i < count; ++i) {
    auto s = r.next("a vertex");
    Eigen::Vector3d v;
    if (!(s >> v.x() >> v.y() >> v.z())) r.fail("a vertex is three numbers");
    a.vertices_mm.push_back(v);
  }
}

void read_triangles(AssetReader& r, SkinnedHumanAsset& a) {
  auto head = r.next("the triangles");
  const int count = r.header(head, "triangles");
  for (int i = 0; i < count; ++i) {
    auto s = r.next("a triangle");
    Eigen::Vector3i t;
    if (!(s >> t.x() >> t.y() >> t.z()) || t.minCoeff() < 0 || t.maxCoeff() >= a.skinned)
      r.fail("a triangle is three skin vertex indices");
    a.triangles.push_back(t);
  }
}

void read_nodes(AssetReader& r, SkinnedHumanAsset& a, const body::Skeleton& hanim) {
  auto head = r.next("the nodes");
  const int count = r.header(head, "nodes");
  if (count != static_cast<int>(hanim.size()))
    r.fail("has " + std::to_string(count) + " nodes, hanim_skeleton() " +
           std::to_string(hanim.size()));
  for (int k = 0; k < count; ++k) {
    auto s = r.next("a node");
    std::string name;
    int n = 0;
    if (!(s >> name >> n) || name != hanim.node(k).name || n < 1)
      r.fail("expected node " + hanim.node(k).name + " and its vertex count");
    std::vector<std::pair<int, double>> place(static_cast<std::size_t>(n));
    for (auto& [i, c] : place) {
      if (!(s >> i >> c) || i < 0 || i >= static_cast<int>(a.vertices_mm.size()))
        r.fail("node " + name + ": expected vertex index and coefficient pairs");
    }
    a.node_places.push_back(std::move(place));
  }
}

void read_weights(AssetReader& r, SkinnedHumanAsset& a) {
  auto head = r.next("the weights");
  if (r.header(head, "weights") != a.skinned) r.fail("one weight line per skin vertex expected");
  const int nodes = static_cast<int>(a.node_places.size());
  for (int i = 0; i < a.skinned; ++i) {
    auto s = r.next("a vertex's weights");
    SkinWeights w;
    if (!(s >> w.count) || w.count < 1 || w.count > 4) r.fail("1 to 4 weights a vertex");
    float sum = 0;
    for (int k = 0; k < w.count; ++k) {
      if (!(s >> w.node[k] >> w.weight[k]) || w.node[k] < 0 || w.node[k] >= nodes)
        r.fail("a weight is a node index and a number");
      sum += w.weight[k];
    }
    if (std::abs(sum - 1.0f) > 1e-2f) r.fail("weights sum to " + std::to_string(sum));
    for (int k = 0; k < w.count; ++k) w.weight[k] /= sum;  // exactly 1: the rest pose is exact
    a.weights.push_back(w);
  }
}

void read_shape(AssetReader& r, SkinnedHumanAsset& a) {
  auto s = r.next("a target or subject");
  std::string kind, name;
  int count = 0;
  if (!(s >> kind >> name >> count) || (kind != "target" && kind != "subject"))
    r.fail("expected \"target NAME COUNT\" or \"subject NAME COUNT ...\"");
  if (kind == "subject") {
    auto& mix = a.subjects[name];
    for (int k = 0; k < count; ++k) {
      std::string target;
      double weight = 0;
      if (!(s >> target >> weight) || !a.targets.count(target))
        r.fail("subject " + name + ": expected known target names and weights");
      mix.emplace_back(target, weight);
    }
    return;
  }
  auto& offsets = a.targets[name];
  for (int k = 0; k < count; ++k) {
    auto line = r.next("a target offset");
    int i = -1;
    Eigen::Vector3d d;
    if (!(line >> i >> d.x() >> d.y() >> d.z()) || i < 0 ||
        i >= static_cast<int>(a.vertices_mm.size()))
      r.fail("target " + name + ": expected \"vertex dx dy dz\"");
    offsets.emplace_back(i, d);
  }
}

body::Skeleton place_skeleton(const std::vector<Eigen::Vector3d>& shaped,
                              const SkinnedHumanAsset& asset, Eigen::Vector3d& root_world) {
  const body::Skeleton hanim = body::hanim_skeleton();
  std::vector<Eigen::Vector3d> at(hanim.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < hanim.size(); ++k) {
    for (const auto& [i, c] : asset.node_places[k]) at[k] += c * shaped[static_cast<size_t>(i)];
  }
  root_world = at[0];
  for (auto& p : at) p -= root_world;
  double floor = std::numeric_limits<double>::infinity();
  for (int i = 0; i < asset.skinned; ++i) floor = std::min(floor, shaped[size_t(i)].z());
  return hanim.with_rest(at, root_world.z() - floor);
}

}  // namespace

SkinnedHumanAsset load_skinned_human(const std::filesystem::path& file) {
  AssetReader r(file);
  {
    auto s = r.next("the format line");
    std::string magic;
    int version = 0;
    if (!(s >> magic >> version) || magic != "syncap-skinned-human" || version != 1)
      r.fail("not a syncap-skinned-human 1 file");
  }
  SkinnedHumanAsset a;
  read_vertices(r, a);
  read_triangles(r, a);
  read_nodes(r, a, body::hanim_skeleton());
  read_weights(r, a);
  while (r.more()) read_shape(r, a);
  return a;
}

std::filesystem::path default_skinned_human_file() {
  return std::filesystem::path(SYNCAP_SOURCE_DIR) / "hil/assets/makehuman/human.txt";
}

SkinnedSubject make_subject(const SkinnedHumanAsset& asset, const std::string& subject) {
  const auto mix = asset.subjects.find(subject);
  if (mix == asset.subjects.end()) {
    std::string known;
    for (const auto& [name, _] : asset.subjects) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("skinned human: no subject \"" + subject + "\" (there are " +
                                known + ")");
  }
  std::vector<Eigen::Vector3d> shaped = asset.vertices_mm;
  for (const auto& [target, weight] : mix->second) {
    for (const auto& [i, d] : asset.targets.at(target))
      shaped[static_cast<size_t>(i)] += weight * d;
  }
  Eigen::Vector3d root = Eigen::Vector3d::Zero();
  body::Skeleton skeleton = place_skeleton(shaped, asset, root);
  SkinnedSubject out{subject, {}, asset.triangles, asset.weights, {}, std::move(skeleton), 0};
  double top = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < asset.skinned; ++i) {
    out.rest_mm.push_back(shaped[static_cast<size_t>(i)] - root);
    top = std::max(top, out.rest_mm.back().z());
  }
  out.height_mm = top + out.skeleton.rest_root_height_mm();
  for (const Eigen::Vector3i& t : out.triangles)
    out.triangle_part.push_back(out.weights[static_cast<size_t>(t.x())].node[0]);
  return out;
}

Mesh pose_subject(const SkinnedSubject& subject, const body::Pose& pose) {
  const auto positions = body::node_positions(subject.skeleton, pose);
  // Per node, the affine map rest -> posed: v -> O v + (p - O rest).
  std::vector<Eigen::Matrix3d> turn(positions.size());
  std::vector<Eigen::Vector3d> shift(positions.size());
  for (std::size_t n = 0; n < positions.size(); ++n) {
    turn[n] = pose.orientation[n].toRotationMatrix();
    shift[n] = positions[n] - turn[n] * subject.skeleton.node(static_cast<int>(n)).rest_mm;
  }
  Mesh mesh;
  mesh.triangles = subject.triangles;
  mesh.triangle_part = subject.triangle_part;
  mesh.texture_mm = subject.rest_mm;
  mesh.vertices_mm.resize(subject.rest_mm.size());
  for (std::size_t i = 0; i < subject.rest_mm.size(); ++i) {
    const SkinWeights& w = subject.weights[i];
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < w.count; ++k) {
      const auto n = static_cast<std::size_t>(w.node[k]);
      v += w.weight[k] * (turn[n] * subject.rest_mm[i] + shift[n]);
    }
    mesh.vertices_mm[i] = v;
  }
  mesh.normals.assign(mesh.vertices_mm.size(), Eigen::Vector3d::Zero());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const auto& a = mesh.vertices_mm[size_t(t.x())];
    const Eigen::Vector3d n =
        (mesh.vertices_mm[size_t(t.y())] - a).cross(mesh.vertices_mm[size_t(t.z())] - a);
    for (int k = 0; k < 3; ++k) mesh.normals[size_t(t[k])] += n;  // area-weighted
  }
  for (auto& n : mesh.normals) n = n.norm() > 0 ? n.normalized() : Eigen::Vector3d::UnitZ();
  return mesh;
}

}  // namespace syncap::sim
