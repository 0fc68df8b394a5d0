// Frame numbers of one GigE Vision acquisition's exposures.
//
// GigE Vision numbers the exposures of an acquisition with 16-bit block ids that wrap from 65535
// to 1; BlockIdUnwrapper turns them into a running count, and the frame number is that count plus
// an offset fixed by the acquisition's first exposure:
// - A camera acquiring before the trigger's first pulse: its first exposure (block id 1) is frame
//   0, so frame number = unwrapped block id - 1. The replay bench's fake cameras send block id =
//   frame number mod 65535 + 1 (docs/design/fakecam.md), which the same rule turns back into the
//   number.
// - A camera reopened in the middle of a run (after it vanished) restarts its block ids, and its
//   first exposure belongs to whichever trigger came first after it was acquiring again, which
//   the edge cannot know from the block id: the first exposure is numbered by time instead, by
//   the trigger pulses the edge noted (their frame numbers and CLOCK_MONOTONIC times):
//   1. the pulse within `tolerance_ns` of the camera's own timestamp, when the camera's clock is
//      the trigger's (the fake cameras; cameras synchronised by PTP to the trigger board);
//   2. otherwise the last pulse at or before the exposure's arrival on the board, once a later
//      pulse has been noted (so the right one cannot still be on its way). This can be one frame
//      late when a frame's transfer takes longer than a trigger period.
//   The camera's clock is taken for the trigger's when its timestamp is less than a second before
//   the arrival. Until a rule decides, the exposure waits (the caller keeps it). Dropped: an
//   exposure on the trigger's clock that matches no noted pulse although later ones were noted
//   (its trigger message was lost, or it came before the reopen), and one that arrived before
//   every noted pulse. After three such drops the clock is no longer taken for the trigger's.
#pragma once

#include <cstdint>
#include <optional>

#include "sensor/trigger_matched_source.hpp"

namespace syncap::edge {

// Unwraps GigE Vision block ids (1..65535, then 1 again) into a running 64-bit count.
class BlockIdUnwrapper {
 public:
  uint64_t next(uint16_t block_id);

 private:
  std::optional<uint16_t> last_;
  uint64_t count_ = 0;
};

class ExposureNumbering {
 public:
  // `reopened`: the camera was reopened mid-run (its first exposure is numbered by time);
  // otherwise it was acquiring before the run's first pulse.
  ExposureNumbering(bool reopened, int64_t tolerance_ns);

  // A trigger pulse the edge received (before it asks for its exposure).
  void note_trigger(int64_t frame_number, int64_t monotonic_ns);

  struct Result {
    enum class Kind { kNumbered, kWait, kDrop };
    Kind kind = Kind::kDrop;
    int64_t frame_number = -1;  // when kNumbered
    bool operator==(const Result&) const = default;
  };
  static Result numbered(int64_t frame_number) { return {Result::Kind::kNumbered, frame_number}; }
  static Result wait() { return {Result::Kind::kWait, -1}; }
  static Result drop() { return {Result::Kind::kDrop, -1}; }

  // The frame number of the next exposure in the stream, from its block id, the camera's
  // timestamp and its arrival on the board (CLOCK_MONOTONIC). Only the first exposure of a
  // reopened camera can wait (ask again with the same exposure after the next pulse) or be
  // dropped (then the next exposure is the first).
  Result number(uint16_t block_id, int64_t camera_ns, int64_t arrival_ns);
  // Whether the stream's numbering is fixed (every later exposure is numbered by its block id).
  bool numbered() const { return offset_.has_value(); }

 private:
  Result first_number(int64_t camera_ns, int64_t arrival_ns);

  bool reopened_;
  TriggerMatcher pulses_;
  BlockIdUnwrapper block_ids_;
  std::optional<int64_t> offset_;  // frame number - unwrapped block id
  int drops_ = 0;                  // first exposures dropped as on the trigger's clock
};

}  // namespace syncap::edge
