#include "sensor/aravis_source.hpp"

#include <arpa/inet.h>
#include <arv.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include "syncap/proto/clock.hpp"

namespace syncap::edge {
namespace {

template <class T>
struct Unref {
  void operator()(T* object) const {
    if (object) g_object_unref(object);
  }
};
template <class T>
using GPtr = std::unique_ptr<T, Unref<T>>;

using proto::monotonic_now_ns;
using proto::realtime_now_ns;

// The local address the kernel would send from to reach `device`: a connected UDP socket sends
// nothing but tells.
std::string route_source_address(const std::string& device) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(3956);  // GVCP
  if (fd < 0 || inet_pton(AF_INET, device.c_str(), &to.sin_addr) != 1 ||
      connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
    if (fd >= 0) close(fd);
    throw FrameSourceError("camera " + device + ": not an IPv4 address with a route");
  }
  sockaddr_in local{};
  socklen_t length = sizeof local;
  getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length);
  close(fd);
  char text[INET_ADDRSTRLEN] = "";
  inet_ntop(AF_INET, &local.sin_addr, text, sizeof text);
  return text;
}

// Throws with the camera's address and what was being done when `error` is set.
void check(GError* error, const std::string& address, const std::string& what) {
  if (!error) return;
  const std::string message = error->message;
  g_error_free(error);
  throw FrameSourceError("camera " + address + ": " + what + ": " + message);
}

}  // namespace

struct AravisSource::Camera {
  GPtr<ArvCamera> camera;
  GPtr<ArvStream> stream;
  std::atomic<bool> control_lost{false};  // set from Aravis' heartbeat thread
  gulong control_lost_handler = 0;
};

namespace {

void on_control_lost(ArvDevice*, gpointer flag) {
  static_cast<std::atomic<bool>*>(flag)->store(true);
}

}  // namespace

AravisSource::AravisSource(const AravisOptions& options, int camera_id)
    : options_(options),
      camera_id_(camera_id),
      camera_(std::make_unique<Camera>()),
      numbering_(options.reopened, options.trigger_tolerance_ns) {
  const std::string& address = options_.device_address;
  const std::string local = options_.interface_address.empty() ? route_source_address(address)
                                                               : options_.interface_address;
  GPtr<GInetAddress> local_address(g_inet_address_new_from_string(local.c_str()));
  GPtr<GInetAddress> device_address(g_inet_address_new_from_string(address.c_str()));
  if (!local_address || !device_address)
    throw FrameSourceError("camera " + address + ": bad address");
  GError* error = nullptr;
  GPtr<ArvDevice> device(arv_gv_device_new(local_address.get(), device_address.get(), &error));
  check(error, address, "opening by address from " + local);
  if (options_.udp_socket) {
    arv_gv_device_set_stream_options(ARV_GV_DEVICE(device.get()),
                                     ARV_GV_STREAM_OPTION_PACKET_SOCKET_DISABLED);
  }
  camera_->camera.reset(arv_camera_new_with_device(device.get(), &error));
  check(error, address, "creating the camera");
  camera_->control_lost_handler = g_signal_connect(
      device.get(), "control-lost", G_CALLBACK(on_control_lost), &camera_->control_lost);
  ArvCamera* cam = camera_->camera.get();
  arv_camera_set_pixel_format(cam, ARV_PIXEL_FORMAT_MONO_8, &error);
  check(error, address, "setting Mono8");
  arv_camera_set_acquisition_mode(cam, ARV_ACQUISITION_MODE_CONTINUOUS, &error);
  check(error, address, "setting continuous acquisition");
  if (!options_.trigger_source.empty()) {
    arv_camera_set_trigger(cam, options_.trigger_source.c_str(), &error);
    check(error, address, "setting TriggerSource " + options_.trigger_source);
  }
  if (options_.exposure_us > 0) {
    arv_camera_set_exposure_time(cam, options_.exposure_us, &error);
    check(error, address, "setting the exposure");
  }
  if (options_.gain_db >= 0) {
    arv_camera_set_gain(cam, options_.gain_db, &error);
    check(error, address, "setting the gain");
  }
  gint sensor_width = 0, sensor_height = 0;
  arv_camera_get_sensor_size(cam, &sensor_width, &sensor_height, &error);
  check(error, address, "reading the sensor size");
  sensor_size_ = {sensor_width, sensor_height};
  gint x = 0, y = 0, width = 0, height = 0;
  arv_camera_get_region(cam, &x, &y, &width, &height, &error);
  check(error, address, "reading the region of interest");
  region_ = {x, y, width, height};
  camera_->stream.reset(arv_camera_create_stream(cam, nullptr, nullptr, &error));
  check(error, address, "creating the stream");
  // A frame is hundreds of packets and lost ones are not resent: give the socket room for a
  // few whole frames instead of Aravis' default.
  if (ARV_IS_GV_STREAM(camera_->stream.get())) {
    // And wait longer for a frame's last packets than Aravis' 100 ms before calling it
    // incomplete: a loaded board (or six cameras' bursts at once) delays the receiving thread.
    g_object_set(camera_->stream.get(), "socket-buffer", ARV_GV_STREAM_SOCKET_BUFFER_FIXED,
                 "socket-buffer-size", 4 << 20, "frame-retention", 500000u, nullptr);
  }
  push_buffers();
  arv_camera_start_acquisition(cam, &error);
  check(error, address, "starting acquisition");
}

