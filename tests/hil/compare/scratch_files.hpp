// Small hand-written inputs for the comparison's tests, in a folder of their own per test.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

namespace syncap::compare::testing {

// A fresh folder named after the running test, removed when the test ends.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("syncap-compare-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_ / "truth");
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Writes `text` to path()/name and returns the file's path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::ofstream(file) << text;
    return file;
  }

 private:
  std::filesystem::path path_;
};

// cameras.json with `count` cameras of width x height pixels (the other parameters do not
// matter to the comparison, but the reader wants all of them).
inline std::string cameras_json(int count, int width = 640, int height = 480) {
  std::string list;
  for (int id = 0; id < count; ++id) {
    list += std::string(id ? "," : "") + R"({"id": )" + std::to_string(id) +
            R"(, "image_size": [)" + std::to_string(width) + ", " + std::to_string(height) +
            R"(], "pixel_size": [0.0099, 0.0099], "c": 6.2, "xp": 0, "yp": 0, "k1": 0, "k2": 0,
             "k3": 0, "p1": 0, "p2": 0, "sc": 0, "sh": 0, "X0": 0, "Y0": -3800, "Z0": 2200,
             "omega": 1.3, "phi": 0, "kappa": 0})";
  }
  return R"({"cameras": [)" + list + "]}\n";
}

}  // namespace syncap::compare::testing
