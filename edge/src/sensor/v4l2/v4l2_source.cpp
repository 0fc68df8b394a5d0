#include "sensor/v4l2/v4l2_source.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include "syncap/proto/clock.hpp"

namespace syncap::edge::v4l2 {
namespace {

uint32_t fourcc(PixelFormat format) {
  switch (format) {
    case PixelFormat::grey:
      return V4L2_PIX_FMT_GREY;
    case PixelFormat::yuyv:
      return V4L2_PIX_FMT_YUYV;
    case PixelFormat::mjpeg:
      return V4L2_PIX_FMT_MJPEG;
  }
  return 0;
}

using proto::monotonic_now_ns;

std::string c_string(const uint8_t* text, std::size_t size) {
  const auto* begin = reinterpret_cast<const char*>(text);
  return std::string(begin, strnlen(begin, size));
}

}  // namespace

std::string to_string(PixelFormat format) {
  switch (format) {
    case PixelFormat::grey:
      return "GREY";
    case PixelFormat::yuyv:
      return "YUYV";
    case PixelFormat::mjpeg:
      return "MJPG";
  }
  return "?";
}

int64_t SequenceMapper::next(uint32_t sequence) {
  if (last_) {
    // Forward distance in 32-bit arithmetic (so a wrap is a step of 1); a driver that repeats
    // or goes back is taken one step forward rather than reusing a frame number.
    const auto step = static_cast<int32_t>(sequence - *last_);
    if (step > 1) lost_ += step - 1;
    number_ += std::max<int64_t>(step, 1);
  }
  last_ = sequence;
  return base_ + number_;
}

cv::Mat to_grey(PixelFormat format, const uint8_t* data, std::size_t bytes_used, int width,
                int height, int bytes_per_line) {
  if (width <= 0 || height <= 0 || data == nullptr || bytes_used == 0) return {};
  auto* pixels = const_cast<uint8_t*>(data);
  switch (format) {
    case PixelFormat::grey: {
      const std::size_t step = std::max(bytes_per_line, width);
      if (bytes_used < step * static_cast<std::size_t>(height - 1) + width) return {};
      return cv::Mat(height, width, CV_8UC1, pixels, step).clone();
    }
    case PixelFormat::yuyv: {
      const std::size_t step = std::max(bytes_per_line, 2 * width);
      if (bytes_used < step * static_cast<std::size_t>(height - 1) + 2 * width) return {};
      cv::Mat grey;
      cv::extractChannel(cv::Mat(height, width, CV_8UC2, pixels, step), grey, 0);  // Y0 U Y1 V
      return grey;
    }
    case PixelFormat::mjpeg: {
      cv::Mat grey;
      try {
        grey = cv::imdecode(cv::Mat(1, static_cast<int>(bytes_used), CV_8UC1, pixels),
                            cv::IMREAD_GRAYSCALE);
      } catch (const cv::Exception&) {
        return {};
      }
      return grey;
    }
  }
  return {};
}

V4l2Source::V4l2Source(const V4l2Options& options, int camera_id,
                       std::shared_ptr<V4l2Device> device)
    : options_(options),
      camera_id_(camera_id),
      device_(std::move(device)),
      sequence_(options.first_frame_number) {
  fd_ = device_->open(options_.device_path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) fail_errno("open");
  try {
    check_capabilities();
    negotiate_format();
    set_frame_rate();
    start_streaming();
  } catch (...) {
    shutdown();
    throw;
  }
}

V4l2Source::~V4l2Source() { shutdown(); }

void V4l2Source::fail(const std::string& step, const std::string& why) const {
  throw FrameSourceError(options_.device_path + ": " + step + ": " + why);
}

void V4l2Source::fail_errno(const std::string& step) const {
  const int error = errno;
  std::string why = std::strerror(error);
  if (error == ENODEV) why += " (device disconnected)";
  fail(step, why);
}

int V4l2Source::xioctl(unsigned long request, void* argument) {
  int result;
  do {
    result = device_->ioctl(fd_, request, argument);
  } while (result < 0 && errno == EINTR);
  return result;
}

void V4l2Source::check_capabilities() {
  v4l2_capability caps{};
  if (xioctl(VIDIOC_QUERYCAP, &caps) < 0) {
    if (errno == ENOTTY) fail("VIDIOC_QUERYCAP", "not a V4L2 device");
    fail_errno("VIDIOC_QUERYCAP");
  }
  driver_ = c_string(caps.driver, sizeof caps.driver);
  card_ = c_string(caps.card, sizeof caps.card);
  const uint32_t device_caps =
      (caps.capabilities & V4L2_CAP_DEVICE_CAPS) ? caps.device_caps : caps.capabilities;
  const std::string which = " (" + card_ + ", driver " + driver_ + ")";
  if (!(device_caps & V4L2_CAP_VIDEO_CAPTURE))
    fail("VIDIOC_QUERYCAP", "not a video capture device" + which);
  if (!(device_caps & V4L2_CAP_STREAMING)) fail("VIDIOC_QUERYCAP", "no streaming I/O" + which);
}

void V4l2Source::negotiate_format() {
  // S_FMT does not refuse a format the driver lacks: it answers with one it has. Ask for each
  // in order of preference and keep the first the driver accepts as asked.
  for (const PixelFormat format : {PixelFormat::grey, PixelFormat::yuyv, PixelFormat::mjpeg}) {
    v4l2_format request{};
    request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    request.fmt.pix.width = static_cast<uint32_t>(std::max(options_.width, 1));
    request.fmt.pix.height = static_cast<uint32_t>(std::max(options_.height, 1));
    request.fmt.pix.pixelformat = fourcc(format);
    request.fmt.pix.field = V4L2_FIELD_NONE;
    if (xioctl(VIDIOC_S_FMT, &request) < 0) {
      if (errno == EINVAL) continue;  // some drivers do refuse
      fail_errno("VIDIOC_S_FMT");
    }
    if (request.fmt.pix.pixelformat != fourcc(format)) continue;
    v4l2_format actual{};
    actual.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(VIDIOC_G_FMT, &actual) < 0) fail_errno("VIDIOC_G_FMT");
    if (actual.fmt.pix.pixelformat != fourcc(format))
      fail("VIDIOC_G_FMT", "driver switched from " + to_string(format) + " after VIDIOC_S_FMT");
    format_ = format;
    width_ = static_cast<int>(actual.fmt.pix.width);
    height_ = static_cast<int>(actual.fmt.pix.height);
    bytes_per_line_ = static_cast<int>(actual.fmt.pix.bytesperline);
    if (width_ <= 0 || height_ <= 0)
      fail("VIDIOC_G_FMT",
           "driver reports size " + std::to_string(width_) + "x" + std::to_string(height_));
    return;
  }
  fail("VIDIOC_S_FMT", "device supports none of GREY, YUYV, MJPG");
}

