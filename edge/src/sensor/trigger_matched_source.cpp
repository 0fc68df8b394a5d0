#include "sensor/trigger_matched_source.hpp"

#include <algorithm>
#include <cstdlib>

namespace syncap::edge {

TriggerMatcher::TriggerMatcher(int64_t tolerance_ns, std::size_t capacity)
    : tolerance_ns_(tolerance_ns), capacity_(std::max<std::size_t>(capacity, 1)) {}

void TriggerMatcher::add(int64_t frame_number, int64_t monotonic_ns) {
  // Triggers arrive in order; one out of order (a restarted trigger) still goes by time.
  auto at =
      std::upper_bound(pulses_.begin(), pulses_.end(), monotonic_ns,
                       [](int64_t time, const Pulse& pulse) { return time < pulse.monotonic_ns; });
  pulses_.insert(at, {frame_number, monotonic_ns});
  while (pulses_.size() > capacity_) pulses_.pop_front();
}

std::optional<int64_t> TriggerMatcher::match(int64_t monotonic_ns) const {
  auto after =
      std::lower_bound(pulses_.begin(), pulses_.end(), monotonic_ns,
                       [](const Pulse& pulse, int64_t time) { return pulse.monotonic_ns < time; });
  const Pulse* best = nullptr;
  int64_t best_distance = tolerance_ns_ + 1;
  auto consider = [&](const Pulse& pulse) {
    const int64_t distance = std::llabs(pulse.monotonic_ns - monotonic_ns);
    if (distance < best_distance) best = &pulse, best_distance = distance;
  };
  if (after != pulses_.end()) consider(*after);
  if (after != pulses_.begin()) consider(*std::prev(after));
  if (!best) return std::nullopt;
  return best->frame_number;
}

std::optional<int64_t> TriggerMatcher::last_at_or_before(int64_t monotonic_ns) const {
  auto after =
      std::upper_bound(pulses_.begin(), pulses_.end(), monotonic_ns,
                       [](int64_t time, const Pulse& pulse) { return time < pulse.monotonic_ns; });
  if (after == pulses_.begin()) return std::nullopt;
  return std::prev(after)->frame_number;
}

std::optional<int64_t> TriggerMatcher::newest_ns() const {
  if (pulses_.empty()) return std::nullopt;
  return pulses_.back().monotonic_ns;
}

std::optional<int64_t> TriggerMatcher::time_of(int64_t frame_number) const {
  for (auto it = pulses_.rbegin(); it != pulses_.rend(); ++it) {
    if (it->frame_number == frame_number) return it->monotonic_ns;
  }
  return std::nullopt;
}

TriggerMatchedSource::TriggerMatchedSource(std::unique_ptr<FrameSource> source,
                                           int64_t tolerance_ns)
    : source_(std::move(source)), matcher_(tolerance_ns) {}

void TriggerMatchedSource::note_trigger(int64_t frame_number, int64_t monotonic_ns) {
  matcher_.add(frame_number, monotonic_ns);
}

std::optional<Frame> TriggerMatchedSource::grab(int64_t frame_number) {
  const std::optional<int64_t> trigger_ns = matcher_.time_of(frame_number);
  if (!trigger_ns) return std::nullopt;  // never told about this trigger: nothing to match
  for (;;) {
    std::optional<Frame> frame = std::move(held_);
    held_.reset();
    if (!frame) {
      // The camera's count starts at its first frame; a number it skipped (or a timeout) is
      // passed over so that the next call asks for the frame after it.
      frame = source_->grab(next_camera_number_ < 0 ? 0 : next_camera_number_);
      if (!frame) {
        if (next_camera_number_ >= 0) ++next_camera_number_;
        return std::nullopt;
      }
      next_camera_number_ = frame->frame_number + 1;
    }
    const std::optional<int64_t> match = matcher_.match(frame->monotonic_ns);
    if (match == frame_number) {
      frame->frame_number = frame_number;
      return frame;
    }
    const bool later =
        match ? *match > frame_number : frame->monotonic_ns > *trigger_ns + matcher_.tolerance_ns();
    if (later) {
      held_ = std::move(frame);  // may belong to a trigger not yet announced
      return std::nullopt;
    }
    ++unmatched_;  // between triggers, or of a trigger already passed
  }
}

std::string TriggerMatchedSource::describe() const {
  return source_->describe() + ", frames numbered by trigger time (tolerance " +
         std::to_string(matcher_.tolerance_ns() / 1000) + " us)";
}

}  // namespace syncap::edge
