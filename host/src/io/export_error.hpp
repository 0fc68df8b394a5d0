// The one error the exports throw: the file it concerns and what went wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace syncap::io {

class ExportError : public std::runtime_error {
 public:
  ExportError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem), path_(path), problem_(problem) {}
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_;
  std::string problem_;
};

}  // namespace syncap::io
