// A minimal C3D reader for the tests: the header words, every parameter by "GROUP:NAME" and the
// float 3D data, read straight from the bytes as the C3D user guide lays them out (Intel only).
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace syncap::io::testing {

struct C3dParameter {
  int type = 0;  // -1 char, 1 byte, 2 int16, 4 float
  std::vector<int> dimensions;
  std::vector<uint8_t> data;
  std::string description;

  uint16_t word(std::size_t i = 0) const {
    return static_cast<uint16_t>(data.at(2 * i) | data.at(2 * i + 1) << 8);
  }
  float real() const {
    float v = 0;
    std::memcpy(&v, data.data(), sizeof v);
    return v;
  }
  // The strings of a (width, count) char array, trailing spaces kept.
  std::vector<std::string> strings() const {
    std::vector<std::string> out;
    const std::size_t width = static_cast<std::size_t>(dimensions.at(0));
    for (std::size_t at = 0; at + width <= data.size(); at += width) {
      out.emplace_back(data.begin() + static_cast<long>(at),
                       data.begin() + static_cast<long>(at + width));
    }
    return out;
  }
  std::string text() const { return std::string(data.begin(), data.end()); }
};

struct C3dPoint {
  float x, y, z, fourth;
};

class C3dTestReader {
 public:
  explicit C3dTestReader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open " + path);
    bytes_.assign(std::istreambuf_iterator<char>(in), {});
    read_parameters();
  }
  std::size_t size() const { return bytes_.size(); }
  uint8_t byte(std::size_t at) const { return static_cast<uint8_t>(bytes_.at(at)); }
  // Header word n, numbered from 1 as in the guide.
  uint16_t header_word(int n) const { return u16(2 * static_cast<std::size_t>(n - 1)); }
  float header_float(int n) const { return f32(2 * static_cast<std::size_t>(n - 1)); }
  const std::map<std::string, C3dParameter>& parameters() const { return parameters_; }
  const C3dParameter& parameter(const std::string& key) const { return parameters_.at(key); }
  uint8_t parameter_blocks() const { return byte(512 + 2); }
  uint8_t processor() const { return byte(512 + 3); }

  // Point m of frame f (0-based) in the data section named by the header.
  C3dPoint point(std::size_t f, std::size_t m, std::size_t markers) const {
    const std::size_t at = (header_word(9) - 1u) * 512u + (f * markers + m) * 16u;
    return {f32(at), f32(at + 4), f32(at + 8), f32(at + 12)};
  }

 private:
  uint16_t u16(std::size_t at) const { return static_cast<uint16_t>(byte(at) | byte(at + 1) << 8); }
  float f32(std::size_t at) const {
    if (at + 4 > bytes_.size()) throw std::out_of_range("float past the end");
    float v = 0;
    std::memcpy(&v, bytes_.data() + at, sizeof v);
    return v;
  }
  void read_parameters() {
    std::map<int, std::string> groups;
    std::size_t at = (byte(0) - 1u) * 512u + byte((byte(0) - 1u) * 512u) + 3u;
    while (true) {
      const int name_length = static_cast<int8_t>(byte(at));
      if (name_length == 0) break;
      const int id = static_cast<int8_t>(byte(at + 1));
      const std::size_t length =
          static_cast<std::size_t>(name_length < 0 ? -name_length : name_length);
      const std::string name(bytes_.begin() + static_cast<long>(at + 2),
                             bytes_.begin() + static_cast<long>(at + 2 + length));
      const std::size_t offset_at = at + 2 + length;
      const uint16_t offset = u16(offset_at);
      if (id < 0) {
        groups[-id] = name;
      } else {
        parameters_[groups.at(id) + ":" + name] = read_parameter(offset_at + 2);
      }
      if (offset == 0) break;
      at = offset_at + offset;
    }
  }
  C3dParameter read_parameter(std::size_t at) const {
    C3dParameter p;
    p.type = static_cast<int8_t>(byte(at));
    const int dimension_count = byte(at + 1);
    std::size_t count = 1;
    for (int d = 0; d < dimension_count; ++d) {
      p.dimensions.push_back(byte(at + 2 + static_cast<std::size_t>(d)));
      count *= static_cast<std::size_t>(p.dimensions.back());
    }
    const std::size_t data_at = at + 2 + static_cast<std::size_t>(dimension_count);
    const std::size_t data_bytes = count * static_cast<std::size_t>(p.type < 0 ? 1 : p.type);
    p.data.assign(bytes_.begin() + static_cast<long>(data_at),
                  bytes_.begin() + static_cast<long>(data_at + data_bytes));
    const std::size_t description_at = data_at + data_bytes;
    p.description.assign(
        bytes_.begin() + static_cast<long>(description_at + 1),
        bytes_.begin() + static_cast<long>(description_at + 1 + byte(description_at)));
    return p;
  }

  std::vector<char> bytes_;
  std::map<std::string, C3dParameter> parameters_;
};

}  // namespace syncap::io::testing
