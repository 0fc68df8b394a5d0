// The contour codec: how silhouette_part_t.data carries polygons.
//
// A part's data is a sequence of pieces. Each piece is
//   varint  header   = (point_count << 2) | (continues << 1) | hole
//   varint  x0, y0   zigzag-encoded absolute pixel coordinates of the first point
//   varint  dx, dy   zigzag-encoded step to each following point (point_count - 1 times)
// Varints are little-endian base-128 (7 bits a byte, high bit = more). A contour traced along
// pixel edges steps by -1..1 per point, so a point costs two bytes; a simplified polygon costs
// two to six. A piece with `continues` set extends the polygon of the piece before it (possibly
// in the previous part), which lets a polygon longer than one datagram span parts.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "syncap/silhouette_part_t.hpp"

namespace syncap::proto {

struct ContourPoint {
  int32_t x = 0;
  int32_t y = 0;
  bool operator==(const ContourPoint&) const = default;
};

struct Contour {
  bool hole = false;     // inner boundary of the foreground
  bool complete = true;  // false when a part holding some of its points was lost
  std::vector<ContourPoint> points;
  bool operator==(const Contour&) const = default;
};

struct Silhouette {
  int camera_id = 0;
  int64_t frame_number = 0;
  int image_width = 0;
  int image_height = 0;
  int parts_received = 0;
  int part_count = 0;
  std::vector<Contour> contours;
};

// Thrown for data that does not decode; what() names camera, frame, part and byte offset.
class ContourDecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Encodes the contours of one frame into parts whose data fit silhouette_part_t::MAX_DATA.
// Coordinates must lie in -32768..32767. A frame without contours gives one empty part.
std::vector<silhouette_part_t> encode_silhouette(int camera_id, int64_t frame_number,
                                                 int image_width, int image_height,
                                                 std::span<const Contour> contours);

// Decodes the parts of one frame (sorted by part_index, possibly with some missing) into its
// contours. A continuation whose first half was in a lost part starts a contour marked
// incomplete, as does a contour whose continuation was lost.
Silhouette decode_silhouette(std::span<const silhouette_part_t> parts);

}  // namespace syncap::proto
