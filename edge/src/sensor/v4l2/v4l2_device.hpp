// The system calls a V4L2 frame source makes, behind an interface so that its logic can be tested
// against a double that emulates a capture device. Every call behaves like the system call of
// the same name: -1 (or MAP_FAILED) and errno on failure.
#pragma once

#include <poll.h>
#include <sys/types.h>

#include <cstddef>
#include <memory>

namespace syncap::edge::v4l2 {

class V4l2Device {
 public:
  virtual ~V4l2Device() = default;
  virtual int open(const char* path, int flags) = 0;
  virtual int close(int fd) = 0;
  virtual int ioctl(int fd, unsigned long request, void* argument) = 0;
  virtual int poll(pollfd* fds, nfds_t count, int timeout_ms) = 0;
  virtual void* mmap(void* address, std::size_t length, int protection, int flags, int fd,
                     off_t offset) = 0;
  virtual int munmap(void* address, std::size_t length) = 0;
};

// The real thing: ::open, ::close, ::ioctl, ::poll, ::mmap, ::munmap.
std::shared_ptr<V4l2Device> system_v4l2_device();

}  // namespace syncap::edge::v4l2
