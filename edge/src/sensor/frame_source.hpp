// Where frames come from: one interface for every kind of camera (replay, Aravis, V4L2), and
// for the wrappers that reopen a vanished camera or number frames by trigger time.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace syncap::edge {

struct Frame {
  int camera_id = 0;
  int64_t frame_number = -1;  // the trigger's frame number this exposure belongs to
  int32_t exposure_us = 0;
  int64_t monotonic_ns = 0;  // board clock when the frame arrived
  cv::Mat image;             // CV_8UC1
  // Where image(0, 0) lies on the sensor (a region of interest) and the sensor's size; an empty
  // sensor_size means the image is the whole sensor.
  cv::Point origin{0, 0};
  cv::Size sensor_size{};
  cv::Size full_size() const { return sensor_size.empty() ? image.size() : sensor_size; }
};

// A frame source failed in a way the caller should report (missing file, corrupt image, ...);
// what() names the input and the place.
class FrameSourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Camera sources read ahead: the exposure of a later trigger may arrive before the one asked
// for (which was then lost); it is held for the next grab.
class ReadAheadFrame {
 public:
  // The held frame when it is `frame_number` (taken out). Otherwise nothing, with `lost` set when
  // the held frame is later (so frame_number was lost; the frame stays held). A held frame older
  // than frame_number is dropped and counted in `stale`.
  std::optional<Frame> take(int64_t frame_number, bool& lost, int64_t& stale) {
    lost = false;
    if (!held_) return std::nullopt;
    if (held_->frame_number > frame_number) {
      lost = true;
      return std::nullopt;
    }
    std::optional<Frame> frame = std::move(held_);
    held_.reset();
    if (frame->frame_number == frame_number) return frame;
    ++stale;
    return std::nullopt;
  }
  void hold(Frame frame) { held_ = std::move(frame); }

 private:
  std::optional<Frame> held_;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The exposure that belongs to trigger `frame_number`, or nothing when the source has none
  // for it (a lost frame). Throws FrameSourceError for a frame that exists but cannot be read.
  virtual std::optional<Frame> grab(int64_t frame_number) = 0;
  // Human-readable description for logs and status messages.
  virtual std::string describe() const = 0;
  // Buffers the camera delivered incomplete (lost packets), since start.
  virtual int64_t frames_incomplete() const { return 0; }

  // A trigger pulse is about to be grabbed (its frame number and CLOCK_MONOTONIC time): sources
  // that number frames by time keep it.
  virtual void note_trigger(int64_t /*frame_number*/, int64_t /*monotonic_ns*/) {}
  // Restricts the sensor readout to `roi` (sensor pixels; an empty rectangle: the whole sensor)
  // and returns the region applied (cameras round to their increments). Throws FrameSourceError
  // when the source cannot window or refuses the region.
  virtual cv::Rect set_roi(const cv::Rect& roi) {
    if (roi.empty()) return roi;
    throw FrameSourceError(describe() + ": cannot set a region of interest");
  }
  // Sets the exposure time [us] / the analog gain [dB] (edge_command_t SET_EXPOSURE, SET_GAIN).
  // Throws FrameSourceError when the source has no such control or the camera refuses it.
  virtual void set_exposure_us(double exposure_us) {
    throw FrameSourceError(describe() + ": cannot set the exposure (" +
                           std::to_string(exposure_us) + " us)");
  }
  virtual void set_gain_db(double gain_db) {
    throw FrameSourceError(describe() + ": cannot set the gain (" + std::to_string(gain_db) +
                           " dB)");
  }
  // Why the source delivers nothing right now (camera gone, reopening ...), or empty.
  virtual std::string problem() const { return {}; }
  // A recent event worth telling that is no problem (the camera came back), or empty.
  virtual std::string note() const { return {}; }
};

}  // namespace syncap::edge
