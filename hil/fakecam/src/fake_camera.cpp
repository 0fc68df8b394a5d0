#include "fake_camera.hpp"

#include <arpa/inet.h>
#include <arv.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "genicam_xml.hpp"
#include "syncap/proto/clock.hpp"

namespace syncap::fakecam {
namespace {

// IP and UDP headers: what a packet costs on the link besides the GVSP bytes.
constexpr std::size_t kIpUdpOverhead = 20 + 8;
// Packets sent back to back before the pacer checks the link's time.
constexpr std::size_t kPacketsPerBurst = 16;

std::int64_t monotonic_ns() { return proto::monotonic_now_ns(); }

// Keeps a frame's packets to the rate of a link, as a real camera's network port does. On the
// loopback nothing else limits the rate, and a frame of hundreds of packets sent in one go
// overflows the receiver's socket buffer whenever its thread is not running at that moment.
class LinkPacer {
 public:
  explicit LinkPacer(std::uint32_t mbps) : mbps_(mbps), start_ns_(monotonic_ns()) {}

  // Counts a sent packet; after each burst, sleeps until the link would have carried them all.
  void sent(std::size_t bytes) {
    bytes_ += bytes + kIpUdpOverhead;
    if (mbps_ == 0 || ++packets_ % kPacketsPerBurst != 0) return;
    const std::int64_t due_ns = start_ns_ + static_cast<std::int64_t>(bytes_ * 8'000 / mbps_);
    const timespec due{static_cast<time_t>(due_ns / 1'000'000'000),
                       static_cast<long>(due_ns % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, nullptr);
  }

 private:
  std::uint32_t mbps_;
  std::int64_t start_ns_;
  std::uint64_t bytes_ = 0;
  std::size_t packets_ = 0;
};

// GigE Vision bootstrap registers (GigE Vision 2.0 spec, table 28), not in Aravis' public API.
constexpr std::uint32_t kStreamChannelPacketSizeRegister = 0x0d04;  // SCPS0
constexpr std::uint32_t kPacketSizeMask = 0xffff;

// What failed, with errno's text.
std::runtime_error system_error(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

// The GenICam XML of this Aravis' fake camera.
std::string stock_genicam_xml() {
  ArvFakeCamera* probe = arv_fake_camera_new("probe");
  size_t size = 0;
  const char* xml = probe != nullptr ? arv_fake_camera_get_genicam_xml(probe, &size) : nullptr;
  std::string copy = xml != nullptr ? std::string(xml, size) : std::string();
  if (probe != nullptr) g_object_unref(probe);
  if (copy.empty()) throw std::runtime_error("Aravis has no fake-camera GenICam XML");
  return copy;
}

// The stock XML patched (genicam_xml.hpp) in a temporary file, which Aravis reads once when the
// camera is created.
class PatchedXmlFile {
 public:
  PatchedXmlFile() {
    const std::string xml = patch_genicam_xml(stock_genicam_xml());
    std::string pattern =
        (std::filesystem::temp_directory_path() / "syncap-fakecam-XXXXXX").string();
    const int fd = mkstemp(pattern.data());
    if (fd < 0) throw system_error("cannot create a temporary file");
    close(fd);
    path_ = pattern;
    std::ofstream(path_, std::ios::binary) << xml;
  }
  ~PatchedXmlFile() { std::filesystem::remove(path_); }
  PatchedXmlFile(const PatchedXmlFile&) = delete;
  PatchedXmlFile& operator=(const PatchedXmlFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A UDP socket on the camera's address: the stream comes from there, as from a real camera.
int open_stream_socket(const std::string& address) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw system_error("cannot create the stream socket");
  sockaddr_in local{};
  local.sin_family = AF_INET;
  inet_pton(AF_INET, address.c_str(), &local.sin_addr);
  if (bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) < 0) {
    const auto error = system_error("cannot send from " + address +
                                    " (is it on an interface? run inside hil/netns-run)");
    close(fd);
    throw error;
  }
  return fd;
}

}  // namespace

struct FakeCamera::Arv {
  ArvGvFakeCamera* gv_camera = nullptr;
  ArvFakeCamera* camera = nullptr;  // owned by gv_camera

  std::uint32_t read(std::uint32_t address) const {
    guint32 value = 0;
    arv_fake_camera_read_register(camera, address, &value);
    return value;
  }
  void write(std::uint32_t address, std::uint32_t value) const {
    arv_fake_camera_write_register(camera, address, value);
  }

  // A Mono8 sensor of the images' size, the region the whole of it, and the trigger registers.
  void set_up(std::uint32_t width, std::uint32_t height, TriggerSpec::Kind trigger) const {
    write(ARV_FAKE_CAMERA_REGISTER_SENSOR_WIDTH, width);
    write(ARV_FAKE_CAMERA_REGISTER_SENSOR_HEIGHT, height);
    write(ARV_FAKE_CAMERA_REGISTER_WIDTH, width);
    write(ARV_FAKE_CAMERA_REGISTER_HEIGHT, height);
    write(ARV_FAKE_CAMERA_REGISTER_X_OFFSET, 0);
    write(ARV_FAKE_CAMERA_REGISTER_Y_OFFSET, 0);
    write(ARV_FAKE_CAMERA_REGISTER_PIXEL_FORMAT, ARV_PIXEL_FORMAT_MONO_8);
    // Hardware trigger on Line0 in Aravis' own registers: its streaming thread never fires.
    write(kStockTriggerModeRegister, 1);
    write(kStockTriggerSourceRegister, kTriggerSourceLine0);
    // What the client reads back: triggered, from the source the command line chose.
    write(kShadowTriggerModeRegister, 1);
    write(kShadowTriggerSourceRegister,
          trigger == TriggerSpec::Kind::software ? kTriggerSourceSoftware : kTriggerSourceLine0);
    write(kShadowTriggerSoftwareRegister, 0);
  }
};

FakeCamera::FakeCamera(const std::string& address, const std::string& serial, int width, int height,
                       TriggerSpec::Kind trigger, std::uint32_t link_mbps)
    : arv_(std::make_unique<Arv>()), link_mbps_(link_mbps) {
  const PatchedXmlFile xml;
  socket_ = open_stream_socket(address);
  arv_->gv_camera =
      arv_gv_fake_camera_new_full(address.c_str(), serial.c_str(), xml.path().c_str());
  if (arv_->gv_camera == nullptr || !arv_gv_fake_camera_is_running(arv_->gv_camera)) {
    if (arv_->gv_camera != nullptr) g_object_unref(arv_->gv_camera);
    close(socket_);
    throw std::runtime_error("cannot serve a GigE Vision camera on " + address +
                             " (GVCP port 3956 taken by another camera there?)");
  }
  arv_->camera = arv_gv_fake_camera_get_fake_camera(arv_->gv_camera);
  arv_->set_up(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), trigger);
}

FakeCamera::~FakeCamera() {
  g_object_unref(arv_->gv_camera);  // stops Aravis' thread and closes its sockets
  close(socket_);
}

bool FakeCamera::is_acquiring() const {
  return arv_fake_camera_get_control_channel_privilege(arv_->camera) != 0 &&
         arv_fake_camera_get_acquisition_status(arv_->camera) != 0;
}

Region FakeCamera::region() const {
  return {arv_->read(ARV_FAKE_CAMERA_REGISTER_X_OFFSET),
          arv_->read(ARV_FAKE_CAMERA_REGISTER_Y_OFFSET), arv_->read(ARV_FAKE_CAMERA_REGISTER_WIDTH),
          arv_->read(ARV_FAKE_CAMERA_REGISTER_HEIGHT)};
}

std::uint32_t FakeCamera::packet_size() const {
  return arv_->read(kStreamChannelPacketSizeRegister) & kPacketSizeMask;
}

bool FakeCamera::take_software_trigger() {
  if (arv_->read(kShadowTriggerSoftwareRegister) == 0) return false;
  arv_->write(kShadowTriggerSoftwareRegister, 0);
  return true;
}

bool FakeCamera::send_frame(const GvspImage& image) {
  GSocketAddress* destination = arv_fake_camera_get_stream_address(arv_->camera);
  sockaddr_in target{};
  const bool has_target =
      destination != nullptr &&
      g_socket_address_to_native(destination, &target, sizeof target, nullptr) &&
      target.sin_port != 0;
  if (destination != nullptr) g_object_unref(destination);
  if (!has_target) return false;
  bool sent_all = true;
  LinkPacer pacer(link_mbps_);
  const bool encoded =
      encode_gvsp_frame(image, packet_size(), [&](std::span<const std::uint8_t> packet) {
        const ssize_t sent = sendto(socket_, packet.data(), packet.size(), 0,
                                    reinterpret_cast<const sockaddr*>(&target), sizeof target);
        sent_all = sent_all && sent == static_cast<ssize_t>(packet.size());
        pacer.sent(packet.size());
      });
  return encoded && sent_all;
}

}  // namespace syncap::fakecam
