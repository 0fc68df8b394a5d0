// What the fuzz targets share: reading typed values from the fuzzer's bytes, and failing a
// contract check loudly. A failed check prints why and aborts, which libFuzzer reports as a
// crash (the input saved as crash-*) and the ctest smoke test as a dead test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::fuzz {

[[noreturn]] inline void fail(const std::string& why) {
  std::fprintf(stderr, "fuzz contract check failed: %s\n", why.c_str());
  std::abort();
}

inline void check(bool ok, const char* why) {
  if (!ok) fail(why);
}

// The `Error` of a decoder that reports damage instead of throwing: nothing may escape it.
struct NothingThrown {};

// Runs `decode` and returns true when it returned, false when it threw the decoder's documented
// `Error`; any other exception breaks the contract.
template <class Error, class Decode>
bool decodes(const char* decoder, Decode&& decode) {
  try {
    decode();
    return true;
  } catch (const Error&) {
    return false;
  } catch (const std::exception& e) {
    fail(std::string(decoder) + " threw an undocumented exception: " + e.what());
  } catch (...) {
    fail(std::string(decoder) + " threw a non-standard exception");
  }
}

// The fuzzer's bytes read front to back as fixed-size values; zeros once they run out.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <class T>
  T take() {
    T value{};
    const std::size_t n = sizeof(T) < left() ? sizeof(T) : left();
    if (n > 0) std::memcpy(&value, data_ + pos_, n);
    pos_ += n;
    return value;
  }

  // Up to `count` bytes (fewer when the input ends).
  std::vector<uint8_t> bytes(std::size_t count) {
    const std::size_t n = count < left() ? count : left();
    std::vector<uint8_t> out(data_ + pos_, data_ + pos_ + n);
    pos_ += n;
    return out;
  }

  std::size_t left() const { return size_ - pos_; }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// The input cut at each `separator` into at most `max_pieces` texts (the last keeps the rest):
// one fuzz input describing several files.
inline std::vector<std::string> split_input(const uint8_t* data, std::size_t size,
                                            std::string_view separator, std::size_t max_pieces) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> pieces;
  std::size_t start = 0;
  while (pieces.size() + 1 < max_pieces) {
    const std::size_t at = text.find(separator, start);
    if (at == std::string_view::npos) break;
    pieces.emplace_back(text.substr(start, at - start));
    start = at + separator.size();
  }
  pieces.emplace_back(text.substr(start));
  return pieces;
}

}  // namespace syncap::fuzz
