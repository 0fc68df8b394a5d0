// printf into a std::string, for the host's text reports (summaries, tables) where columns are
// laid out with printf widths. GCC 12's libstdc++ has no std::format yet.
#pragma once

#include <cstdarg>
#include <cstdio>
#include <string>

namespace syncap::util {

// The text printf(format, ...) would print, whatever its length.
__attribute__((format(printf, 1, 2))) inline std::string printf_string(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int length = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string text(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  return text;
}

}  // namespace syncap::util
