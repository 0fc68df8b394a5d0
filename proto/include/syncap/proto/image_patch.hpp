// The image patch codec: how image_patch_t carries the grey values where the person is, for the
// host's surface matching (docs/design/matching.md, "Live").
//
// The edge cuts the silhouette's bounding box (widened by a margin) out of the frame, sets the
// pixels farther than the margin from the silhouette to 0 (they compress to almost nothing),
// and cuts it into tiles: columns of at most kMaxTileWidth, each cut into runs of whole rows
// whose PNG fits image_patch_t::MAX_DATA. Each tile decodes on its own; a lost tile leaves its
// pixels unknown, and the rest of the patch stands.
//
// Separate from syncap_proto (library syncap_proto_image) so that the message library itself
// needs no OpenCV.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

#include "syncap/image_patch_t.hpp"

namespace syncap::proto {

// A PNG row of 1024 pixels that do not compress (1025 bytes with its filter byte, plus zlib's
// and PNG's framing) still fits one part.
inline constexpr int kMaxTileWidth = 1024;

struct PatchEncoding {
  // Pixels within this distance of the silhouette are sent: least-squares matching reads a
  // window's grey values and their gradients a pixel or two beyond the outline.
  int margin_px = 4;
  int png_compression = 3;  // zlib level 0-9 (OpenCV's IMWRITE_PNG_COMPRESSION)
};

// Encodes the grey values of `image` (8-bit, one channel) where `mask` (8-bit, same size) is
// non-zero, widened by options.margin_px, into parts of one frame. `origin` is the sensor
// position of image(0, 0) (a sensor window), `sensor_size` the full sensor's (empty: the
// image's). No foreground: no parts. std::invalid_argument for images of another type or size.
std::vector<image_patch_t> encode_image_patch(int camera_id, int64_t frame_number,
                                              const cv::Mat& image, const cv::Mat& mask,
                                              cv::Point origin = {}, cv::Size sensor_size = {},
                                              const PatchEncoding& options = {});

// One camera's patch of one frame, joined from the parts that arrived.
struct ImagePatch {
  int camera_id = 0;
  int64_t frame_number = 0;
  cv::Mat image;  // 8-bit grey, the full sensor's size; 0 where no tile arrived
  cv::Mat known;  // 8-bit, 255 where a tile arrived (the sent pixels and the zeros beside them)
  int parts_received = 0;
  int part_count = 0;
  // One line per part that did not decode (bad encoding, a tile outside the image, a corrupt
  // PNG), naming camera, frame and part; the other parts are kept.
  std::vector<std::string> errors;
  bool complete() const { return parts_received == part_count && errors.empty(); }
};

// Joins the parts of one camera's frame (any order, some missing). A part whose sensor size
// differs from the first part's, or outside 1..8192 pixels, is refused like a corrupt one.
ImagePatch decode_image_patch(std::span<const image_patch_t> parts);

}  // namespace syncap::proto
