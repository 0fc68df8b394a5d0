#include "syncap/proto/marker_parts.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "syncap/proto/item_parts.hpp"

namespace syncap::proto {

std::vector<marker_frame_t> split_marker_frame(const marker_frame_t& frame) {
  const std::size_t total = frame.markers.size();
  if (total > static_cast<std::size_t>(std::numeric_limits<int16_t>::max())) {
    throw std::invalid_argument("frame " + std::to_string(frame.frame_number) + ": " +
                                std::to_string(total) +
                                " markers exceed the 32767 a frame can carry");
  }
  return detail::split_items(
      frame, &marker_frame_t::markers, marker_frame_t::MAX_MARKERS,
      [total](marker_frame_t& part, std::size_t index, std::size_t count, std::size_t markers) {
        part.num_markers = static_cast<int16_t>(markers);
        part.total_markers = static_cast<int16_t>(total);
        part.part_index = static_cast<int16_t>(index);
        part.part_count = static_cast<int16_t>(count);
      });
}

marker_frame_t join_marker_parts(std::span<const marker_frame_t> parts) {
  if (parts.empty()) throw std::invalid_argument("join_marker_parts: no parts");
  std::vector<marker_frame_t> sorted(parts.begin(), parts.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.part_index < b.part_index; });
  marker_frame_t whole =
      detail::join_items(std::span<const marker_frame_t>(sorted), &marker_frame_t::markers);
  whole.num_markers = static_cast<int16_t>(whole.markers.size());
  whole.part_index = 0;
  whole.part_count = 1;
  return whole;
}

}  // namespace syncap::proto
