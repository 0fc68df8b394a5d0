// A UVC (or any V4L2 capture) camera through V4L2 mmap streaming, e.g. /dev/video0.
//
// Formats: the source asks the driver for GREY, then YUYV (keeps the Y plane), then MJPEG
// (decoded to grey with OpenCV), at the requested size; the driver may adjust the size, and
// width()/height() report what it chose.
//
// Frame numbers: UVC cameras have no trigger input, so frame numbers come from V4L2's buffer
// sequence numbers: frame number = sequence - first sequence seen + options.first_frame_number.
// Sequence numbers the driver skipped are counted lost. Matching frames to trigger messages by
// time is the edge's job; Frame::monotonic_ns carries the buffer's CLOCK_MONOTONIC timestamp
// (or the dequeue time when the driver's timestamps are not monotonic).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sensor/frame_source.hpp"
#include "sensor/v4l2/v4l2_device.hpp"

namespace syncap::edge::v4l2 {

struct V4l2Options {
  std::string device_path = "/dev/video0";
  int width = 640;  // requested; the driver may adjust
  int height = 480;
  double fps = 0;                  // requested with VIDIOC_S_PARM when > 0 and supported
  int buffers = 4;                 // mmap buffers asked for with VIDIOC_REQBUFS
  int frame_timeout_ms = 1000;     // how long grab() waits for a frame
  int64_t first_frame_number = 0;  // the frame number of the first buffer dequeued
  int32_t exposure_us = 0;         // reported in every Frame; not set on the camera
};

enum class PixelFormat { grey, yuyv, mjpeg };
std::string to_string(PixelFormat format);  // "GREY", "YUYV", "MJPG"

// Maps 32-bit V4L2 buffer sequence numbers to frame numbers and counts the skipped ones.
class SequenceMapper {
 public:
  explicit SequenceMapper(int64_t base = 0) : base_(base) {}
  int64_t next(uint32_t sequence);
  int64_t lost() const { return lost_; }

 private:
  int64_t base_;
  std::optional<uint32_t> last_;
  int64_t number_ = 0;
  int64_t lost_ = 0;
};

// The grey image in a buffer of `format`: GREY and YUYV rows `bytes_per_line` apart, MJPEG of
// `bytes_used` bytes. Empty when the buffer is too short or the JPEG does not decode.
cv::Mat to_grey(PixelFormat format, const uint8_t* data, std::size_t bytes_used, int width,
                int height, int bytes_per_line);

class V4l2Source : public FrameSource {
 public:
  // Opens the device, checks it captures with streaming I/O, negotiates format, size and rate,
  // maps the buffers and starts streaming. Throws FrameSourceError naming the device and the
  // step ("/dev/video2: VIDIOC_S_FMT: device supports none of GREY, YUYV, MJPG").
  V4l2Source(const V4l2Options& options, int camera_id,
             std::shared_ptr<V4l2Device> device = system_v4l2_device());
  ~V4l2Source() override;  // STREAMOFF, munmap, close
  V4l2Source(const V4l2Source&) = delete;
  V4l2Source& operator=(const V4l2Source&) = delete;

  // The exposure of `frame_number`: frames before it still queued are stale and dropped
  // (counted); a later frame arriving first means this one was lost, and is kept for the next
  // call. Buffers flagged V4L2_BUF_FLAG_ERROR (or short, or undecodable JPEG) are counted
  // incomplete and never returned. Throws FrameSourceError when dequeuing fails (EIO, ENODEV).
  std::optional<Frame> grab(int64_t frame_number) override;
  std::string describe() const override;
  int64_t frames_incomplete() const override { return incomplete_; }

  int64_t frames_stale() const { return stale_; }
  int64_t frames_lost() const { return sequence_.lost(); }  // sequence numbers skipped
  PixelFormat format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double fps() const { return fps_; }  // 0: unknown (the driver cannot set the rate)

 private:
  struct Buffer {
    void* start = nullptr;
    std::size_t length = 0;
  };
  [[noreturn]] void fail(const std::string& step, const std::string& why) const;
  [[noreturn]] void fail_errno(const std::string& step) const;
  int xioctl(unsigned long request, void* argument);
  void check_capabilities();
  void negotiate_format();
  void set_frame_rate();
  void start_streaming();
  void shutdown() noexcept;

  V4l2Options options_;
  int camera_id_;
  std::shared_ptr<V4l2Device> device_;
  int fd_ = -1;
  std::string card_;
  std::string driver_;
  PixelFormat format_ = PixelFormat::grey;
  int width_ = 0;
  int height_ = 0;
  int bytes_per_line_ = 0;
  double fps_ = 0;
  bool requested_buffers_ = false;
  bool streaming_ = false;
  std::vector<Buffer> buffers_;
  SequenceMapper sequence_;
  ReadAheadFrame read_ahead_;  // a frame that arrived before its trigger was asked for
  int64_t stale_ = 0;
  int64_t incomplete_ = 0;
};

// For syncap-edge's `--source v4l2:/dev/video0`: the source as a FrameSource.
std::unique_ptr<FrameSource> make_v4l2_source(const V4l2Options& options, int camera_id);

}  // namespace syncap::edge::v4l2
