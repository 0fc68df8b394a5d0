// Splitting a frame's 3D markers into datagram-sized marker_frame_t parts, and joining them.
#pragma once

#include <span>
#include <vector>

#include "syncap/marker_frame_t.hpp"

namespace syncap::proto {

// Parts of at most marker_frame_t::MAX_MARKERS markers (one part when there are none); throws
// std::invalid_argument when the count does not fit total_markers' int16.
std::vector<marker_frame_t> split_marker_frame(const marker_frame_t& frame);

// The parts of one frame (any order, some possibly missing) as one frame with part_count 1;
// total_markers still tells how many were sent.
marker_frame_t join_marker_parts(std::span<const marker_frame_t> parts);

}  // namespace syncap::proto
