// --drop: which frames the fake camera leaves out, as a list of frame numbers or as a rate.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::fakecam {

class DropPolicy {
 public:
  // Drops nothing.
  DropPolicy() = default;

  // "3,17,40-45": exactly those frame numbers (ranges inclusive). "0.05" or "5%": each frame with
  // that probability, decided by a hash of (seed, frame number) alone, so a run is reproducible
  // and independent of timing. Throws std::invalid_argument saying what is wrong.
  static DropPolicy parse(std::string_view text, std::uint64_t seed);

  bool drops(std::uint64_t frame) const;

  // "nothing", "frames 3,17,40-45" or "5% (seed 1)", for the start line.
  std::string describe() const;

 private:
  struct Range {
    std::uint64_t first;
    std::uint64_t last;
  };
  std::vector<Range> ranges_;
  double rate_ = 0.0;
  std::uint64_t seed_ = 0;
  std::string text_;
};

}  // namespace syncap::fakecam
