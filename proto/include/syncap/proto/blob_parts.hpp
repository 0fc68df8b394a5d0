// Splitting a frame's blobs into datagram-sized blob_frame_t parts, and joining them again.
#pragma once

#include <span>
#include <vector>

#include "syncap/blob_frame_t.hpp"

namespace syncap::proto {

// Splits `frame` (header fields set, any number of blobs) into parts of at most
// blob_frame_t::MAX_BLOBS blobs. A frame without blobs gives one part. Throws
// std::invalid_argument when the blob count does not fit total_blobs' int16.
std::vector<blob_frame_t> split_blob_frame(const blob_frame_t& frame);

// Joins the parts of one frame (sorted by part_index, as PartCollector hands them out) into one
// frame with part_count 1. Missing parts simply contribute no blobs: total_blobs still tells how
// many were sent, so the caller can see the loss.
blob_frame_t join_blob_parts(std::span<const blob_frame_t> parts);

}  // namespace syncap::proto
