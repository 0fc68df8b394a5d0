#include "sensor/v4l2/v4l2_device.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace syncap::edge::v4l2 {
namespace {

class SystemV4l2Device final : public V4l2Device {
 public:
  int open(const char* path, int flags) override { return ::open(path, flags); }
  int close(int fd) override { return ::close(fd); }
  int ioctl(int fd, unsigned long request, void* argument) override {
    return ::ioctl(fd, request, argument);
  }
  int poll(pollfd* fds, nfds_t count, int timeout_ms) override {
    return ::poll(fds, count, timeout_ms);
  }
  void* mmap(void* address, std::size_t length, int protection, int flags, int fd,
             off_t offset) override {
    return ::mmap(address, length, protection, flags, fd, offset);
  }
  int munmap(void* address, std::size_t length) override { return ::munmap(address, length); }
};

}  // namespace

std::shared_ptr<V4l2Device> system_v4l2_device() {
  static const auto device = std::make_shared<SystemV4l2Device>();
  return device;
}

}  // namespace syncap::edge::v4l2
