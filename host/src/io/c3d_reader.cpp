// The layout follows the C3D user guide (c3d.org), as c3d_writer.cpp writes it: a 512-byte header
// block, the parameter section at the block the header's first byte names, the data from
// POINT:DATA_START, all in 512-byte blocks.
#include "io/c3d_reader.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <vector>

#include "io/import_error.hpp"
#include "io/unit_scale.hpp"

namespace syncap::io {
namespace {

constexpr std::size_t kBlockBytes = 512;
constexpr uint8_t kParameterKey = 0x50;
constexpr uint8_t kIntelProcessor = 84;

// One parameter's raw value: its type (-1 char, 1 byte, 2 int16, 4 float), dimensions, bytes.
struct Parameter {
  int8_t type = 0;
  std::vector<int> dimensions;
  std::vector<uint8_t> data;
};

class Reader {
 public:
  Reader(std::string path, std::vector<uint8_t> bytes)
      : path_(std::move(path)), bytes_(std::move(bytes)) {}

  [[noreturn]] void fail(const std::string& problem) const { throw ImportError(path_, problem); }

  void need(std::size_t at, std::size_t n, const char* what) const {
    if (at + n > bytes_.size()) {
      fail(std::string(what) + " at byte " + std::to_string(at) + ": the file ends at byte " +
           std::to_string(bytes_.size()));
    }
  }
  uint8_t u8(std::size_t at, const char* what) const {
    need(at, 1, what);
    return bytes_[at];
  }
  int16_t i16(std::size_t at, const char* what) const {
    need(at, 2, what);
    return static_cast<int16_t>(bytes_[at] | (bytes_[at + 1] << 8));
  }
  uint16_t u16(std::size_t at, const char* what) const {
    return static_cast<uint16_t>(i16(at, what));
  }
  float f32(std::size_t at, const char* what) const {
    need(at, 4, what);
    const uint32_t bits = static_cast<uint32_t>(bytes_[at]) | (bytes_[at + 1] << 8) |
                          (bytes_[at + 2] << 16) | (static_cast<uint32_t>(bytes_[at + 3]) << 24);
    float v = 0;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  std::string text(std::size_t at, std::size_t n, const char* what) const {
    need(at, n, what);
    return std::string(bytes_.begin() + static_cast<std::ptrdiff_t>(at),
                       bytes_.begin() + static_cast<std::ptrdiff_t>(at + n));
  }

  // "GROUP:NAME" -> its value.
  std::map<std::string, Parameter> parameters(std::size_t start) const;

 private:
  std::string path_;
  std::vector<uint8_t> bytes_;
};

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::map<std::string, Parameter> Reader::parameters(std::size_t start) const {
  // Its second byte is 0x50 in most files, 0 in some (Qualisys): the processor type tells.
  const uint8_t processor = u8(start + 3, "parameter section");
  if (processor < kIntelProcessor || processor > kIntelProcessor + 2)
    fail("no parameter section at byte " + std::to_string(start) + " (not a C3D file?)");
  if (processor != kIntelProcessor) {
    fail("processor type " + std::to_string(processor) +
         " (DEC 85 or MIPS 86): only Intel (84) files are read; convert it with ezc3d or Mokka");
  }
  std::map<int, std::string> groups;
  std::vector<std::pair<int, std::pair<std::string, Parameter>>> entries;
  std::size_t at = start + 4;
  while (true) {
    const int length = std::abs(static_cast<int8_t>(u8(at, "parameter entry")));
    if (length == 0) break;
    const int id = static_cast<int8_t>(u8(at + 1, "parameter entry"));
    const std::string name =
        upper(text(at + 2, static_cast<std::size_t>(length), "parameter name"));
    const std::size_t offset_at = at + 2 + static_cast<std::size_t>(length);
    const uint16_t next = u16(offset_at, "parameter entry");
    if (id < 0) {
      groups[-id] = name;
    } else {
      Parameter p;
      std::size_t body = offset_at + 2;
      p.type = static_cast<int8_t>(u8(body, "parameter type"));
      const int dims = u8(body + 1, "parameter dimensions");
      std::size_t count = 1;
      for (int d = 0; d < dims; ++d) {
        p.dimensions.push_back(u8(body + 2 + static_cast<std::size_t>(d), "parameter dimension"));
        count *= static_cast<std::size_t>(p.dimensions.back());
      }
      const std::size_t size = count * static_cast<std::size_t>(std::abs(p.type));
      const std::size_t data_at = body + 2 + static_cast<std::size_t>(dims);
      need(data_at, size, ("parameter " + name).c_str());
      p.data.assign(bytes_.begin() + static_cast<std::ptrdiff_t>(data_at),
                    bytes_.begin() + static_cast<std::ptrdiff_t>(data_at + size));
      entries.push_back({id, {name, std::move(p)}});
    }
    if (next == 0) break;
    at = offset_at + next;
  }
  std::map<std::string, Parameter> out;
  for (auto& [group, entry] : entries) {
    const auto g = groups.find(group);
    out[(g == groups.end() ? std::to_string(group) : g->second) + ":" + entry.first] =
        std::move(entry.second);
  }
  return out;
}

std::string trimmed(const std::string& s) {
  const std::size_t end = s.find_last_not_of(" \0", std::string::npos, 2);
  return end == std::string::npos ? "" : s.substr(0, end + 1);
}

// A char array's strings: dimensions (width, count).
std::vector<std::string> strings(const Parameter& p) {
  std::vector<std::string> out;
  if (p.type != -1 || p.dimensions.empty()) return out;
  const std::size_t width = static_cast<std::size_t>(p.dimensions[0]);
  const std::size_t count = p.dimensions.size() > 1 ? static_cast<std::size_t>(p.dimensions[1]) : 1;
  for (std::size_t i = 0; i < count && width > 0; ++i) {
    out.push_back(
        trimmed(std::string(p.data.begin() + static_cast<std::ptrdiff_t>(i * width),
                            p.data.begin() + static_cast<std::ptrdiff_t>((i + 1) * width))));
  }
  return out;
}

std::optional<double> first_float(const Parameter& p) {
  if (p.type != 4 || p.data.size() < 4) return std::nullopt;
  const uint32_t bits = static_cast<uint32_t>(p.data[0]) | (p.data[1] << 8) | (p.data[2] << 16) |
                        (static_cast<uint32_t>(p.data[3]) << 24);
  float v = 0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImportError(path, "cannot open the file");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

C3dFile read_c3d(const std::string& path) {
  const Reader r(path, read_bytes(path));
  const std::size_t parameter_block = r.u8(0, "header");
  if (r.u8(1, "header") != kParameterKey || parameter_block == 0)
    r.fail("the header's second byte is not 0x50: not a C3D file");
  const int points = r.u16(2, "header");
  const int analog_per_frame = r.u16(4, "header");
  const int first_frame = r.u16(6, "header");
  const int last_frame = r.u16(8, "header");
  const float scale = r.f32(12, "header");
  const int data_block = r.u16(16, "header");
  const float header_rate = r.f32(20, "header");
  const auto parameters = r.parameters((parameter_block - 1) * kBlockBytes);

  C3dFile out;
  tracking::MarkerTrajectories& t = out.trajectories;
  const auto rate = parameters.find("POINT:RATE");
  t.rate_hz =
      rate != parameters.end() ? first_float(rate->second).value_or(header_rate) : header_rate;
  if (!(t.rate_hz > 0)) r.fail("header: the frame rate is not positive");
  for (const char* key : {"POINT:LABELS", "POINT:LABELS2", "POINT:LABELS3"}) {
    const auto labels = parameters.find(key);
    if (labels == parameters.end()) continue;
    for (const std::string& l : strings(labels->second)) t.labels.push_back(l);
  }
  t.labels.resize(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    if (t.labels[static_cast<std::size_t>(i)].empty())
      t.labels[static_cast<std::size_t>(i)] = "M" + std::to_string(i + 1);
  }
  const auto units = parameters.find("POINT:UNITS");
  out.units = units == parameters.end() ? "mm" : strings(units->second).at(0);
  const std::optional<double> unit = millimetres_per(out.units);
  if (!unit) r.fail("POINT:UNITS: unknown unit '" + out.units + "' (mm, cm, m)");
  const double to_mm = *unit;

  const bool floats = scale < 0;
  const double point_scale = std::abs(scale);
  const std::size_t word = floats ? 4 : 2;
  const std::size_t frame_bytes =
      (4 * static_cast<std::size_t>(points) + static_cast<std::size_t>(analog_per_frame)) * word;
  const int frames = last_frame - first_frame + 1;
  if (frames < 0) r.fail("header: the last frame comes before the first");
  // Our exports keep the frame number of their first frame beside the header's 1.
  const auto ours = parameters.find("SYNCAP:FIRST_FRAME");
  const std::vector<std::string> ours_text =
      ours == parameters.end() ? std::vector<std::string>{} : strings(ours->second);
  char* end = nullptr;
  const long long ours_frame = ours_text.empty() ? 0 : std::strtoll(ours_text[0].c_str(), &end, 10);
  t.first_frame = ours_text.empty() || end == ours_text[0].c_str() ? first_frame : ours_frame;
  std::size_t at = (static_cast<std::size_t>(data_block) - 1) * kBlockBytes;
  auto value = [&](std::size_t where) {
    return floats ? static_cast<double>(r.f32(where, "3D data"))
                  : point_scale * r.i16(where, "3D data");
  };
  for (int f = 0; f < frames; ++f, at += frame_bytes) {
    r.need(at, 4 * static_cast<std::size_t>(points) * word,
           ("frame " + std::to_string(first_frame + f)).c_str());
    std::vector<std::optional<tracking::MarkerSample>> row(static_cast<std::size_t>(points));
    for (int m = 0; m < points; ++m) {
      const std::size_t p = at + 4 * static_cast<std::size_t>(m) * word;
      // The fourth word: camera mask (high byte) and residual (low byte); negative: missing.
      const double fourth =
          floats ? static_cast<double>(r.f32(p + 3 * word, "3D data")) : r.i16(p + 3 * word, "");
      if (fourth < 0) continue;
      const int packed = static_cast<int>(fourth);
      tracking::MarkerSample s;
      s.position_mm = to_mm * Eigen::Vector3d(value(p), value(p + word), value(p + 2 * word));
      s.residual_mm = to_mm * point_scale * (packed & 0xff);
      s.cameras = static_cast<uint32_t>((packed >> 8) & 0x7f);
      if (!s.position_mm.allFinite()) continue;
      row[static_cast<std::size_t>(m)] = s;
    }
    t.samples.push_back(std::move(row));
  }
  return out;
}

}  // namespace syncap::io
