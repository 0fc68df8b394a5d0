// The layout follows the C3D user guide (c3d.org): a 512-byte header block, the parameter section
// from block 2, then the 3D data, all in 512-byte blocks, little-endian (Intel processor type).
#include "io/c3d_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/export_checks.hpp"
#include "io/export_error.hpp"

namespace syncap::io {
namespace {

constexpr std::size_t kBlockBytes = 512;
constexpr uint8_t kParameterKey = 0x50;           // second byte of the header and parameters
constexpr uint8_t kIntelProcessor = 84;           // 83 + 1: Intel/PC floats and byte order
constexpr uint8_t kParameterBlock = 2;            // the parameter section starts at block 2
constexpr std::size_t kMaxParameterBlocks = 255;  // its block count is one byte
constexpr std::size_t kLabelsPerParameter = 255;  // an array dimension is one byte
constexpr std::size_t kMaxMarkers = 32767;        // POINT:USED is a signed 16-bit word
constexpr std::size_t kMaxFrames = 0xffffffff;    // TRIAL:ACTUAL_END_FIELD: two words
constexpr std::size_t kMaxWordFrame = 65535;      // header's last frame and POINT:FRAMES: one word
constexpr uint16_t kFourCharEventLabels = 12345;  // header key: event labels have 4 characters
constexpr float kInvalidSampleWord = -1.0f;       // 4th word of a point not seen in a frame
constexpr double kCoordinatesPerScaleUnit =
    32000;  // the guide's POINT:SCALE: max coordinate / 32000

enum : int8_t { kChar = -1, kInt16 = 2, kFloat = 4 };  // parameter data types
enum : int8_t { kPointGroup = 1, kAnalogGroup = 2, kTrialGroup = 3, kSyncapGroup = 4 };

// Little-endian bytes, the C3D Intel layout whatever the host's byte order.
class Bytes {
 public:
  void u8(uint8_t v) { data_.push_back(static_cast<char>(v)); }
  void u16(uint16_t v) {
    u8(static_cast<uint8_t>(v & 0xff));
    u8(static_cast<uint8_t>(v >> 8));
  }
  void f32(float v) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    u16(static_cast<uint16_t>(bits & 0xffff));
    u16(static_cast<uint16_t>(bits >> 16));
  }
  void text(std::string_view s) { data_.insert(data_.end(), s.begin(), s.end()); }
  void append(const Bytes& other) {
    data_.insert(data_.end(), other.data_.begin(), other.data_.end());
  }
  void patch_u8(std::size_t at, uint8_t v) { data_.at(at) = static_cast<char>(v); }
  void patch_u16(std::size_t at, uint16_t v) {
    patch_u8(at, static_cast<uint8_t>(v & 0xff));
    patch_u8(at + 1, static_cast<uint8_t>(v >> 8));
  }
  void pad_to(std::size_t size) { data_.resize(std::max(size, data_.size())); }
  void pad_to_block() { pad_to((data_.size() + kBlockBytes - 1) / kBlockBytes * kBlockBytes); }
  std::size_t size() const { return data_.size(); }
  void write_to(std::ostream& out) const {
    out.write(data_.data(), static_cast<std::streamsize>(data_.size()));
  }

 private:
  std::vector<char> data_;
};

// The parameter section: groups and their parameters, each entry pointing to the next.
class ParameterSection {
 public:
  ParameterSection() {
    bytes_.u8(1);  // the first entry follows this 4-byte header directly
    bytes_.u8(kParameterKey);
    bytes_.u8(0);  // block count, known at the end
    bytes_.u8(kIntelProcessor);
  }

  void group(int8_t id, std::string_view name, std::string_view description) {
    entry(name, static_cast<int8_t>(-id), Bytes{}, description);
  }
  // Returns where the value lies in the section, for a value known only later.
  std::size_t int16(int8_t group, std::string_view name, uint16_t value,
                    std::string_view description) {
    Bytes body = typed(kInt16, {});
    body.u16(value);
    return entry(name, group, body, description) + 2;  // past type and dimension count
  }
  void int16s(int8_t group, std::string_view name, const std::vector<uint16_t>& values,
              std::string_view description) {
    Bytes body = typed(kInt16, {static_cast<uint8_t>(values.size())});
    for (uint16_t v : values) body.u16(v);
    entry(name, group, body, description);
  }
  void real(int8_t group, std::string_view name, float value, std::string_view description) {
    Bytes body = typed(kFloat, {});
    body.f32(value);
    entry(name, group, body, description);
  }
  void text(int8_t group, std::string_view name, std::string_view value,
            std::string_view description) {
    Bytes body = typed(kChar, {static_cast<uint8_t>(value.size())});
    body.text(value);
    entry(name, group, body, description);
  }
  void texts(int8_t group, std::string_view name, const std::vector<std::string>& values,
             std::string_view description);

