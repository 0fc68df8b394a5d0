// libFuzzer target: the image patch decoder (proto::decode_image_patch) on the parts of one
// camera's frame as the host's grouper hands them out (any order, duplicates refused before).
// Each part is read from the input as: tile_x, tile_y (int16), image_width, image_height
// (int16), encoding (int8), data length (uint8 x 8, so the fuzzer reaches the 1333-byte maximum),
// data.
//
// Contract: decode_image_patch never throws; every part given is either received or named in
// an error; the image and the known mask have the sensor's size (or none, for a sensor size it
// refuses), and nothing is known outside the tiles' rectangles.
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "fuzz_check.hpp"
#include "syncap/proto/image_patch.hpp"

namespace {

using syncap::image_patch_t;

std::vector<image_patch_t> parts_of(syncap::fuzz::ByteReader& in) {
  std::vector<image_patch_t> parts;
  while (in.left() > 0 && parts.size() < 6) {
    image_patch_t part{};
    part.camera_id = 2;
    part.frame_number = 64;
    part.tile_x = in.take<int16_t>();
    part.tile_y = in.take<int16_t>();
    part.image_width = in.take<int16_t>();
    part.image_height = in.take<int16_t>();
    part.encoding = in.take<int8_t>();
    part.data = in.bytes(std::size_t{in.take<uint8_t>()} * 8);
    part.data_size = static_cast<int16_t>(part.data.size());
    part.part_index = static_cast<int16_t>(parts.size());
    parts.push_back(std::move(part));
  }
  for (auto& part : parts) part.part_count = static_cast<int16_t>(parts.size());
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  syncap::fuzz::ByteReader in(data, size);
  const std::vector<image_patch_t> parts = parts_of(in);
  syncap::proto::ImagePatch patch;
  try {
    patch = syncap::proto::decode_image_patch(parts);
  } catch (...) {
    syncap::fuzz::fail("decode_image_patch threw");
  }
  if (parts.empty()) return 0;
  if (patch.image.empty()) {
    syncap::fuzz::check(patch.errors.size() == 1 && patch.parts_received == 0,
                        "a refused sensor size is one error and no part");
    return 0;
  }
  syncap::fuzz::check(patch.parts_received + static_cast<int>(patch.errors.size()) ==
                          static_cast<int>(parts.size()),
                      "a part neither received nor named in an error");
  const cv::Size sensor(parts.front().image_width, parts.front().image_height);
  syncap::fuzz::check(patch.image.size() == sensor && patch.known.size() == sensor,
                      "the patch is not the sensor's size");
  cv::Mat covered = cv::Mat::zeros(sensor, CV_8UC1);
  for (const image_patch_t& part : parts) {
    const cv::Rect r =
        cv::Rect(part.tile_x, part.tile_y, sensor.width, sensor.height) & cv::Rect({0, 0}, sensor);
    covered(r).setTo(255);
  }
  syncap::fuzz::check(cv::countNonZero(patch.known & ~covered) == 0,
                      "pixels known outside every tile");
  return 0;
}
