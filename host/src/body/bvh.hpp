// BVH motion files (Biovision Hierarchy): the skeleton (HIERARCHY: ROOT, JOINT, End Site,
// OFFSET, CHANNELS) and the motion (MOTION: Frames, Frame Time, one line of channel values per
// frame). A broken file is reported as "<file>:<line>: <problem>".
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::body {

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

struct BvhJoint {
  std::string name;  // an End Site is named after its parent: "<parent>/End Site"
  int parent = -1;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // from the parent, file units
  std::vector<BvhChannel> channels;                  // in file order
  int first_channel = 0;                             // index of channels[0] within a frame's values
  bool end_site = false;
  int line = 0;  // where the joint is declared
};

struct Bvh {
  std::string source;            // the file name used in messages
  std::vector<BvhJoint> joints;  // parents before children, the root first
  int channel_count = 0;
  int frame_count = 0;
  double frame_time_s = 0;
  std::vector<double> values;  // frame_count rows of channel_count values

  std::span<const double> frame(int k) const;
  double duration_s() const { return frame_count > 1 ? (frame_count - 1) * frame_time_s : 0.0; }
  int find(std::string_view name) const;  // -1 when absent
};

class BvhError : public std::runtime_error {
 public:
  BvhError(const std::string& file, int line, const std::string& problem);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  std::string problem_;
};

// `source` names the text in error messages (usually the file's name).
Bvh parse_bvh(std::string_view text, const std::string& source);
// Reads and parses a file; errors name the path as given.
Bvh load_bvh(const std::filesystem::path& path);

}  // namespace syncap::body