void V4l2Source::set_frame_rate() {
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(VIDIOC_G_PARM, &parm) < 0) {
    if (errno == EINVAL || errno == ENOTTY) return;  // the driver has no notion of a rate
    fail_errno("VIDIOC_G_PARM");
  }
  if (options_.fps > 0 && (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME)) {
    parm.parm.capture.timeperframe.numerator = 1000;
    parm.parm.capture.timeperframe.denominator =
        static_cast<uint32_t>(std::lround(options_.fps * 1000));
    if (xioctl(VIDIOC_S_PARM, &parm) < 0) fail_errno("VIDIOC_S_PARM");
  }
  const v4l2_fract& period = parm.parm.capture.timeperframe;
  fps_ = period.numerator > 0 ? static_cast<double>(period.denominator) / period.numerator : 0;
}

void V4l2Source::start_streaming() {
  v4l2_requestbuffers request{};
  request.count = static_cast<uint32_t>(std::max(options_.buffers, 2));
  request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  request.memory = V4L2_MEMORY_MMAP;
  if (xioctl(VIDIOC_REQBUFS, &request) < 0) fail_errno("VIDIOC_REQBUFS");
  requested_buffers_ = true;
  if (request.count < 2)
    fail("VIDIOC_REQBUFS", "driver granted " + std::to_string(request.count) + " buffers");
  for (uint32_t i = 0; i < request.count; ++i) {
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    buffer.index = i;
    const std::string which = " buffer " + std::to_string(i);
    if (xioctl(VIDIOC_QUERYBUF, &buffer) < 0) fail_errno("VIDIOC_QUERYBUF" + which);
    void* start = device_->mmap(nullptr, buffer.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_,
                                static_cast<off_t>(buffer.m.offset));
    if (start == MAP_FAILED) fail_errno("mmap" + which);
    buffers_.push_back({start, buffer.length});
  }
  for (uint32_t i = 0; i < request.count; ++i) {
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    buffer.index = i;
    if (xioctl(VIDIOC_QBUF, &buffer) < 0) fail_errno("VIDIOC_QBUF buffer " + std::to_string(i));
  }
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(VIDIOC_STREAMON, &type) < 0) fail_errno("VIDIOC_STREAMON");
  streaming_ = true;
}

