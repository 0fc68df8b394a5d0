// Where tests find the shared real data: $SYNCAP_DATA (ctest sets it to ../shared/data beside
// the source tree unless the caller's environment has it). Tests whose data is absent skip and
// name the path they looked for.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace syncap::test {

inline std::filesystem::path data_root() {
  const char* env = std::getenv("SYNCAP_DATA");
  return env != nullptr && *env != '\0' ? std::filesystem::path(env)
                                        : std::filesystem::path("../shared/data");
}

// The path of `relative` under the data root, or an empty path when it does not exist.
inline std::filesystem::path data_path(const std::string& relative) {
  std::filesystem::path p = data_root() / relative;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
}

}  // namespace syncap::test

// Skips the current test, naming the missing path, when `relative` is not under the data root.
#define SYNCAP_REQUIRE_DATA(var, relative)                                                      \
  const std::filesystem::path var = ::syncap::test::data_path(relative);                        \
  if (var.empty()) {                                                                            \
    GTEST_SKIP() << "real data absent: " << (::syncap::test::data_root() / (relative)).string() \
                 << " (set SYNCAP_DATA to the folder holding it)";                              \
  }
