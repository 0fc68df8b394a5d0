// Text as HTML shows it: the characters markup would take (<, >, &, ") as entities. For the HTML
// reports (the calibration's, syncap reconstruct's).
#pragma once

#include <string>

namespace syncap::util {

inline std::string html_escaped(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace syncap::util
