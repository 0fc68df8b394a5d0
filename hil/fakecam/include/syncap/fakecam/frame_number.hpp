// How a syncap-fakecam frame carries its 64-bit frame number through GigE Vision
// (docs/design/fakecam.md, "Frame numbers"). GVSP block ids are 16-bit and never 0, so frame number
// f travels as
//
//   block id (arv_buffer_get_frame_id) = f mod 65535 + 1          in 1..65535
//   timestamp (arv_buffer_get_timestamp) = the trigger's rising edge, CLOCK_MONOTONIC ns
//
// which makes consecutive frames consecutive block ids in GigE Vision's wrapping order
// (65535 -> 1), so Aravis' own missing-frame count stays right. The block id alone gives f up to
// a multiple of 65535; a receiver recovers f from a nearby frame number it already knows.
// Header-only, no Aravis needed.
#pragma once

#include <cstdint>
#include <optional>

namespace syncap::fakecam {

// Block ids run 1..kBlockIdCycle; frame numbers repeat their block id every kBlockIdCycle frames.
inline constexpr std::uint64_t kBlockIdCycle = 65535;

// The GVSP block id that carries frame number `frame`.
constexpr std::uint16_t block_id_of(std::uint64_t frame) {
  return static_cast<std::uint16_t>(frame % kBlockIdCycle + 1);
}

// The frame number with this block id nearest to `reference` (a frame number known to be close,
// e.g. the previous frame's plus one). Exact while the true number is within 32767 frames of the
// reference; nothing for block id 0, which no frame has. On a tie the later frame wins; below 0 the
// smallest frame number with the id.
constexpr std::optional<std::uint64_t> frame_number_from_block_id(std::uint16_t block_id,
                                                                  std::uint64_t reference) {
  if (block_id == 0) return std::nullopt;
  const std::uint64_t residue = block_id - 1u;
  const std::uint64_t base = reference - reference % kBlockIdCycle;  // same cycle as the reference
  std::uint64_t best = base + residue;
  const auto distance = [reference](std::uint64_t f) {
    return f > reference ? f - reference : reference - f;
  };
  if (best > reference && best >= kBlockIdCycle &&
      distance(best - kBlockIdCycle) < distance(best)) {
    best -= kBlockIdCycle;  // the previous cycle is nearer
  } else if (best < reference && distance(best + kBlockIdCycle) <= distance(best)) {
    best += kBlockIdCycle;  // the next cycle is nearer (or as near: the later frame wins)
  }
  return best;
}

// Follows one camera's stream: each block id is resolved against the frame after the previous
// one, so a run of frames recovers exactly across wraps and across gaps (dropped frames) shorter
// than 32767 frames.
class FrameNumberTracker {
 public:
  // `first_expected`: the frame number the first frame is expected near (the trigger's first
  // frame, usually 0, or the fake camera's --start-frame).
  explicit FrameNumberTracker(std::uint64_t first_expected = 0) : expected_(first_expected) {}

  // The full frame number of a frame with this block id; nothing for block id 0.
  std::optional<std::uint64_t> next(std::uint16_t block_id) {
    const auto frame = frame_number_from_block_id(block_id, expected_);
    if (frame) expected_ = *frame + 1;
    return frame;
  }

 private:
  std::uint64_t expected_;
};

}  // namespace syncap::fakecam
