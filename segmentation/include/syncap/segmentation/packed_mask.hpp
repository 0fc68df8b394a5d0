// A binary mask packed one bit a pixel, for the clean-up step of MediPicture::apply: the
// closing, the removal of small 8-connected components and the filling of small holes work on 64
// pixels a word, with the same result as cv::morphologyEx (MORPH_CLOSE, default border) and
// cv::connectedComponentsWithStats on the byte image. Internal to syncap_edge_segmentation.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::segmentation::detail {

class PackedMask {
 public:
  // Packs `bytes` (CV_8UC1): non-zero is foreground.
  void pack(const cv::Mat& bytes);
  // Writes 255 / 0 into `bytes` (CV_8UC1 of the packed size).
  void unpack(cv::Mat& bytes) const;

  // Whether close() takes `element`: at most 127 wide, each row one run of ones (or none).
  static bool closable_by(const cv::Mat& element);
  // Dilation then erosion by `element` anchored at its centre (cols / 2, rows / 2), as
  // cv::morphologyEx: outside the image neither dilates nor erodes.
  void close(const cv::Mat& element);
  // Clears the 8-connected components of fewer than `min_area` pixels.
  void remove_small_components(int min_area);
  // Sets the holes of at most `max_area` pixels: the 4-connected components of the background
  // that touch no edge of the mask (as connectedComponentsWithStats of the inverse finds them).
  void fill_holes(int max_area);

 private:
  struct Run {
    int y, x0, x1;  // pixels x0..x1 of row y
  };
  std::uint64_t* row(int y) { return words_.data() + static_cast<std::size_t>(y) * stride_ + 1; }
  const std::uint64_t* row(int y) const {
    return words_.data() + static_cast<std::size_t>(y) * stride_ + 1;
  }
  // Sets the padding words and the bits past the last column of every row to `fill`.
  void set_padding(std::uint64_t fill);
  // The runs of ones row by row (runs_), joined into components by union-find (parent_, 8- or
  // 4-connected), and each component's area at its root (area_).
  void label_runs(bool eight_connected);
  int root_of(int run);  // the run's component, halving the path on the way
  void set_run(const Run& run, bool value);
  void invert();  // every pixel of the mask; the padding stays clear
  // this = morphology of `source` by `element` (dilate: OR, else AND).
  template <bool kDilate>
  void morph_from(const PackedMask& source, const cv::Mat& element);

  int rows_ = 0, cols_ = 0, words_per_row_ = 0;
  std::size_t stride_ = 0;            // words a row: one padding word each side
  std::vector<std::uint64_t> words_;  // row y, word k at y * stride_ + 1 + k
  // morph_from: one source row combined over runs of 2^i pixels, and every source row combined
  // over each distinct run of the element's rows.
  std::vector<std::uint64_t> levels_, combined_;
  std::vector<Run> runs_;
  std::vector<int> parent_, area_;
  std::vector<std::uint8_t> rim_;  // fill_holes: per component, whether it touches the rim
};

}  // namespace syncap::segmentation::detail
