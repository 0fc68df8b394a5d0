// The one error the imports (c3d_reader.hpp, trc_reader.hpp) throw: the file, where in it, and
// what is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace syncap::io {

class ImportError : public std::runtime_error {
 public:
  ImportError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem) {}
};

}  // namespace syncap::io
