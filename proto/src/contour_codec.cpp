#include "syncap/proto/contour_codec.hpp"

#include <algorithm>
#include <cstdint>

namespace syncap::proto {
namespace {

constexpr std::size_t kMaxVarintBytes = 5;  // a 32-bit value
constexpr uint32_t kHoleBit = 1;
constexpr uint32_t kContinuesBit = 2;

uint32_t zigzag(int32_t v) {
  return (static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(v >> 31);
}
int32_t unzigzag(uint32_t u) { return static_cast<int32_t>(u >> 1) ^ -static_cast<int32_t>(u & 1); }

void put_varint(std::vector<uint8_t>& out, uint32_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

bool in_int16(int32_t v) { return v >= -32768 && v <= 32767; }

// `from` (within int16) moved by a step read from the data; summed in int64, so that no step can
// overflow (a step past INT32_MAX did: found by fuzzing, issue 15). Anything outside int16 is
// rejected by the caller.
ContourPoint stepped(ContourPoint from, int32_t dx, int32_t dy) {
  const auto clamp = [](int64_t v) {
    return static_cast<int32_t>(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX));
  };
  return {clamp(int64_t{from.x} + dx), clamp(int64_t{from.y} + dy)};
}

void check_coordinate(int32_t v) {
  if (!in_int16(v)) {
    throw std::invalid_argument("contour coordinate " + std::to_string(v) + " outside int16");
  }
}

// Builds the parts: each holds whole pieces; a contour that does not fit the room left is cut
// into a piece here and a `continues` piece in the next part.
class PartWriter {
 public:
  PartWriter(int camera_id, int64_t frame_number, int width, int height) {
    templ_.camera_id = static_cast<int16_t>(camera_id);
    templ_.frame_number = frame_number;
    templ_.image_width = static_cast<int16_t>(width);
    templ_.image_height = static_cast<int16_t>(height);
  }

  void add(const Contour& contour) {
    if (contour.points.empty()) {  // kept so that the receiver sees what was sent
      if (data_.size() + kMaxVarintBytes > silhouette_part_t::MAX_DATA) start_part();
      put_varint(data_, contour.hole ? kHoleBit : 0);
      ++pieces_;
      return;
    }
    std::size_t next = 0;
    bool continues = false;
    while (next < contour.points.size()) {
      const std::size_t taken = write_piece(contour, next, continues);
      if (taken == 0) {  // not one more point fits: a fresh part always takes some
        start_part();
        continue;
      }
      next += taken;
      continues = true;
    }
  }

  std::vector<silhouette_part_t> finish() {
    close_part();
    for (auto& part : parts_) part.part_count = static_cast<int16_t>(parts_.size());
    return std::move(parts_);
  }

 private:
  // Writes as many points from `first` on as fit in the current part; returns how many.
  std::size_t write_piece(const Contour& c, std::size_t first, bool continues) {
    const std::size_t used = data_.size() + kMaxVarintBytes;  // room kept for the header
    if (used >= silhouette_part_t::MAX_DATA) return 0;
    const std::size_t room = silhouette_part_t::MAX_DATA - used;
    std::vector<uint8_t> body;
    std::size_t n = 0;
    for (std::size_t i = first; i < c.points.size(); ++i, ++n) {
      const ContourPoint p = c.points[i];
      check_coordinate(p.x);
      check_coordinate(p.y);
      const ContourPoint step =
          n == 0 ? p : ContourPoint{p.x - c.points[i - 1].x, p.y - c.points[i - 1].y};
      const std::size_t before = body.size();
      put_varint(body, zigzag(step.x));
      put_varint(body, zigzag(step.y));
      if (body.size() > room) {
        body.resize(before);
        break;
      }
    }
    if (n == 0) return 0;
    put_varint(data_, (static_cast<uint32_t>(n) << 2) | (continues ? kContinuesBit : 0) |
                          (c.hole ? kHoleBit : 0));
    data_.insert(data_.end(), body.begin(), body.end());
    ++pieces_;
    return n;
  }

  void start_part() { close_part(); }

  void close_part() {
    silhouette_part_t part = templ_;
    part.part_index = static_cast<int16_t>(parts_.size());
    part.num_pieces = static_cast<int16_t>(pieces_);
    part.data_size = static_cast<int16_t>(data_.size());
    part.data = data_;
    parts_.push_back(std::move(part));
    data_.clear();
    pieces_ = 0;
  }

  silhouette_part_t templ_{};
  std::vector<silhouette_part_t> parts_;
  std::vector<uint8_t> data_;
  int pieces_ = 0;
};

class PartReader {
 public:
  explicit PartReader(const silhouette_part_t& part) : part_(part) {}

  uint32_t varint() {
    uint32_t value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      if (pos_ >= part_.data.size()) fail("data ends inside a varint");
      const uint8_t byte = part_.data[pos_++];
      value |= static_cast<uint32_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    fail("varint longer than 5 bytes");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw ContourDecodeError(
        "silhouette camera " + std::to_string(part_.camera_id) + " frame " +
        std::to_string(part_.frame_number) + " part " + std::to_string(part_.part_index) + "/" +
        std::to_string(part_.part_count) + " byte " + std::to_string(pos_) + ": " + what);
  }

  std::size_t pos() const { return pos_; }

 private:
  const silhouette_part_t& part_;
  std::size_t pos_ = 0;
};

void decode_part(const silhouette_part_t& part, bool previous_part_present,
                 std::vector<Contour>& contours) {
  if (part.data_size != static_cast<int16_t>(part.data.size()) || part.data_size < 0) {
    PartReader(part).fail("data_size does not match the data");
  }
  PartReader in(part);
  for (int piece = 0; piece < part.num_pieces; ++piece) {
    const uint32_t header = in.varint();
    const uint32_t count = header >> 2;
    if (count > part.data.size()) in.fail("piece claims " + std::to_string(count) + " points");
    const bool continues = (header & kContinuesBit) != 0;
    const bool extend = continues && piece == 0 ? previous_part_present && !contours.empty()
                                                : continues && !contours.empty();
    if (!extend) {
      contours.push_back(Contour{(header & kHoleBit) != 0, !continues, {}});
    }
    Contour& contour = contours.back();
    ContourPoint p{};
    for (uint32_t i = 0; i < count; ++i) {
      const int32_t dx = unzigzag(in.varint());
      const int32_t dy = unzigzag(in.varint());
      p = i == 0 ? ContourPoint{dx, dy} : stepped(p, dx, dy);
      if (!in_int16(p.x) || !in_int16(p.y)) in.fail("point outside the coordinate range int16");
      contour.points.push_back(p);
    }
  }
  if (in.pos() != part.data.size()) in.fail("bytes left after the last piece");
}

}  // namespace

std::vector<silhouette_part_t> encode_silhouette(int camera_id, int64_t frame_number,
                                                 int image_width, int image_height,
                                                 std::span<const Contour> contours) {
  PartWriter writer(camera_id, frame_number, image_width, image_height);
  for (const Contour& contour : contours) writer.add(contour);
  return writer.finish();
}

Silhouette decode_silhouette(std::span<const silhouette_part_t> parts) {
  Silhouette out;
  if (parts.empty()) return out;
  out.camera_id = parts.front().camera_id;
  out.frame_number = parts.front().frame_number;
  out.image_width = parts.front().image_width;
  out.image_height = parts.front().image_height;
  out.part_count = parts.front().part_count;
  int expected_index = 0;
  for (const silhouette_part_t& part : parts) {
    const bool previous_present = part.part_index == expected_index;
    if (!previous_present && !out.contours.empty()) out.contours.back().complete = false;
    decode_part(part, previous_present, out.contours);
    expected_index = part.part_index + 1;
    ++out.parts_received;
  }
  if (expected_index != out.part_count && !out.contours.empty()) {
    out.contours.back().complete = false;
  }
  return out;
}

}  // namespace syncap::proto
