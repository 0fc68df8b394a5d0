// JSON text written straight into a std::string, without building a document first: the host
// writes a JSON line per frame group on its worker thread, where nlohmann::json's tree of
// allocated nodes cost as much as matching and triangulation together (bench_frame_json).
// The text is laid out as nlohmann::json's dump() lays it out, so that lines keep their form.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::io {

// `value` as nlohmann::json's dump() writes a double: "null" when not finite, else the shortest
// digits that read back to `value`, in fixed notation from 1e-4 up to 15 digits before the point
// ("12.5", "3.0", "0.00012", "-0.0"), in scientific beyond ("1.5e+20", "1e-05"). The digits are
// to_chars': the shortest and of those the closest, where dump()'s Grisu2 now and then gave a
// longer or another last digit for the same double (json_text_test.cpp).
void append_json_number(std::string& out, double value);

// `text` as a JSON string, escaped as dump() escapes it; a byte that is not part of valid UTF-8
// is written as U+FFFD (dump() would throw, and a reader would refuse the line).
void append_json_string(std::string& out, std::string_view text);

// Writes values, arrays and objects to `out`, putting the commas between members and elements.
// Members come in the order they are written: a writer that must match nlohmann::json's sorted
// keys writes them sorted. The text gathers in a buffer of its own first, a string append per
// kilobyte instead of one per token (a group's line has thousands), and is in `out` after
// flush() or once the JsonText is gone.
class JsonText {
 public:
  explicit JsonText(std::string& out) : out_(out) {}
  JsonText(const JsonText&) = delete;
  JsonText& operator=(const JsonText&) = delete;
  ~JsonText() { flush(); }
  void flush() {
    out_.append(buffer_, pos_);
    pos_ = buffer_;
  }

  JsonText& begin_object() { return open('{'); }
  JsonText& end_object() { return close('}'); }
  JsonText& begin_array() { return open('['); }
  JsonText& end_array() { return close(']'); }
  // The key of the next member, a name that needs no escaping (the writer's own); its value
  // follows.
  JsonText& key(std::string_view name);

  JsonText& number(double value);
  JsonText& integer(std::int64_t value);
  JsonText& flag(bool value);
  JsonText& string(std::string_view value);
  JsonText& integers(const std::vector<int>& values);

 private:
  static constexpr std::ptrdiff_t kBufferSize = 1024;

  // Where the next token goes, with room for `size` bytes (at most kBufferSize) and the comma
  // before it when it needs one.
  char* next(std::ptrdiff_t size) {
    if (buffer_ + kBufferSize - pos_ < size + 1) flush();
    if (!first_) *pos_++ = ',';
    first_ = false;
    return pos_;
  }
  JsonText& open(char bracket) {
    *next(1) = bracket;
    ++pos_;
    first_ = true;
    return *this;
  }
  JsonText& close(char bracket) {
    if (pos_ == buffer_ + kBufferSize) flush();
    *pos_++ = bracket;
    first_ = false;
    return *this;
  }

  std::string& out_;
  char buffer_[kBufferSize];
  char* pos_ = buffer_;
  bool first_ = true;  // nothing written yet in the current array or object
};

}  // namespace syncap::io
