// Rigid marker set files (docs/design/reconstruction.md, "Tracking"): YAML,
//
//   rigid_sets:
//     - name: wand
//       tolerance_mm: 3          # optional, default 3
//       markers:
//         - {name: wand_a, position: [0, 0, 0]}
//         - {name: wand_b, position: [200, 0, 0]}
//         - {name: wand_c, position: [500, 0, 0]}
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "tracking/rigid_set.hpp"

namespace syncap::tracking {

// What is wrong with a tracking file, and where: "path:line: problem" (line 0: the whole file).
class TrackingFileError : public std::runtime_error {
 public:
  TrackingFileError(const std::string& path, int line, const std::string& problem)
      : std::runtime_error(path + ":" + std::to_string(line) + ": " + problem),
        path_(path),
        line_(line) {}
  const std::string& path() const { return path_; }
  int line() const { return line_; }

 private:
  std::string path_;
  int line_ = 0;
};

// Throws TrackingFileError when the file cannot be read or parsed, or a set has no name, a name
// used twice, fewer than 3 markers, a marker without a name or with a repeated one, a position
// that is not 3 finite numbers, two markers closer than twice the tolerance, a tolerance that is
// not positive, or an unknown key.
std::vector<RigidSet> read_rigid_sets(const std::string& path);
// The same from text; `path` only names it in errors.
std::vector<RigidSet> parse_rigid_sets(const std::string& text, const std::string& path);

}  // namespace syncap::tracking
