#include "reconstruction/merged_spots.hpp"

#include <algorithm>

namespace syncap::reconstruction {
namespace {

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

void TypicalSpotWidth::add_frame(std::span<const double> widths_mm) {
  if (widths_mm.size() < kMinWidths) return;
  frame_medians_.push_back(median({widths_mm.begin(), widths_mm.end()}));
  if (frame_medians_.size() > kFrames) frame_medians_.pop_front();
  width_mm_ = median({frame_medians_.begin(), frame_medians_.end()});
}

std::vector<bool> merged_spots(std::span<const double> widths_mm, double typical_width_mm,
                               const MergedSpotOptions& options) {
  std::vector<bool> merged(widths_mm.size(), false);
  if (!options.enabled() || !(typical_width_mm > 0)) return merged;
  for (std::size_t i = 0; i < widths_mm.size(); ++i)
    merged[i] = widths_mm[i] > options.max_width_ratio * typical_width_mm;
  return merged;
}

}  // namespace syncap::reconstruction
