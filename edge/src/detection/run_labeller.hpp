// 8-connected labelling of the pixels at or above a threshold in one pass over row runs: every
// row is run-length encoded, runs of adjacent rows that overlap (8-connectivity: they touch at
// least diagonally) are joined by union-find, and each run adds its area, box and moments to its
// component as it is found, so no second pass over the pixels is needed for them.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::edge {

// A maximal horizontal run of pixels >= threshold: pixels x0 .. x1-1 of row y.
struct Run {
  int y = 0, x0 = 0, x1 = 0;
  int component = 0;  // index into LabelResult::components once labelling is done
};

// One 8-connected component with the sums its runs added. Sums are over the component's pixels;
// "i" sums weight each pixel by its intensity.
struct Component {
  int area = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounding box, inclusive
  int peak = 0;
  int64_t sum_x = 0, sum_y = 0, sum_xx = 0, sum_yy = 0, sum_xy = 0;  // unweighted
  int64_t sum_i = 0, sum_ix = 0, sum_iy = 0, sum_ixx = 0, sum_iyy = 0, sum_ixy = 0;
  int first_run = -1;  // the component's runs, in row order, linked through RunLabeller::next_run
  cv::Rect box() const { return {x0, y0, x1 - x0 + 1, y1 - y0 + 1}; }
};

// Keeps its buffers between calls: one labeller per thread, reused frame after frame.
class RunLabeller {
 public:
  // Labels the pixels of `image` (CV_8UC1) inside `roi` (clipped to the image) that are
  // >= threshold. Coordinates stay those of `image`.
  void label(const cv::Mat& image, cv::Rect roi, int threshold);

  const std::vector<Run>& runs() const { return runs_; }
  const std::vector<Component>& components() const { return components_; }
  // The run after run r in the same component (in row order), or -1.
  int next_run(int r) const { return next_run_[static_cast<size_t>(r)]; }

 private:
  // The intensity sums of one run, taken while its pixels are in cache; the unweighted sums
  // follow from its ends.
  struct RunSums {
    int64_t sum_ix = 0, sum_ixx = 0;
    int32_t sum_i = 0, peak = 0;
  };
  void label_rows(const cv::Mat& image, cv::Rect roi, uint8_t t);  // runs, joined by union-find
  void gather();  // components from the joined runs
  int find(int a);
  void add_run(const uint8_t* row, int y, int x0, int x1, const uint8_t* dataend);
  void add_to(Component& c, size_t r) const;

  std::vector<Run> runs_;
  std::vector<int> parent_;  // union-find over runs
  std::vector<int> next_run_;
  std::vector<RunSums> run_sums_;  // per run, added to its component's
  std::vector<Component> components_;
  std::vector<int> root_component_;
  std::vector<int> roots_;
};

// Throws std::invalid_argument, naming `who`, unless the image is non-empty 8-bit grey.
void check_mono8_image(const cv::Mat& image, const char* who);

}  // namespace syncap::edge
