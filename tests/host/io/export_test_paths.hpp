// A fresh path per test in GoogleTest's temporary folder.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace syncap::io::testing {

inline std::string fresh_path(const std::string& extension) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("syncap-io-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path path =
      dir / (std::string(test->test_suite_name()) + "." + test->name() + extension);
  std::filesystem::remove(path);
  return path.string();
}

}  // namespace syncap::io::testing