  // Ends the section (the last entry points nowhere, whole blocks); returns its block count.
  std::size_t finish() {
    bytes_.patch_u16(last_offset_at_, 0);
    bytes_.pad_to_block();
    const std::size_t blocks = bytes_.size() / kBlockBytes;
    bytes_.patch_u8(2, static_cast<uint8_t>(std::min(blocks, kMaxParameterBlocks)));
    return blocks;
  }
  void patch_u16(std::size_t at, uint16_t v) { bytes_.patch_u16(at, v); }
  const Bytes& bytes() const { return bytes_; }

 private:
  static Bytes typed(int8_t type, const std::vector<uint8_t>& dimensions) {
    Bytes body;
    body.u8(static_cast<uint8_t>(type));
    body.u8(static_cast<uint8_t>(dimensions.size()));
    for (uint8_t d : dimensions) body.u8(d);
    return body;
  }
  // Appends one entry; returns where its body starts.
  std::size_t entry(std::string_view name, int8_t id, const Bytes& body,
                    std::string_view description) {
    bytes_.u8(static_cast<uint8_t>(name.size()));
    bytes_.u8(static_cast<uint8_t>(id));
    bytes_.text(name);
    last_offset_at_ = bytes_.size();
    // From this word to the next entry: itself, the body, the description and its length.
    bytes_.u16(static_cast<uint16_t>(2 + body.size() + 1 + description.size()));
    const std::size_t body_at = bytes_.size();
    bytes_.append(body);
    bytes_.u8(static_cast<uint8_t>(description.size()));
    bytes_.text(description);
    return body_at;
  }

  Bytes bytes_;
  std::size_t last_offset_at_ = 0;
};

// A text array: dimensions (width, count), each string padded with spaces to the longest.
void ParameterSection::texts(int8_t group, std::string_view name,
                             const std::vector<std::string>& values, std::string_view description) {
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  Bytes body = typed(kChar, {static_cast<uint8_t>(width), static_cast<uint8_t>(values.size())});
  for (const auto& v : values) {
    body.text(v);
    body.text(std::string(width - v.size(), ' '));
  }
  entry(name, group, body, description);
}

// What the header and parameters say about the whole recording.
struct C3dLayout {
  std::size_t markers = 0;
  std::size_t frames = 0;
  float rate_hz = 0;
  float scale = 0;  // negative: float data; its magnitude scales the residuals
};

// The guide's scale, largest coordinate / 32000, so that the file could be converted to integers;
// 1 mm when every coordinate is 0.
float point_scale(const tracking::MarkerTrajectories& trajectories) {
  double largest = 1.0;
  for (const auto& row : trajectories.samples) {
    for (const auto& sample : row) {
      if (sample) largest = std::max(largest, sample->position_mm.cwiseAbs().maxCoeff());
    }
  }
  return -static_cast<float>(largest / kCoordinatesPerScaleUnit);
}

// Labels and descriptions, 255 to a parameter: LABELS, LABELS2, LABELS3, ...
void add_point_names(ParameterSection& section, const std::vector<std::string>& labels) {
  for (std::size_t first = 0, part = 1; first < labels.size();
       first += kLabelsPerParameter, ++part) {
    const std::size_t last = std::min(labels.size(), first + kLabelsPerParameter);
    const std::string suffix = part == 1 ? "" : std::to_string(part);
    section.texts(kPointGroup, "LABELS" + suffix,
                  std::vector<std::string>(labels.begin() + first, labels.begin() + last),
                  "marker names");
    section.texts(kPointGroup, "DESCRIPTIONS" + suffix,
                  std::vector<std::string>(last - first, "tracked marker"), "marker descriptions");
  }
}

// Returns where POINT:DATA_START's value lies, filled in once the section's size is known.
std::size_t add_point_group(ParameterSection& section, const C3dLayout& layout,
                            const std::vector<std::string>& labels) {
  section.group(kPointGroup, "POINT", "3D marker trajectories");
  section.int16(kPointGroup, "USED", static_cast<uint16_t>(layout.markers), "number of markers");
  // An unsigned word; 65535 for longer recordings, whose count TRIAL:ACTUAL_END_FIELD holds.
  section.int16(kPointGroup, "FRAMES",
                static_cast<uint16_t>(std::min(layout.frames, kMaxWordFrame)), "number of frames");
  const std::size_t data_start_at =
      section.int16(kPointGroup, "DATA_START", 0, "first block of the 3D data");
  section.real(kPointGroup, "SCALE", layout.scale, "negative: float data; residual units in mm");
  section.real(kPointGroup, "RATE", layout.rate_hz, "frames per second");
  add_point_names(section, labels);
  section.text(kPointGroup, "UNITS", "mm", "unit of the coordinates");
  return data_start_at;
}

void add_other_groups(ParameterSection& section, const C3dLayout& layout, int64_t first_frame) {
  section.group(kAnalogGroup, "ANALOG", "no analog channels");
  section.int16(kAnalogGroup, "USED", 0, "number of analog channels");
  section.real(kAnalogGroup, "RATE", 0.0f, "no analog samples");
  // Frame numbers as two words, low first, for recordings past the header's 65535 frames.
  const auto words = [](std::size_t frame) {
    return std::vector<uint16_t>{static_cast<uint16_t>(frame & 0xffff),
                                 static_cast<uint16_t>(frame >> 16)};
  };
  section.group(kTrialGroup, "TRIAL", "the recorded frames");
  section.int16s(kTrialGroup, "ACTUAL_START_FIELD", words(1), "first frame");
  section.int16s(kTrialGroup, "ACTUAL_END_FIELD", words(layout.frames), "last frame");
  section.group(kSyncapGroup, "SYNCAP", "origin of the export");
  section.text(kSyncapGroup, "FIRST_FRAME", std::to_string(first_frame),
               "syncap frame number of C3D frame 1");
}

// The 512-byte header block; words are numbered from 1 as in the guide.
Bytes header_block(const C3dLayout& layout, uint16_t data_start) {
  Bytes header;
  header.u8(kParameterBlock);
  header.u8(kParameterKey);
  header.u16(static_cast<uint16_t>(layout.markers));                          // word 2
  header.u16(0);                                                              // 3: analog
  header.u16(1);                                                              // 4: first frame
  header.u16(static_cast<uint16_t>(std::min(layout.frames, kMaxWordFrame)));  // 5: last frame
  header.u16(0);                     // 6: largest interpolation gap: none interpolated
  header.f32(layout.scale);          // 7-8
  header.u16(data_start);            // 9
  header.u16(0);                     // 10: analog samples per frame
  header.f32(layout.rate_hz);        // 11-12
  header.pad_to(2 * 149);            // 13-149: reserved, no label and range section
  header.u16(kFourCharEventLabels);  // 150
  header.u16(0);                     // 151: no events
  header.pad_to(kBlockBytes);
  return header;
}

// The 4th word of a seen point: the integer (camera mask << 8 | residual / |scale|) as a float.
// A residual of 0 stays 0, the guide's mark of a point that was not measured (interpolated);
// a measured one is at least 1 unit and saturates at 255.
float residual_word(const tracking::MarkerSample& sample, float scale) {
  const double units = sample.residual_mm / std::fabs(static_cast<double>(scale));
  const long residual = sample.residual_mm == 0 ? 0 : std::clamp(std::lround(units), 1L, 255L);
  return static_cast<float>(static_cast<long>(sample.cameras & 0x7f) << 8 | residual);
}

void write_frame(std::ostream& out, const std::vector<std::optional<tracking::MarkerSample>>& row,
                 float scale) {
  Bytes frame;
  for (const auto& sample : row) {
    if (sample) {
      for (int axis = 0; axis < 3; ++axis) frame.f32(static_cast<float>(sample->position_mm[axis]));
      frame.f32(residual_word(*sample, scale));
    } else {
      for (int axis = 0; axis < 3; ++axis) frame.f32(0.0f);
      frame.f32(kInvalidSampleWord);
    }
  }
  frame.write_to(out);
}

void check_c3d_limits(const tracking::MarkerTrajectories& trajectories, const std::string& path) {
  check_exportable(trajectories, path);
  if (trajectories.labels.size() > kMaxMarkers) {
    throw ExportError(path, std::to_string(trajectories.labels.size()) +
                                " markers: C3D holds at most " + std::to_string(kMaxMarkers));
  }
  if (trajectories.samples.size() > kMaxFrames) {
    throw ExportError(path, std::to_string(trajectories.samples.size()) +
                                " frames: this C3D export holds at most " +
                                std::to_string(kMaxFrames));
  }
}

}  // namespace

