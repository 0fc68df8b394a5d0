// The scene description language (SDL) of thesis section 4.2.1 (thesis.txt lines 3058-3139,
// Fig 4.9): a readable text form of scene::Network, the input of the bundle adjustment. The
// grammar, with examples, is in docs/reference/sdl.md.
//
// Usage:
//   scene::Network network = sdl::parse_file("scene.sdl");   // throws sdl::ParseError
//   std::string text = sdl::write(network);                   // parse_string(text) == network
//
// write() prints every value with the shortest decimal form that reads back to the same double,
// so write -> parse reproduces the network exactly (names, values, priors, order, design tags).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scene/network.hpp"

namespace syncap::sdl {

// A scene that does not parse: where (file, line, column, 1-based; the column counts bytes) and
// what was expected. what() is "FILE:LINE:COLUMN: MESSAGE", as compilers print it; for a file
// that cannot be read at all line and column are 0 and what() is "FILE: MESSAGE".
class ParseError : public std::runtime_error {
 public:
  ParseError(std::string file, int line, int column, const std::string& message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_ = 0;
  int column_ = 0;
  std::string message_;
};

// Parses SDL text. `name` stands for the text in error messages; `include "f"` resolves relative
// to the directory of `name` (the working directory when `name` has none).
scene::Network parse_string(std::string_view text, const std::string& name = "<string>");

// Parses an SDL file; includes resolve relative to the including file; an include cycle and a
// file that cannot be read are ParseErrors naming the include statement.
scene::Network parse_file(const std::filesystem::path& path);

// The network as SDL text: the design block, the camera models, the stations, the points, the
// measurements, the constraints and the residual test, in the network's order. Throws
// std::invalid_argument (naming the element) for a value SDL cannot hold: a non-finite number.
std::string write(const scene::Network& network);

// write() into a file; throws std::runtime_error naming the path when it cannot be written.
void write_file(const scene::Network& network, const std::filesystem::path& path);

}  // namespace syncap::sdl
