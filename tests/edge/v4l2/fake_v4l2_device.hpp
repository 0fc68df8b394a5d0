// A test double of the V4L2 system calls: emulates one capture device with its capabilities,
// the pixel formats it has, a buffer queue fed by scripted frames, and injected errors. Every
// call is recorded in `calls` ("open", "VIDIOC_S_FMT GREY", "munmap 2", "close", ...).
#pragma once

#include <linux/videodev2.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "sensor/v4l2/v4l2_device.hpp"

namespace syncap::edge::v4l2::testing {

inline std::string fourcc_name(uint32_t code) {
  std::string name(4, ' ');
  for (int i = 0; i < 4; ++i) name[i] = static_cast<char>((code >> (8 * i)) & 0xff);
  return name;
}

struct ScriptedFrame {
  uint32_t sequence = 0;
  std::vector<uint8_t> data;  // copied into the buffer; bytesused = data.size()
  bool error = false;         // V4L2_BUF_FLAG_ERROR
  int64_t timestamp_us = 0;   // with V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC unless monotonic = false
  bool monotonic = true;
  int dqbuf_errno = 0;  // non-zero: VIDIOC_DQBUF fails with this errno instead
};

class FakeV4l2Device : public V4l2Device {
 public:
  static constexpr int kFd = 42;

  // What the device is.
  int open_errno = 0;
  uint32_t capabilities = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
  std::vector<uint32_t> formats = {V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_MJPEG};
  uint32_t max_width = 1280;
  uint32_t max_height = 720;
  uint32_t line_padding = 0;  // bytes at the end of each line
  bool timeperframe = true;
  uint32_t max_buffers = 8;
  std::map<std::string, int> fail_ioctl;  // request name -> errno
  std::deque<ScriptedFrame> script;

  // What happened.
  std::vector<std::string> calls;
  v4l2_pix_format format{};
  v4l2_fract period{1, 30};
  bool streaming = false;
  int open_fds = 0;
  int mapped = 0;

  int open(const char*, int) override {
    calls.push_back("open");
    if (open_errno) return fail(open_errno);
    ++open_fds;
    return kFd;
  }
  int close(int fd) override {
    calls.push_back("close");
    if (fd != kFd) return fail(EBADF);
    --open_fds;
    return 0;
  }
  int poll(pollfd* fds, nfds_t, int) override {
    calls.push_back("poll");
    fds[0].revents = 0;
    if (script.empty()) return 0;  // a timeout, at once
    if (script.front().dqbuf_errno == 0 && queued_.empty()) return 0;
    fds[0].revents = script.front().dqbuf_errno ? POLLERR : POLLIN;
    return 1;
  }
  void* mmap(void*, std::size_t length, int, int, int fd, off_t offset) override {
    calls.push_back("mmap " + std::to_string(offset / kPage));
    const auto index = static_cast<std::size_t>(offset / kPage);
    if (fd != kFd || index >= buffers_.size() || length != buffers_[index].size()) {
      errno = EINVAL;
      return MAP_FAILED;
    }
    ++mapped;
    return buffers_[index].data();
  }
  int munmap(void* address, std::size_t) override {
    for (std::size_t i = 0; i < buffers_.size(); ++i) {
      if (buffers_[i].data() == address) {
        calls.push_back("munmap " + std::to_string(i));
        --mapped;
        return 0;
      }
    }
    calls.push_back("munmap ?");
    return fail(EINVAL);
  }