void write_c3d(const std::string& path, const tracking::MarkerTrajectories& trajectories) {
  check_c3d_limits(trajectories, path);
  C3dLayout layout;
  layout.markers = trajectories.labels.size();
  layout.frames = trajectories.samples.size();
  layout.rate_hz = static_cast<float>(trajectories.rate_hz);
  layout.scale = point_scale(trajectories);

  ParameterSection section;
  const std::size_t data_start_at = add_point_group(section, layout, trajectories.labels);
  add_other_groups(section, layout, trajectories.first_frame);
  const std::size_t parameter_blocks = section.finish();
  if (parameter_blocks > kMaxParameterBlocks) {
    throw ExportError(path, "the labels need " + std::to_string(parameter_blocks) +
                                " parameter blocks, C3D allows " +
                                std::to_string(kMaxParameterBlocks));
  }
  const auto data_start = static_cast<uint16_t>(kParameterBlock + parameter_blocks);
  section.patch_u16(data_start_at, data_start);

  write_file_atomically(path, [&](std::ostream& out) {
    header_block(layout, data_start).write_to(out);
    section.bytes().write_to(out);
    for (const auto& row : trajectories.samples) write_frame(out, row, layout.scale);
    // The data section too ends on a whole block.
    const std::size_t data_bytes = layout.frames * layout.markers * 16;
    out << std::string((kBlockBytes - data_bytes % kBlockBytes) % kBlockBytes, '\0');
  });
}

}  // namespace syncap::io
