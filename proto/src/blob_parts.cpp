#include "syncap/proto/blob_parts.hpp"

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
  const std::size_t per_part = blob_frame_t::MAX_BLOBS;
  const std::size_t count = std::max<std::size_t>(1, (total + per_part - 1) / per_part);
  std::vector<blob_frame_t> parts;
  parts.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    blob_frame_t part = frame;
    const std::size_t begin = i * per_part;
    const std::size_t end = std::min(total, begin + per_part);
    part.blobs.assign(frame.blobs.begin() + begin, frame.blobs.begin() + end);
    part.num_blobs = static_cast<int16_t>(end - begin);
    part.total_blobs = static_cast<int16_t>(total);
    part.part_index = static_cast<int16_t>(i);
    part.part_count = static_cast<int16_t>(count);
    parts.push_back(std::move(part));
  }
  return parts;
}

blob_frame_t join_blob_parts(std::span<const blob_frame_t> parts) {
  if (parts.empty()) throw std::invalid_argument("join_blob_parts: no parts");
  blob_frame_t whole = parts.front();
  whole.blobs.clear();
  for (const auto& part : parts) {
    whole.blobs.insert(whole.blobs.end(), part.blobs.begin(), part.blobs.end());
    // processing ends with the slowest part
    whole.processing_us = std::max(whole.processing_us, part.processing_us);
  }
  whole.num_blobs = static_cast<int16_t>(whole.blobs.size());
  whole.part_index = 0;
  whole.part_count = 1;
  return whole;
}

}  // namespace syncap::proto
