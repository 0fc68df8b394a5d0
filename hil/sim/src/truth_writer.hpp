// Writes a rendered sequence to disk: per camera the 8-bit images named by frame number, and the
// ground truth beside them (docs/design/scenario.md, "Output").
#pragma once

#include <filesystem>
#include <fstream>
#include <vector>

#include "render.hpp"
#include "sequence.hpp"

namespace syncap::sim {

class TruthWriter {
 public:
  // Creates out/, out/cameraNN/ and out/truth/; throws std::runtime_error naming what failed.
  TruthWriter(const std::filesystem::path& out, int cameras);

  // One frame: the state of the scene and what every camera rendered.
  void write(const FrameState& state, const std::vector<RenderedView>& views);

  static std::filesystem::path image_path(const std::filesystem::path& out, int camera, int frame);
  static std::filesystem::path mask_path(const std::filesystem::path& out, int camera, int frame);

 private:
  void write_image(const std::filesystem::path& path, const cv::Mat& image) const;
  void write_names(const FrameState& state);

  std::filesystem::path out_;
  std::ofstream frames_, targets_, projections_, body_;
  std::ofstream names_;   // truth/marker_names.csv, opened at the first mocap phase
  int names_phase_ = -1;  // the last phase whose names were written
};

}  // namespace syncap::sim
