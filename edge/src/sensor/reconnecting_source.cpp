#include "sensor/reconnecting_source.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include "syncap/proto/clock.hpp"

namespace syncap::edge {
namespace {

// Fewer consecutive triggers without a frame are lost frames, not a vanished camera.
constexpr int kMinMisses = 3;

int64_t to_ns(double seconds) { return static_cast<int64_t>(std::llround(seconds * 1e9)); }

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

}  // namespace

ReconnectingSource::ReconnectingSource(SourceFactory open, ReconnectOptions options,
                                       std::function<int64_t()> clock_ns)
    : open_(std::move(open)),
      options_(options),
      clock_ns_(clock_ns ? std::move(clock_ns) : proto::monotonic_now_ns),
      source_(open_(0)),
      description_(source_->describe()),
      delay_s_(options_.first_delay_s) {}

std::optional<Frame> ReconnectingSource::grab(int64_t frame_number) {
  const int64_t now = clock_ns_();
  if (!source_) {
    if (now >= retry_at_ns_) try_reopen(frame_number, now);
    return std::nullopt;
  }
  std::optional<Frame> frame;
  try {
    frame = source_->grab(frame_number);
  } catch (const FrameSourceError& e) {
    lose(e.what(), now);
    return std::nullopt;
  }
  const int64_t after = clock_ns_();
  if (frame) {
    misses_ = 0;
    return frame;
  }
  // Silence is measured from the first of consecutive triggers without a frame, not from the
  // last frame: a pause between runs is no silence.
  if (misses_++ == 0) first_miss_ns_ = now;
  if (options_.silent_s > 0 && misses_ >= kMinMisses &&
      after - first_miss_ns_ >= to_ns(options_.silent_s)) {
    lose("no frame for " + seconds_text(static_cast<double>(after - first_miss_ns_) * 1e-9) +
             " while triggers kept coming",
         after);
  }
  return frame;
}

void ReconnectingSource::lose(const std::string& why, int64_t now) {
  incomplete_before_ += source_->frames_incomplete();
  source_.reset();  // closes the device: a vanished camera's handles are useless
  why_ = why;
  lost_at_ns_ = now;
  attempts_ = 0;
  delay_s_ = options_.first_delay_s;
  retry_at_ns_ = now + to_ns(delay_s_);
}

void ReconnectingSource::try_reopen(int64_t frame_number, int64_t now) {
  ++attempts_;
  try {
    auto source = open_(frame_number + 1);
    if (!roi_.empty()) source->set_roi(roi_);
    if (exposure_us_) source->set_exposure_us(*exposure_us_);
    if (gain_db_) source->set_gain_db(*gain_db_);
    source_ = std::move(source);
    description_ = source_->describe();
    why_.clear();
    misses_ = 0;
    delay_s_ = options_.first_delay_s;
    ++reopened_;
    reopened_at_ns_ = now;
    reopen_note_ = "camera reopened after " +
                   seconds_text(static_cast<double>(now - lost_at_ns_) * 1e-9) +
                   " away, on attempt " + std::to_string(attempts_);
  } catch (const FrameSourceError& e) {
    why_ = e.what();
    delay_s_ = std::min(delay_s_ * 2, options_.max_delay_s);
    retry_at_ns_ = now + to_ns(delay_s_);
  }
}

std::string ReconnectingSource::describe() const { return description_; }

int64_t ReconnectingSource::frames_incomplete() const {
  return incomplete_before_ + (source_ ? source_->frames_incomplete() : 0);
}

void ReconnectingSource::note_trigger(int64_t frame_number, int64_t monotonic_ns) {
  if (source_) source_->note_trigger(frame_number, monotonic_ns);
}

cv::Rect ReconnectingSource::set_roi(const cv::Rect& roi) {
  const cv::Rect applied = source_ ? source_->set_roi(roi) : roi;
  roi_ = roi;
  return applied;
}

void ReconnectingSource::set_exposure_us(double exposure_us) {
  if (source_) source_->set_exposure_us(exposure_us);
  exposure_us_ = exposure_us;
}

void ReconnectingSource::set_gain_db(double gain_db) {
  if (source_) source_->set_gain_db(gain_db);
  gain_db_ = gain_db;
}

std::string ReconnectingSource::note() const {
  if (!source_ || reopened_ == 0 || clock_ns_() - reopened_at_ns_ >= to_ns(kNoteSeconds)) return {};
  return reopen_note_;
}

std::string ReconnectingSource::problem() const {
  if (source_) return source_->problem();
  const double wait_s = std::max<double>(0, static_cast<double>(retry_at_ns_ - clock_ns_()) * 1e-9);
  return "camera lost (" + why_ + "); reopening in " + seconds_text(wait_s);
}

}  // namespace syncap::edge
