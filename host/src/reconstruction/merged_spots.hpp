// Merged spots. Two markers whose images touch make one blob, and when the two are nearly in line
// with the camera that blob still looks round enough to pass the edge's roundness filter. Paired
// with a neighbour's own blob in another camera it makes a two-camera point between the two
// markers: on a dense real marker set (sternum, clavicles, hands 2-3 cm apart) 788 of 792 ghosts
// were such points (issue #38). Its size tells it apart: a blob of two markers has up to twice
// the area of one, so its apparent width (partial_spots.hpp: sqrt(area) * distance / the image
// scale at the spot, the same for every whole spot of one marker size) is up to sqrt(2) times a
// whole spot's. What a whole spot's width is comes from the data: the median over the recent
// frames' spots of points seen by three or more cameras (most spots are whole), so no marker
// size needs to be told.
#pragma once

#include <deque>
#include <span>
#include <vector>

namespace syncap::reconstruction {

struct MergedSpotOptions {
  // A spot wider than this times the typical whole spot's apparent width is counted as merged:
  // left out of its point's position, and a point with fewer than two other spots is dropped.
  // A whole spot's width varies by 5-10 % between cameras (its area counted in whole pixels);
  // two touching markers are 1.41 times one, two overlapping by half of their radius still 1.3.
  // 0: no spot is counted as merged.
  double max_width_ratio = 1.25;
  bool enabled() const { return max_width_ratio > 0; }
};

// The apparent width of a whole spot, from the widths of recent frames' spots.
class TypicalSpotWidth {
 public:
  // A frame's apparent widths [mm]; frames with fewer than kMinWidths leave the figure as it was.
  void add_frame(std::span<const double> widths_mm);
  // The median of the last frames' medians; 0 until a frame had enough widths.
  double width_mm() const { return width_mm_; }

  static constexpr std::size_t kMinWidths = 6;
  static constexpr std::size_t kFrames = 15;

 private:
  std::deque<double> frame_medians_;
  double width_mm_ = 0;
};

// Which of a point's spots are merged (true): wider than options.max_width_ratio times
// `typical_width_mm`. None when the options are off or no typical width is known yet.
std::vector<bool> merged_spots(std::span<const double> widths_mm, double typical_width_mm,
                               const MergedSpotOptions& options);

}  // namespace syncap::reconstruction
