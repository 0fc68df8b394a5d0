// The command line of syncap-fakecam (docs/design/fakecam.md, "Options").
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "drop_policy.hpp"

namespace syncap::fakecam {

struct TriggerSpec {
  enum class Kind { software, gpiosim };
  Kind kind = Kind::software;
  std::string chip;   // gpiosim: the shared chip's name
  unsigned line = 0;  // gpiosim: the line watched

  std::string describe() const;
};

struct Options {
  std::string address;  // IPv4 on the loopback, 127.x.y.z
  std::filesystem::path images;
  std::string serial;  // default SYNCAP-FAKE-<last octet of the address>
  TriggerSpec trigger;
  DropPolicy drop;
  std::uint64_t seed = 1;
  std::int64_t delay_ms = 0;
  std::uint64_t start_frame = 0;
  std::uint64_t cache_mb = 256;
  std::uint32_t link_mbps = 1000;  // 0: unpaced
  bool loop = false;               // frames past the last image start the images again (soak runs)
  bool quiet = false;
};

struct ParsedOptions {
  enum class Result { run, help, invalid };
  Result result = Result::invalid;
  Options options;
  std::string error;  // for invalid: "invalid --delay-ms 'x': why" or "unknown option '--x'"
};

// Parses the arguments after the program name.
ParsedOptions parse_options(std::span<const char* const> arguments);

// The usage text.
std::string usage();

}  // namespace syncap::fakecam