AravisSource::~AravisSource() {
  if (!camera_ || !camera_->camera) return;
  ArvCamera* cam = camera_->camera.get();
  // A vanished camera does not answer: skip the stop command's retries.
  if (!camera_->control_lost) arv_camera_stop_acquisition(cam, nullptr);
  if (camera_->control_lost_handler)
    g_signal_handler_disconnect(arv_camera_get_device(cam), camera_->control_lost_handler);
}

void AravisSource::push_buffers() {
  GError* error = nullptr;
  const guint payload = arv_camera_get_payload(camera_->camera.get(), &error);
  check(error, options_.device_address, "reading the payload size");
  for (int i = 0; i < options_.buffers; ++i) {
    arv_stream_push_buffer(camera_->stream.get(), arv_buffer_new_allocate(payload));
  }
}

cv::Rect AravisSource::set_roi(const cv::Rect& roi) {
  const std::string& address = options_.device_address;
  const cv::Rect wanted = roi.empty() ? cv::Rect(cv::Point(0, 0), sensor_size_) : roi;
  ArvCamera* cam = camera_->camera.get();
  ArvStream* stream = camera_->stream.get();
  GError* error = nullptr;
  // Width and Height are locked while acquiring, and the payload changes with them.
  arv_camera_stop_acquisition(cam, &error);
  check(error, address, "stopping acquisition for a new region");
  arv_stream_stop_thread(stream, TRUE);  // and free the buffers of the old payload size
  arv_camera_set_region(cam, wanted.x, wanted.y, wanted.width, wanted.height, &error);
  GError* refused = error;
  error = nullptr;
  gint x = 0, y = 0, width = 0, height = 0;
  arv_camera_get_region(cam, &x, &y, &width, &height, &error);
  check(error, address, "reading the region of interest");
  region_ = {x, y, width, height};
  read_ahead_ = ReadAheadFrame{};  // a held frame of the old region
  arv_stream_start_thread(stream);
  push_buffers();
  arv_camera_start_acquisition(cam, &error);
  check(error, address, "starting acquisition");
  check(refused, address,
        "setting the region " + std::to_string(wanted.width) + "x" + std::to_string(wanted.height) +
            " at (" + std::to_string(wanted.x) + ", " + std::to_string(wanted.y) + ")");
  return region_;
}

void AravisSource::note_trigger(int64_t frame_number, int64_t monotonic_ns) {
  numbering_.note_trigger(frame_number, monotonic_ns);
}

void AravisSource::set_exposure_us(double exposure_us) {
  GError* error = nullptr;
  arv_camera_set_exposure_time(camera_->camera.get(), exposure_us, &error);
  check(error, options_.device_address, "setting the exposure to " + std::to_string(exposure_us));
  options_.exposure_us = exposure_us;
}

void AravisSource::set_gain_db(double gain_db) {
  GError* error = nullptr;
  arv_camera_set_gain(camera_->camera.get(), gain_db, &error);
  check(error, options_.device_address, "setting the gain to " + std::to_string(gain_db));
  options_.gain_db = gain_db;
}

void AravisSource::software_trigger() {
  GError* error = nullptr;
  arv_camera_software_trigger(camera_->camera.get(), &error);
  check(error, options_.device_address, "software trigger");
}

Frame AravisSource::copy_frame(ArvBuffer* buffer) const {
  Frame frame;
  frame.camera_id = camera_id_;
  frame.monotonic_ns = monotonic_now_ns();
  frame.exposure_us = static_cast<int32_t>(options_.exposure_us);
  frame.origin = {arv_buffer_get_image_x(buffer), arv_buffer_get_image_y(buffer)};
  frame.sensor_size = sensor_size_;
  size_t size = 0;
  const void* data = arv_buffer_get_image_data(buffer, &size);
  const cv::Mat view(arv_buffer_get_image_height(buffer), arv_buffer_get_image_width(buffer),
                     CV_8UC1, const_cast<void*>(data));
  frame.image = view.clone();
  return frame;
}

