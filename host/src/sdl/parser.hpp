// The SDL parser with its file access behind a function, so that the fuzzer (and tests) can serve
// included files from memory. Internal to host/src/sdl; users call sdl.hpp.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "scene/network.hpp"

namespace syncap::sdl::detail {

struct SourceFile {
  std::string identity;  // names the file uniquely (its canonical path): include cycles compare it
  std::string text;
};

// Reads the file at a path; throws std::runtime_error saying why it cannot.
using FileReader = std::function<SourceFile(const std::filesystem::path& path)>;

// The file system: regular files only (a device or a directory is refused, never read).
SourceFile read_source_file(const std::filesystem::path& path);

// Parses `text` read from `path` (its identity `identity`), reading includes through `reader`.
scene::Network parse(std::string text, const std::filesystem::path& path,
                     const std::string& identity, const FileReader& reader);

}  // namespace syncap::sdl::detail
