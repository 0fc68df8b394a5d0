// libFuzzer target: syncap-edge's configuration file (`--config FILE`, /etc/syncap/edge-N.yaml;
// edge::parse_edge_options), on the input as the file's YAML text. The reader takes a path, so
// each input is written to one file of this process first.
//
// Contract: the options are parsed or edge::UsageError is thrown, nothing else (yaml-cpp's
// exceptions included); accepted options name a camera 0..99.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/edge_options.hpp"
#include "fuzz_check.hpp"

namespace {

// In memory (/dev/shm) where there is one: a file on disk made the smoke test's 3000 inputs take
// 6 s instead of 1 s. Removed when the process ends.
struct ConfigFile {
  std::string path;
  ConfigFile() {
    const std::filesystem::path shm("/dev/shm");
    const std::filesystem::path dir =
        std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
    path = (dir / ("syncap-fuzz-edge-" + std::to_string(getpid()) + ".yaml")).string();
  }
  ~ConfigFile() { std::filesystem::remove(path); }
};

const std::string& config_file() {
  static const ConfigFile file;
  return file.path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::ofstream(config_file(), std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  syncap::edge::EdgeOptions options;
  const bool parsed = syncap::fuzz::decodes<syncap::edge::UsageError>("parse_edge_options", [&] {
    options = syncap::edge::parse_edge_options({"--config", config_file()});
  });
  if (parsed) {
    syncap::fuzz::check(options.camera_id >= 0 && options.camera_id <= 99,
                        "a camera id outside 0..99 was accepted");
  }
  return 0;
}
