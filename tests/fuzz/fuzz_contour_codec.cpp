// libFuzzer target: the contour codec's decoder (proto::decode_silhouette) on the parts of one
// frame as PartCollector hands them out, sorted by part_index with some possibly missing. Each
// part is read from the input as: part_index (int8), num_pieces (int8), data length (uint8 x 8,
// so the fuzzer reaches the 1336-byte maximum), data.
//
// Contract: decode_silhouette returns or throws proto::ContourDecodeError, nothing else; it
// reports every part it was given; and when every decoded contour is complete and within the
// encoder's coordinate range, encoding them and decoding the result gives them back.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_check.hpp"
#include "syncap/proto/contour_codec.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace {

using syncap::silhouette_part_t;
using syncap::proto::Contour;

constexpr int kCamera = 3;
constexpr int64_t kFrame = 1234;

std::vector<silhouette_part_t> parts_of(syncap::fuzz::ByteReader& in) {
  std::vector<silhouette_part_t> parts;
  while (in.left() > 0 && parts.size() < 8) {
    silhouette_part_t part{};
    part.camera_id = kCamera;
    part.frame_number = kFrame;
    part.image_width = 640;
    part.image_height = 480;
    part.part_index = in.take<int8_t>();
    part.num_pieces = in.take<int8_t>();
    part.data = in.bytes(std::size_t{in.take<uint8_t>()} * 8);
    part.data_size = static_cast<int16_t>(part.data.size());
    parts.push_back(std::move(part));
  }
  // As the collector hands them out: sorted, no index twice, part_count above every index.
  std::sort(parts.begin(), parts.end(),
            [](const auto& a, const auto& b) { return a.part_index < b.part_index; });
  parts.erase(
      std::unique(parts.begin(), parts.end(),
                  [](const auto& a, const auto& b) { return a.part_index == b.part_index; }),
      parts.end());
  std::erase_if(parts, [](const auto& p) { return p.part_index < 0; });
  const int16_t count = parts.empty() ? 1 : static_cast<int16_t>(parts.back().part_index + 1);
  for (auto& part : parts) part.part_count = count;
  return parts;
}

bool encodable(const std::vector<Contour>& contours) {
  const auto in_range = [](int32_t v) { return v >= -32768 && v <= 32767; };
  return std::all_of(contours.begin(), contours.end(), [&](const Contour& c) {
    return c.complete && std::all_of(c.points.begin(), c.points.end(),
                                     [&](const auto& p) { return in_range(p.x) && in_range(p.y); });
  });
}

void check_round_trip(const std::vector<Contour>& contours) {
  const std::vector<silhouette_part_t> parts =
      syncap::proto::encode_silhouette(kCamera, kFrame, 640, 480, contours);
  for (const auto& part : parts) {
    syncap::fuzz::check(part.data_size <= silhouette_part_t::MAX_DATA,
                        "an encoded part exceeds MAX_DATA");
  }
  syncap::fuzz::check(syncap::proto::decode_silhouette(parts).contours == contours,
                      "encode -> decode does not give the decoded contours back");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  syncap::fuzz::ByteReader in(data, size);
  const std::vector<silhouette_part_t> parts = parts_of(in);
  syncap::proto::Silhouette silhouette;
  const bool decoded = syncap::fuzz::decodes<syncap::proto::ContourDecodeError>(
      "decode_silhouette", [&] { silhouette = syncap::proto::decode_silhouette(parts); });
  if (!decoded) return 0;
  syncap::fuzz::check(silhouette.parts_received == static_cast<int>(parts.size()),
                      "parts_received differs from the parts given");
  if (encodable(silhouette.contours)) check_round_trip(silhouette.contours);
  return 0;
}
