// Test helper: an Aravis client of one fake camera, opened by address (never by discovery),
// Mono8, with a region and a trigger source, that receives frames with their pixels.
#pragma once

#include <arv.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>
#include "syncap/proto/clock.hpp"

namespace syncap::test {

template <class T>
struct GObjectUnref {
  void operator()(T* object) const { g_object_unref(object); }
};
template <class T>
using GPtr = std::unique_ptr<T, GObjectUnref<T>>;

struct Region {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
};

struct ReceivedFrame {
  ArvBufferStatus status = ARV_BUFFER_STATUS_UNKNOWN;
  std::uint16_t block_id = 0;
  std::uint64_t timestamp_ns = 0;
  std::int64_t arrival_ns = 0;  // CLOCK_MONOTONIC when the test got it
  Region region;
  ArvPixelFormat pixel_format = 0;
  std::vector<std::uint8_t> pixels;
};

inline std::int64_t monotonic_ns() { return proto::monotonic_now_ns(); }

// Every method throws std::runtime_error saying what failed.
class AravisClient {
 public:
  static constexpr int kBuffers = 32;
  static constexpr int kSocketBufferBytes = 4 << 20;

  explicit AravisClient(const std::string& camera_address) {
    GPtr<GInetAddress> client(g_inet_address_new_from_string("127.0.0.1"));
    GPtr<GInetAddress> camera(g_inet_address_new_from_string(camera_address.c_str()));
    device_.reset(arv_gv_device_new(client.get(), camera.get(), error_out()));
    check(device_ != nullptr, "opening " + camera_address);
    // Packet sockets see loopback traffic in both directions; plain UDP sockets are enough here.
    arv_gv_device_set_stream_options(ARV_GV_DEVICE(device_.get()),
                                     ARV_GV_STREAM_OPTION_PACKET_SOCKET_DISABLED);
    camera_.reset(arv_camera_new_with_device(device_.get(), error_out()));
    check(camera_ != nullptr, "camera on " + camera_address);
  }
  ~AravisClient() {
    if (stream_) arv_camera_stop_acquisition(camera_.get(), nullptr);
    stream_.reset();
    camera_.reset();
    device_.reset();
    g_clear_error(&error_);
  }
  AravisClient(const AravisClient&) = delete;
  AravisClient& operator=(const AravisClient&) = delete;

  // Mono8, the region (or the whole sensor when width is 0), hardware ("Line0") or "Software"
  // trigger, a stream with kBuffers buffers, acquisition started.
  void start(const std::string& trigger_source, Region region = {}) {
    ArvCamera* camera = camera_.get();
    arv_camera_set_pixel_format(camera, ARV_PIXEL_FORMAT_MONO_8, error_out());
    check("pixel format");
    if (region.width > 0) {
      arv_camera_set_region(camera, region.x, region.y, region.width, region.height, error_out());
      check("region");
    }
    arv_camera_set_acquisition_mode(camera, ARV_ACQUISITION_MODE_CONTINUOUS, error_out());
    check("acquisition mode");
    arv_camera_set_trigger(camera, trigger_source.c_str(), error_out());
    check("trigger " + trigger_source);
    const guint payload = arv_camera_get_payload(camera, error_out());
    check("payload");
    stream_.reset(arv_camera_create_stream(camera, nullptr, nullptr, error_out()));
    check(stream_ != nullptr, "stream");
    // Room for several frames: with the CPU busy the receiving thread may sleep for milliseconds
    // while packets keep coming (Aravis' default is one payload, less kernel overhead).
    g_object_set(stream_.get(), "socket-buffer", ARV_GV_STREAM_SOCKET_BUFFER_FIXED,
                 "socket-buffer-size", kSocketBufferBytes, nullptr);
    for (int i = 0; i < kBuffers; ++i)
      arv_stream_push_buffer(stream_.get(), arv_buffer_new_allocate(payload));
    arv_camera_start_acquisition(camera, error_out());
    check("start");
  }

  void software_trigger() {
    arv_camera_software_trigger(camera_.get(), error_out());
    check("software trigger");
  }

  std::string string_feature(const char* name) {
    const char* value = arv_device_get_string_feature_value(device_.get(), name, error_out());
    check(name);
    return value;
  }

  // The next frame, or nothing within timeout_ms.
  std::optional<ReceivedFrame> receive(int timeout_ms) {
    ArvBuffer* buffer =
        arv_stream_timeout_pop_buffer(stream_.get(), static_cast<guint64>(timeout_ms) * 1000);
    if (buffer == nullptr) return std::nullopt;
    ReceivedFrame frame{
        .status = arv_buffer_get_status(buffer),
        .block_id = static_cast<std::uint16_t>(arv_buffer_get_frame_id(buffer)),
        .timestamp_ns = arv_buffer_get_timestamp(buffer),
        .arrival_ns = monotonic_ns(),
        .region = {arv_buffer_get_image_x(buffer), arv_buffer_get_image_y(buffer),
                   arv_buffer_get_image_width(buffer), arv_buffer_get_image_height(buffer)},
        .pixel_format = arv_buffer_get_image_pixel_format(buffer),
        .pixels = {}};
    size_t size = 0;
    const auto* data = static_cast<const std::uint8_t*>(arv_buffer_get_image_data(buffer, &size));
    if (data != nullptr) frame.pixels.assign(data, data + size);
    arv_stream_push_buffer(stream_.get(), buffer);
    return frame;
  }

  // Packets Aravis never got.
  std::uint64_t missing_packets() {
    return arv_stream_get_info_uint64_by_name(stream_.get(), "n_missing_packets");
  }

  // Frames Aravis saw missing: gaps in the block ids.
  std::uint64_t missing_frames() {
    return arv_stream_get_info_uint64_by_name(stream_.get(), "n_missing_frames");
  }

 private:
  GError** error_out() {
    g_clear_error(&error_);
    return &error_;
  }
  void check(const std::string& what) { check(error_ == nullptr, what); }
  void check(bool ok, const std::string& what) {
    if (!ok)
      throw std::runtime_error(what + ": " + (error_ != nullptr ? error_->message : "failed"));
  }

  GError* error_ = nullptr;
  GPtr<ArvDevice> device_;
  GPtr<ArvCamera> camera_;
  GPtr<ArvStream> stream_;
};

}  // namespace syncap::test
