// Prints region messages (clip_polygon_t) as JSON lines and, when asked, signs and publishes them
// on SYNCAP_EDGE_CLIP: the common end of `syncap clip` and `syncap regions`.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "syncap/clip_polygon_t.hpp"

namespace syncap::tools {

struct RegionSending {
  bool publish = false;
  std::string key_path;  // needed by publish
  std::string lcm_url;
};

// Prints every message (signed when publishing) and publishes it; the notes go to `err` after
// `prefix`. Returns the exit status: 0, 1 with notes, 2 when the key or LCM cannot be opened
// (named; nothing is printed or sent then).
int send_regions(std::vector<clip_polygon_t> messages, const std::vector<std::string>& notes,
                 const RegionSending& sending, const char* prefix, std::ostream& out,
                 std::ostream& err);

}  // namespace syncap::tools
