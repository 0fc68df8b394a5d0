#include "io/json_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace syncap::io {
namespace {

// nlohmann::json's limits for fixed notation (its to_chars: kMinExp, kMaxExp = digits10).
constexpr int kMinPoint = -4;
constexpr int kMaxPoint = 15;

// Writes the significant `digits` with the decimal point `point` places after their first
// (point <= 0: before it) as nlohmann::json's format_buffer does in fixed notation; nullptr when
// the number takes scientific notation there.
char* write_fixed(char* out, std::string_view digits, int point) {
  const int k = static_cast<int>(digits.size());
  if (point > kMaxPoint || point <= kMinPoint) return nullptr;
  if (k <= point) {  // a whole number keeps ".0" to read as a double
    out = std::fill_n(std::copy(digits.begin(), digits.end(), out), point - k, '0');
    return std::copy_n(".0", 2, out);
  }
  if (point > 0) {
    out = std::copy_n(digits.begin(), point, out);
    *out++ = '.';
    return std::copy(digits.begin() + point, digits.end(), out);
  }
  out = std::fill_n(std::copy_n("0.", 2, out), -point, '0');
  return std::copy(digits.begin(), digits.end(), out);
}

// `value` when it is exactly the double of k / 1000 for a whole k below 10^15 in magnitude, as
// most of the host's numbers are (millimetres rounded to micrometres, whole pixel areas): its
// shortest digits are k's, since no two decimals of at most 15 significant digits are the same
// double, so it is written without to_chars' search for them. nullptr otherwise.
char* write_thousandths(char* out, double value) {
  const double scaled = std::round(value * 1000);
  if (!(std::abs(scaled) < 1e15) || scaled / 1000 != value) return nullptr;
  if (std::signbit(value)) *out++ = '-';
  const auto k = static_cast<std::uint64_t>(std::abs(scaled));
  out = std::to_chars(out, out + 16, k / 1000).ptr;
  *out++ = '.';
  auto fraction = static_cast<unsigned>(k % 1000);
  if (fraction == 0) *out++ = '0';
  for (unsigned unit = 100; fraction != 0; unit /= 10) {  // trailing zeros stay out
    *out++ = static_cast<char>('0' + fraction / unit);
    fraction %= unit;
  }
  return out;
}

// to_chars' own choice between fixed and scientific notation (the shorter) is nlohmann::json's
// layout when it is fixed, with a fraction and at most 15 digits before the point: most numbers,
// written so in one go. nullptr otherwise (`out` then holds nothing of use).
char* write_if_fixed(char* out, double value) {
  char* const end = std::to_chars(out, out + 32, value).ptr;
  const std::string_view text(out, static_cast<std::size_t>(end - out));
  const std::size_t point = text.find('.');
  const std::size_t digits_before = point - (text[0] == '-' ? 1 : 0);
  const bool fixed = point != std::string_view::npos && text.find('e') == std::string_view::npos;
  return fixed && digits_before <= kMaxPoint ? end : nullptr;
}

// The shortest digits that read back to `value` (to_chars), laid out as nlohmann::json does.
char* write_shortest(char* out, double value) {
  if (char* end = write_if_fixed(out, value)) return end;
  // Scientific notation gives the digits and the exponent apart: "-1.2345e+02" -> 12345, 2.
  char text[32];
  const char* const end =
      std::to_chars(text, text + sizeof text, value, std::chars_format::scientific).ptr;
  const char* p = text;
  if (*p == '-') *out++ = *p++;
  const char* const number = p;
  char digits[20];
  std::size_t k = 0;
  for (; *p != 'e'; ++p) {
    if (*p != '.') digits[k++] = *p;
  }
  int exponent = 0;
  std::from_chars(p + 2, end, exponent);
  if (p[1] == '-') exponent = -exponent;
  if (char* fixed = write_fixed(out, std::string_view(digits, k), exponent + 1)) return fixed;
  return std::copy(number, end, out);  // as to_chars wrote it: "1.5e+20", "1e-05"
}

// The length of the valid UTF-8 sequence at the start of `s` (RFC 3629: no overlong forms, no
// surrogates, nothing beyond U+10FFFF); 0 when it is not one.
std::size_t utf8_length(std::string_view s) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // the second byte's range
  if (lead >= 0xC2 && lead <= 0xDF)
    length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF)
    length = 3;
  else if (lead >= 0xF0 && lead <= 0xF4)
    length = 4;
  if (length == 0 || s.size() < length) return 0;
  if (lead == 0xE0) low = 0xA0;
  if (lead == 0xED) high = 0x9F;
  if (lead == 0xF0) low = 0x90;
  if (lead == 0xF4) high = 0x8F;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t i = 2; i < length; ++i) {
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  }
  return length;
}

// A control character as dump() writes it: the short escapes, else \u00xx in lower case.
void append_control(std::string& out, unsigned char c) {
  static constexpr char kHex[] = "0123456789abcdef";
  switch (c) {
    case '\b':
      out += "\\b";
      break;
    case '\f':
      out += "\\f";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      out.append("\\u00").append(1, kHex[c >> 4]).append(1, kHex[c & 0xF]);
  }
}

}  // namespace

// `value` as append_json_number writes it, into `out` (room for 32 bytes); the end returned.
char* write_number(char* out, double value) {
  if (!std::isfinite(value)) return std::copy_n("null", 4, out);
  char* end = write_thousandths(out, value);
  return end != nullptr ? end : write_shortest(out, value);
}

void append_json_number(std::string& out, double value) {
  char text[32];
  out.append(text, write_number(text, value));
}

void append_json_string(std::string& out, std::string_view text) {
  out += '"';
  while (!text.empty()) {
    const auto c = static_cast<unsigned char>(text[0]);
    std::size_t length = 1;
    if (c == '"' || c == '\\') {
      out.append(1, '\\').append(1, static_cast<char>(c));
    } else if (c < 0x20) {
      append_control(out, c);
    } else if ((length = utf8_length(text)) > 0) {
      out.append(text.substr(0, length));
    } else {
      out += "\xEF\xBF\xBD";  // U+FFFD for the byte that starts no valid sequence
      length = 1;
    }
    text.remove_prefix(length);
  }
  out += '"';
}

JsonText& JsonText::key(std::string_view name) {
  const auto size = static_cast<std::ptrdiff_t>(name.size());
  if (size + 3 > kBufferSize) {  // not one of the writer's names: never so long
    next(0);
    flush();
    append_json_string(out_, name);
    out_ += ':';
  } else {
    char* p = next(size + 3);
    *p++ = '"';
    p = std::copy(name.begin(), name.end(), p);
    *p++ = '"';
    *p++ = ':';
    pos_ = p;
  }
  first_ = true;  // the value follows without a comma
  return *this;
}

JsonText& JsonText::number(double value) {
  pos_ = write_number(next(32), value);
  return *this;
}

JsonText& JsonText::integer(std::int64_t value) {
  pos_ = std::to_chars(next(20), buffer_ + kBufferSize, value).ptr;
  return *this;
}

JsonText& JsonText::flag(bool value) {
  pos_ = value ? std::copy_n("true", 4, next(4)) : std::copy_n("false", 5, next(5));
  return *this;
}

// Strings are rare (a rigid set's name) and may grow sixfold by escaping: straight to `out`.
JsonText& JsonText::string(std::string_view value) {
  next(0);
  flush();
  append_json_string(out_, value);
  return *this;
}

JsonText& JsonText::integers(const std::vector<int>& values) {
  begin_array();
  for (const int v : values) integer(v);
  return end_array();
}

}  // namespace syncap::io