  int ioctl(int fd, unsigned long request, void* argument) override {
    const std::string name = request_name(request);
    std::string call = name;
    if (request == VIDIOC_S_FMT)
      call += " " + fourcc_name(static_cast<v4l2_format*>(argument)->fmt.pix.pixelformat);
    if (request == VIDIOC_REQBUFS)
      call += " " + std::to_string(static_cast<v4l2_requestbuffers*>(argument)->count);
    calls.push_back(call);
    if (fd != kFd) return fail(EBADF);
    if (auto it = fail_ioctl.find(name); it != fail_ioctl.end()) return fail(it->second);
    switch (request) {
      case VIDIOC_QUERYCAP: {
        auto* caps = static_cast<v4l2_capability*>(argument);
        *caps = {};
        std::strcpy(reinterpret_cast<char*>(caps->driver), "fakevideo");
        std::strcpy(reinterpret_cast<char*>(caps->card), "Fake Camera");
        caps->capabilities = capabilities | V4L2_CAP_DEVICE_CAPS;
        caps->device_caps = capabilities;
        return 0;
      }
      case VIDIOC_S_FMT: {
        auto* request_format = static_cast<v4l2_format*>(argument);
        if (streaming) return fail(EBUSY);
        v4l2_pix_format& pix = request_format->fmt.pix;
        bool known = false;
        for (uint32_t f : formats) known = known || f == pix.pixelformat;
        if (!known) pix.pixelformat = formats.empty() ? V4L2_PIX_FMT_RGB24 : formats.front();
        pix.width = std::min(pix.width, max_width);
        pix.height = std::min(pix.height, max_height);
        pix.field = V4L2_FIELD_NONE;
        const uint32_t bytes_per_pixel = pix.pixelformat == V4L2_PIX_FMT_YUYV    ? 2
                                         : pix.pixelformat == V4L2_PIX_FMT_RGB24 ? 3
                                                                                 : 1;
        pix.bytesperline =
            pix.pixelformat == V4L2_PIX_FMT_MJPEG ? 0 : pix.width * bytes_per_pixel + line_padding;
        pix.sizeimage = pix.pixelformat == V4L2_PIX_FMT_MJPEG ? pix.width * pix.height * 2
                                                              : pix.bytesperline * pix.height;
        format = pix;
        return 0;
      }
      case VIDIOC_G_FMT:
        static_cast<v4l2_format*>(argument)->fmt.pix = format;
        return 0;
      case VIDIOC_G_PARM:
      case VIDIOC_S_PARM: {
        auto* parm = static_cast<v4l2_streamparm*>(argument);
        if (!timeperframe) return fail(EINVAL);
        if (request == VIDIOC_S_PARM) period = parm->parm.capture.timeperframe;
        parm->parm.capture.capability = V4L2_CAP_TIMEPERFRAME;
        parm->parm.capture.timeperframe = period;
        return 0;
      }
      case VIDIOC_REQBUFS: {
        auto* buffers = static_cast<v4l2_requestbuffers*>(argument);
        if (streaming) return fail(EBUSY);
        buffers->count = std::min(buffers->count, max_buffers);
        buffers_.assign(buffers->count, std::vector<uint8_t>(format.sizeimage));
        queued_.clear();
        return 0;
      }
      case VIDIOC_QUERYBUF: {
        auto* buffer = static_cast<v4l2_buffer*>(argument);
        if (buffer->index >= buffers_.size()) return fail(EINVAL);
        buffer->length = static_cast<uint32_t>(buffers_[buffer->index].size());
        buffer->m.offset = buffer->index * kPage;
        return 0;
      }
      case VIDIOC_QBUF: {
        auto* buffer = static_cast<v4l2_buffer*>(argument);
        if (buffer->index >= buffers_.size()) return fail(EINVAL);
        queued_.push_back(buffer->index);
        return 0;
      }
      case VIDIOC_DQBUF:
        return dequeue(*static_cast<v4l2_buffer*>(argument));
      case VIDIOC_STREAMON:
        streaming = true;
        return 0;
      case VIDIOC_STREAMOFF:
        streaming = false;
        queued_.clear();
        return 0;
      default:
        return fail(ENOTTY);
    }
  }

  // Calls whose text starts with `prefix`.
  int count(const std::string& prefix) const {
    int n = 0;
    for (const auto& call : calls) n += call.rfind(prefix, 0) == 0;
    return n;
  }

 private:
  static constexpr off_t kPage = 4096;

  static int fail(int error) {
    errno = error;
    return -1;
  }

  static std::string request_name(unsigned long request) {
    switch (request) {
      case VIDIOC_QUERYCAP:
        return "VIDIOC_QUERYCAP";
      case VIDIOC_S_FMT:
        return "VIDIOC_S_FMT";
      case VIDIOC_G_FMT:
        return "VIDIOC_G_FMT";
      case VIDIOC_G_PARM:
        return "VIDIOC_G_PARM";
      case VIDIOC_S_PARM:
        return "VIDIOC_S_PARM";
      case VIDIOC_REQBUFS:
        return "VIDIOC_REQBUFS";
      case VIDIOC_QUERYBUF:
        return "VIDIOC_QUERYBUF";
      case VIDIOC_QBUF:
        return "VIDIOC_QBUF";
      case VIDIOC_DQBUF:
        return "VIDIOC_DQBUF";
      case VIDIOC_STREAMON:
        return "VIDIOC_STREAMON";
      case VIDIOC_STREAMOFF:
        return "VIDIOC_STREAMOFF";
      default:
        return "ioctl " + std::to_string(request);
    }
  }

  int dequeue(v4l2_buffer& buffer) {
    if (!streaming) return fail(EINVAL);
    if (script.empty()) return fail(EAGAIN);
    ScriptedFrame next = script.front();
    if (next.dqbuf_errno) {
      script.pop_front();
      return fail(next.dqbuf_errno);
    }
    if (queued_.empty()) return fail(EAGAIN);
    script.pop_front();
    const uint32_t index = queued_.front();
    queued_.pop_front();
    std::vector<uint8_t>& storage = buffers_[index];
    const std::size_t size = std::min(storage.size(), next.data.size());
    std::memcpy(storage.data(), next.data.data(), size);
    buffer.index = index;
    buffer.bytesused = static_cast<uint32_t>(size);
    buffer.sequence = next.sequence;
    buffer.flags =
        (next.error ? V4L2_BUF_FLAG_ERROR : 0) |
        (next.monotonic ? V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC : V4L2_BUF_FLAG_TIMESTAMP_UNKNOWN);
    buffer.timestamp.tv_sec = static_cast<time_t>(next.timestamp_us / 1'000'000);
    buffer.timestamp.tv_usec = static_cast<suseconds_t>(next.timestamp_us % 1'000'000);
    return 0;
  }

  std::vector<std::vector<uint8_t>> buffers_;
  std::deque<uint32_t> queued_;
};

}  // namespace syncap::edge::v4l2::testing
