#include "sensor/exposure_numbering.hpp"

namespace syncap::edge {
namespace {

// A camera timestamp this much before the arrival is taken to be on the trigger's clock: more
// than any exposure and transfer, far less than the offset of two unrelated clocks (almost always).
constexpr int64_t kSharedClockWindowNs = 1'000'000'000;
// First exposures dropped as on the trigger's clock before the arrival rule takes over.
constexpr int kMaxSharedClockDrops = 3;
// Pulses kept: a few seconds at the highest trigger rates, enough for a reopen.
constexpr std::size_t kPulsesKept = 1024;

}  // namespace

uint64_t BlockIdUnwrapper::next(uint16_t block_id) {
  if (!last_) {
    count_ = block_id;
  } else {
    // Ids run 1..65535; the step from the last id, forward, skipping 0.
    const int step = (block_id - *last_ + 65535) % 65535;
    count_ += step;
  }
  last_ = block_id;
  return count_;
}

ExposureNumbering::ExposureNumbering(bool reopened, int64_t tolerance_ns)
    : reopened_(reopened), pulses_(tolerance_ns, kPulsesKept) {}

void ExposureNumbering::note_trigger(int64_t frame_number, int64_t monotonic_ns) {
  if (reopened_ && !offset_) pulses_.add(frame_number, monotonic_ns);
}

ExposureNumbering::Result ExposureNumbering::number(uint16_t block_id, int64_t camera_ns,
                                                    int64_t arrival_ns) {
  if (offset_) return numbered(static_cast<int64_t>(block_ids_.next(block_id)) + *offset_);
  const Result first = reopened_ ? first_number(camera_ns, arrival_ns) : numbered(block_id - 1);
  if (first.kind != Result::Kind::kNumbered) return first;
  offset_ = first.frame_number - static_cast<int64_t>(block_ids_.next(block_id));
  return first;
}

ExposureNumbering::Result ExposureNumbering::first_number(int64_t camera_ns, int64_t arrival_ns) {
  const auto newest = pulses_.newest_ns();
  if (!newest) return wait();
  if (const auto match = pulses_.match(camera_ns)) return numbered(*match);
  const int64_t before_arrival = arrival_ns - camera_ns;
  const bool shared_clock =
      before_arrival >= 0 && before_arrival < kSharedClockWindowNs && drops_ < kMaxSharedClockDrops;
  if (shared_clock) {
    if (camera_ns > *newest + pulses_.tolerance_ns()) return wait();  // its pulse is on its way
    ++drops_;
    return drop();
  }
  const auto last = pulses_.last_at_or_before(arrival_ns);
  if (!last) return drop();
  if (*newest <= arrival_ns) return wait();  // a nearer pulse may still be on its way
  return numbered(*last);
}

}  // namespace syncap::edge
