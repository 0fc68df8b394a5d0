// Unusable input: a file that cannot be read or does not have the expected form. what() names
// the file and, where there is one, the line: "groups.jsonl:17: not JSON".
#pragma once

#include <stdexcept>
#include <string>

namespace syncap::compare {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws InputError "<file>:<line>: <what>".
[[noreturn]] inline void fail_at(const std::string& file, long line, const std::string& what) {
  throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

}  // namespace syncap::compare
