// libFuzzer target of the SDL parser (scripts/fuzz-sdl.sh, docs/reference/sdl.md "Fuzzing"). Every
// input is a scene file; `include "self.sdl"` serves the input itself (so cycles are reachable),
// `include "other.sdl"` a small valid scene, anything else is a missing file. The oracle beyond
// the sanitizers: a scene that parses must survive write -> parse -> write unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "sdl/parser.hpp"
#include "sdl/sdl.hpp"

namespace {

constexpr const char* kOther = R"(declare f = 6
camera_model "m" { sensor { width = 640 height = 480 pixel_width = 0.01 pixel_height = 0.01 }
                   c = f sigma 0.1 }
station "s" { model = "m" X0 = 1 Y0 = 2 Z0 = 3 omega = 0 phi = 0 kappa = 0 }
point "p" { xyz = <0, 0, 1000> }
measurements { "s" "p" <320, 240> }
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto reader = [&input](const std::filesystem::path& path) {
    if (path == "self.sdl") return syncap::sdl::detail::SourceFile{"self.sdl", input};
    if (path == "other.sdl") return syncap::sdl::detail::SourceFile{"other.sdl", kOther};
    throw std::runtime_error("no such file " + path.string());
  };
  syncap::scene::Network network;
  try {
    network = syncap::sdl::detail::parse(input, "fuzz.sdl", "fuzz.sdl", reader);
  } catch (const syncap::sdl::ParseError&) {
    return 0;  // the expected outcome for most inputs
  }
  const std::string written = syncap::sdl::write(network);
  std::string rewritten;
  try {
    rewritten = syncap::sdl::write(syncap::sdl::parse_string(written, "written.sdl"));
  } catch (const syncap::sdl::ParseError& error) {
    std::fprintf(stderr, "written scene does not parse: %s\n%s\n", error.what(), written.c_str());
    std::abort();
  }
  if (rewritten != written) {
    std::fprintf(stderr, "write -> parse -> write changed the scene:\n%s\n---\n%s\n",
                 written.c_str(), rewritten.c_str());
    std::abort();
  }
  return 0;
}