void V4l2Source::shutdown() noexcept {
  if (fd_ < 0) return;
  if (streaming_) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(VIDIOC_STREAMOFF, &type);
    streaming_ = false;
  }
  for (const Buffer& buffer : buffers_) device_->munmap(buffer.start, buffer.length);
  buffers_.clear();
  if (requested_buffers_) {
    v4l2_requestbuffers release{};
    release.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    release.memory = V4L2_MEMORY_MMAP;
    xioctl(VIDIOC_REQBUFS, &release);  // count 0: the driver frees its buffers
    requested_buffers_ = false;
  }
  device_->close(fd_);
  fd_ = -1;
}

std::optional<Frame> V4l2Source::grab(int64_t frame_number) {
  bool lost = false;
  if (auto held = read_ahead_.take(frame_number, lost, stale_)) return held;
  if (lost) return std::nullopt;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options_.frame_timeout_ms);
  for (auto now = std::chrono::steady_clock::now(); now < deadline;
       now = std::chrono::steady_clock::now()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count();
    pollfd waiting{fd_, POLLIN, 0};
    const int ready = device_->poll(&waiting, 1, static_cast<int>(std::max<int64_t>(left, 1)));
    if (ready < 0) {
      if (errno == EINTR) continue;
      fail_errno("poll");
    }
    if (ready == 0) break;  // timeout
    // POLLERR/POLLHUP (not streaming, device gone) fall through: VIDIOC_DQBUF says why.
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    if (xioctl(VIDIOC_DQBUF, &buffer) < 0) {
      if (errno == EAGAIN) continue;
      fail_errno("VIDIOC_DQBUF");
    }
    const int64_t arrival_ns = monotonic_now_ns();
    if (buffer.index >= buffers_.size())
      fail("VIDIOC_DQBUF", "driver returned buffer " + std::to_string(buffer.index) + " of " +
                               std::to_string(buffers_.size()));
    const int64_t number = sequence_.next(buffer.sequence);
    bool complete = !(buffer.flags & V4L2_BUF_FLAG_ERROR);
    std::optional<Frame> frame;
    if (complete && number >= frame_number) {
      const Buffer& mapped = buffers_[buffer.index];
      cv::Mat image = to_grey(format_, static_cast<const uint8_t*>(mapped.start),
                              std::min<std::size_t>(buffer.bytesused, mapped.length), width_,
                              height_, bytes_per_line_);
      if (image.empty()) {
        complete = false;
      } else {
        frame.emplace();
        frame->camera_id = camera_id_;
        frame->frame_number = number;
        frame->exposure_us = options_.exposure_us;
        const bool monotonic =
            (buffer.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
        frame->monotonic_ns = monotonic
                                  ? static_cast<int64_t>(buffer.timestamp.tv_sec) * 1'000'000'000 +
                                        static_cast<int64_t>(buffer.timestamp.tv_usec) * 1000
                                  : arrival_ns;
        frame->image = std::move(image);
      }
    }
    if (xioctl(VIDIOC_QBUF, &buffer) < 0)
      fail_errno("VIDIOC_QBUF buffer " + std::to_string(buffer.index));
    if (!complete) {
      ++incomplete_;
      if (number >= frame_number) return std::nullopt;
      continue;
    }
    if (number < frame_number) {
      ++stale_;  // an exposure whose trigger this process never asked for
      continue;
    }
    if (number == frame_number) return frame;
    read_ahead_.hold(std::move(*frame));  // a later exposure came first: ours was lost
    return std::nullopt;
  }
  return std::nullopt;
}

std::string V4l2Source::describe() const {
  std::string text = "V4L2 camera " + options_.device_path + " (" + card_ + ", driver " + driver_ +
                     "), " + to_string(format_) + " " + std::to_string(width_) + "x" +
                     std::to_string(height_);
  if (fps_ > 0) {
    char rate[32];
    std::snprintf(rate, sizeof rate, " @ %.4g fps", fps_);
    text += rate;
  }
  return text;
}

std::unique_ptr<FrameSource> make_v4l2_source(const V4l2Options& options, int camera_id) {
  return std::make_unique<V4l2Source>(options, camera_id);
}

}  // namespace syncap::edge::v4l2