std::optional<Frame> AravisSource::deliver(Frame frame, int64_t frame_number, bool& done) {
  done = frame.frame_number >= frame_number;
  if (!done) {
    ++stale_;  // an exposure whose trigger this process never saw
    return std::nullopt;
  }
  if (frame.frame_number == frame_number) return frame;
  read_ahead_.hold(std::move(frame));  // a later exposure came first: ours was lost
  return std::nullopt;
}

std::optional<Frame> AravisSource::grab_waiting(int64_t frame_number, bool& done) {
  done = false;
  if (!waiting_) return std::nullopt;
  const auto number =
      numbering_.number(waiting_->block_id, waiting_->camera_ns, waiting_->arrival_ns);
  if (number.kind == ExposureNumbering::Result::Kind::kWait) {
    done = true;
    return std::nullopt;
  }
  Unnumbered exposure = std::move(*waiting_);
  waiting_.reset();
  if (number.kind == ExposureNumbering::Result::Kind::kDrop) {
    ++stale_;
    return std::nullopt;
  }
  exposure.frame.frame_number = number.frame_number;
  return deliver(std::move(exposure.frame), frame_number, done);
}

std::optional<Frame> AravisSource::grab(int64_t frame_number) {
  if (camera_->control_lost) {
    throw FrameSourceError("camera " + options_.device_address +
                           ": control lost (no answer to the heartbeat)");
  }
  bool lost = false;
  if (auto held = read_ahead_.take(frame_number, lost, stale_)) return held;
  if (lost) return std::nullopt;
  bool done = false;
  if (auto frame = grab_waiting(frame_number, done); done) return frame;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options_.frame_timeout_ms);
  // The board's CLOCK_MONOTONIC minus Aravis' system timestamps (CLOCK_REALTIME at a frame's
  // first packet): when a reopened camera's first exposure arrived.
  const int64_t realtime_to_monotonic = monotonic_now_ns() - realtime_now_ns();
  for (auto now = std::chrono::steady_clock::now(); now < deadline;
       now = std::chrono::steady_clock::now()) {
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - now).count();
    ArvBuffer* buffer =
        arv_stream_timeout_pop_buffer(camera_->stream.get(), static_cast<guint64>(left));
    if (!buffer) break;
    const auto block_id = static_cast<uint16_t>(arv_buffer_get_frame_id(buffer));
    if (arv_buffer_get_status(buffer) != ARV_BUFFER_STATUS_SUCCESS) {
      arv_stream_push_buffer(camera_->stream.get(), buffer);
      ++incomplete_;
      // Once the stream is numbered, an incomplete exposure of this trigger or a later one ends
      // the wait: this trigger's frame is lost.
      if (numbering_.numbered() && numbering_.number(block_id, 0, 0).frame_number >= frame_number)
        return std::nullopt;
      continue;
    }
    const int64_t camera_ns = static_cast<int64_t>(arv_buffer_get_timestamp(buffer));
    const int64_t arrival_ns =
        static_cast<int64_t>(arv_buffer_get_system_timestamp(buffer)) + realtime_to_monotonic;
    const auto number = numbering_.number(block_id, camera_ns, arrival_ns);
    if (number.kind == ExposureNumbering::Result::Kind::kWait) {
      waiting_ = Unnumbered{copy_frame(buffer), block_id, camera_ns, arrival_ns};
      arv_stream_push_buffer(camera_->stream.get(), buffer);
      return std::nullopt;
    }
    const bool wanted = number.kind == ExposureNumbering::Result::Kind::kNumbered &&
                        number.frame_number >= frame_number;
    std::optional<Frame> frame;
    if (wanted) frame = copy_frame(buffer);  // the buffer goes back to the pool right after
    arv_stream_push_buffer(camera_->stream.get(), buffer);
    if (!wanted) {
      ++stale_;  // dropped, or an exposure whose trigger this process never saw
      continue;
    }
    frame->frame_number = number.frame_number;
    return deliver(std::move(*frame), frame_number, done);
  }
  return std::nullopt;
}

std::string AravisSource::describe() const {
  return "GigE Vision camera " + options_.device_address +
         (options_.trigger_source.empty() ? "" : ", trigger " + options_.trigger_source);
}

}  // namespace syncap::edge
