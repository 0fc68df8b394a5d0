// libFuzzer target: the cameras.json reader (sensor::parse_camera_set, which read_cameras and
// read_camera_set use), on the input as the file's text.
//
// Contract: the reader returns a camera set or throws sensor::CameraFileError, nothing else; a
// set it accepts is written (format_camera_set) as a file it reads back to the same text.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "sensor/camera_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  syncap::sensor::CameraSet set;
  const bool read = syncap::fuzz::decodes<syncap::sensor::CameraFileError>(
      "parse_camera_set", [&] { set = syncap::sensor::parse_camera_set(text, "cameras.json"); });
  if (!read) return 0;
  const std::string written = syncap::sensor::format_camera_set(set);
  std::string rewritten;
  const bool reread =
      syncap::fuzz::decodes<syncap::sensor::CameraFileError>("parse_camera_set", [&] {
        rewritten = syncap::sensor::format_camera_set(
            syncap::sensor::parse_camera_set(written, "written.json"));
      });
  if (!reread) syncap::fuzz::fail("a written cameras.json does not read back:\n" + written);
  if (rewritten != written) {
    syncap::fuzz::fail("write -> read -> write changed cameras.json:\n" + written + "---\n" +
                       rewritten);
  }
  return 0;
}
