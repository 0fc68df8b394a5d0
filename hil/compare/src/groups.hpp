// The host's frame groups as syncap-host --out writes them (host/src/app/host_main.cpp,
// group_json), one JSON object a line:
//   {"frame":k,"complete":true,"missing_cameras":[..],"trigger_monotonic_ns":..,
//    "cameras":{"0":{"processing_us":..,"blobs":[{"x":..,"y":..,"area":..},...]},...}}
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::compare {

struct Blob {
  double x = 0, y = 0;  // sub-pixel centroid, pixel (0, 0) the centre of the top-left pixel
  double area = 0;      // pixels
};

struct CameraBlobs {
  double processing_us = 0;
  std::vector<Blob> blobs;
};

struct Group {
  long frame = 0;
  bool complete = false;
  std::vector<int> missing_cameras;
  std::map<int, CameraBlobs> cameras;  // by camera id: the cameras whose message arrived
};

// One line; `where` ("groups.jsonl:17") starts every InputError message.
Group parse_group(std::string_view line, const std::string& where);

// Every non-empty line of `file`, in file order; a frame may appear only once.
std::vector<Group> read_groups(const std::filesystem::path& file);

}  // namespace syncap::compare
