#include "syncap/proto/blob_parts.hpp"

#include "syncap/proto/item_parts.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace syncap::proto {

std::vector<blob_frame_t> split_blob_frame(const blob_frame_t& frame) {
  const std::size_t total = frame.blobs.size();
  if (total > static_cast<std::size_t>(std::numeric_limits<int16_t>::max())) {
    throw std::invalid_argument("camera " + std::to_string(frame.camera_id) + " frame " +
                                std::to_string(frame.frame_number) + ": " + std::to_string(total) +
                                " blobs exceed the 32767 a frame can carry");
  }
  return detail::split_items(
      frame, &blob_frame_t::blobs, blob_frame_t::MAX_BLOBS,
      [total](blob_frame_t& part, std::size_t index, std::size_t count, std::size_t blobs) {
        part.num_blobs = static_cast<int16_t>(blobs);
        part.total_blobs = static_cast<int16_t>(total);
        part.part_index = static_cast<int16_t>(index);
        part.part_count = static_cast<int16_t>(count);
      });
}

blob_frame_t join_blob_parts(std::span<const blob_frame_t> parts) {
  if (parts.empty()) throw std::invalid_argument("join_blob_parts: no parts");
  blob_frame_t whole = detail::join_items(parts, &blob_frame_t::blobs);
  // processing ends with the slowest part
  for (const auto& part : parts)
    whole.processing_us = std::max(whole.processing_us, part.processing_us);
  whole.num_blobs = static_cast<int16_t>(whole.blobs.size());
  whole.part_index = 0;
  whole.part_count = 1;
  return whole;
}

}  // namespace syncap::proto
