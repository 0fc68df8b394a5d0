// A file's extension in lower case (".PNG" -> ".png"): how the host tells file formats apart by
// name (camera files, mask images, output formats).
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace syncap::util {

inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::ranges::transform(ext, ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace syncap::util
