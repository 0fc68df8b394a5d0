// libFuzzer target: the reader of the host's JSON lines (io::parse_frame_line, which
// read_frame_lines and syncap-hil-compare use), on the input as one line of groups.jsonl.
//
// Contract: the reader returns a record or throws io::FrameLineError, nothing else; the error
// names the line first ("<where>: <problem>"); a record it accepts is consistent: every camera
// has blobs or a silhouette, each silhouette carries its camera's id and the line's frame, and a
// marker's covariance is the squares of its sigmas (never negative).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "io/frame_json.hpp"

namespace {

using syncap::fuzz::check;

const std::string kWhere = "groups.jsonl:1";

void check_record(const syncap::io::FrameRecord& r) {
  for (const auto& [id, camera] : r.cameras) {
    check(id >= 0, "a camera id is negative");
    check(camera.blobs || camera.silhouette, "a camera has neither blobs nor a silhouette");
    if (camera.silhouette) {
      check(camera.silhouette->camera_id == id, "a silhouette's camera id is not its key");
      check(camera.silhouette->frame_number == r.frame, "a silhouette's frame is not the line's");
    }
  }
  if (!r.markers) return;
  for (const syncap::pipeline::Marker3d& m : *r.markers) {
    for (int i = 0; i < 3; ++i) {
      check(!(m.covariance(i, i) < 0), "a marker's variance is negative");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  std::string error;
  syncap::io::FrameRecord record;
  bool read = false;
  // FrameLineError caught here rather than in decodes() so that its text can be checked.
  syncap::fuzz::decodes<syncap::fuzz::NothingThrown>("parse_frame_line", [&] {
    try {
      record = syncap::io::parse_frame_line(line, kWhere);
      read = true;
    } catch (const syncap::io::FrameLineError& e) {
      error = e.what();
    }
  });
  if (read) {
    check_record(record);
  } else {
    check(
        error.size() > kWhere.size() + 2 && error.compare(0, kWhere.size() + 2, kWhere + ": ") == 0,
        "a FrameLineError does not start with the line's name");
  }
  return 0;
}
