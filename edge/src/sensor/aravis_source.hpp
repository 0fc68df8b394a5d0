// A GigE Vision (or USB3 Vision) camera through Aravis, opened by address: never by discovery,
// which broadcasts on every interface.
//
// Frame numbers: sensor/exposure_numbering.hpp (block ids from the run's start; by time for a
// camera reopened mid-run).
//
// Region of interest: set_roi() stops the acquisition, sets OffsetX/Y and Width/Height, gives the
// stream buffers of the new payload size and starts again; the stream channel stays open, so
// block ids (and frame numbers) go on. Frames carry the region's origin and the sensor size.
//
// A camera that stops answering its heartbeat (Aravis' control-lost signal) makes grab() throw.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "sensor/exposure_numbering.hpp"
#include "sensor/frame_source.hpp"

struct _ArvBuffer;  // Aravis' buffer type, kept out of this header

namespace syncap::edge {

struct AravisOptions {
  std::string device_address;     // IPv4 address of the camera
  std::string interface_address;  // local address that reaches it; empty: from the routing table
  std::string trigger_source;     // "Line1", "Software", ...; empty: as the camera is configured
  double exposure_us = 0;         // 0: as configured
  double gain_db = -1;            // analog gain (GenICam Gain) [dB]; < 0: as configured
  int buffers = 16;               // buffer pool size
  int frame_timeout_ms = 1000;    // how long grab() waits for a frame
  // Receive with a plain UDP socket instead of Aravis' packet socket (which needs CAP_NET_RAW
  // and falls back to UDP without it). Aravis sizes a UDP socket's buffer only when the first
  // frame starts, so under load the first frame's burst can overflow the default buffer: the
  // replay bench lost frame 0 in 2 of 5 short runs that way, and none with packet sockets.
  bool udp_socket = false;
  // false: frame number = block id - 1 (acquiring before the trigger's first pulse). true: a
  // camera reopened mid-run, whose first exposure is numbered by time (ExposureNumbering).
  bool reopened = false;
  // How near the camera's timestamp must be to a trigger's time to be its exposure.
  int64_t trigger_tolerance_ns = 500'000;
};

class AravisSource : public FrameSource {
 public:
  // Opens the camera, sets Mono8, the trigger and exposure, starts acquisition. Throws
  // FrameSourceError naming the address when the camera does not answer or refuses a setting.
  AravisSource(const AravisOptions& options, int camera_id);
  ~AravisSource() override;
  AravisSource(const AravisSource&) = delete;
  AravisSource& operator=(const AravisSource&) = delete;

  // The exposure of `frame_number`: frames before it still queued are stale and dropped
  // (counted lost); a later frame arriving first means this one was lost, and is kept for the
  // next call. Incomplete buffers are counted and never returned.
  std::optional<Frame> grab(int64_t frame_number) override;
  void note_trigger(int64_t frame_number, int64_t monotonic_ns) override;
  std::string describe() const override;
  // Applies the region (empty: the whole sensor) as the camera rounds it; throws
  // FrameSourceError naming the camera when it refuses.
  cv::Rect set_roi(const cv::Rect& roi) override;

  // Exposure and gain while acquiring (GenICam ExposureTime, Gain); frames carry the new exposure.
  void set_exposure_us(double exposure_us) override;
  void set_gain_db(double gain_db) override;

  // For TriggerSource=Software: expose one frame now.
  void software_trigger();

  // Exposures dropped because their trigger was never asked for, and incomplete buffers.
  int64_t frames_stale() const { return stale_; }
  int64_t frames_incomplete() const override { return incomplete_; }

 private:
  struct Camera;  // Aravis objects
  // An exposure of a reopened camera that cannot be numbered yet (ExposureNumbering waits).
  struct Unnumbered {
    Frame frame;
    uint16_t block_id = 0;
    int64_t camera_ns = 0;
    int64_t arrival_ns = 0;
  };
  Frame copy_frame(::_ArvBuffer* buffer) const;
  void push_buffers();
  // A numbered exposure for the caller asking for `frame_number`: returned when it is that one,
  // held when later (`done` set for both), counted stale when earlier.
  std::optional<Frame> deliver(Frame frame, int64_t frame_number, bool& done);
  // The waiting exposure, once it can be numbered; `done` when the caller's grab is over.
  std::optional<Frame> grab_waiting(int64_t frame_number, bool& done);

  AravisOptions options_;
  int camera_id_;
  std::unique_ptr<Camera> camera_;
  ExposureNumbering numbering_;
  std::optional<Unnumbered> waiting_;  // the first exposure after a reopen, not yet numbered
  cv::Rect region_;                    // the sensor window frames come from
  cv::Size sensor_size_;
  ReadAheadFrame read_ahead_;  // a frame that arrived before its trigger was asked for
  int64_t stale_ = 0;
  int64_t incomplete_ = 0;
};

}  // namespace syncap::edge
