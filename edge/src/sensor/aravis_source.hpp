// A GigE Vision (or USB3 Vision) camera through Aravis, opened by address: never by discovery,
// which broadcasts on every interface.
//
// Frame numbers: GigE Vision numbers the exposures of an acquisition with 16-bit block ids that
// wrap from 65535 to 1. The source unwraps them into a 64-bit count, and frame number =
// unwrapped block id - 1, so the first exposure of an acquisition (block id 1) is frame 0: the
// trigger's first pulse of a run, provided the camera is acquiring before the run starts. The
// replay bench's fake cameras send block id = frame number mod 65535 + 1 (docs/fakecam.md),
// which the same rule turns back into the frame number. A camera reopened mid-run (after it
// vanished) restarts its block ids: `first_frame_number` then numbers its first exposure, and the
// block ids count on from there.
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
  // -1: frame number = block id - 1 (acquiring before the trigger's first pulse). Otherwise the
  // number of the first exposure received (a camera reopened mid-run).
  int64_t first_frame_number = -1;
};

// Unwraps GigE Vision block ids (1..65535, then 1 again) into a running 64-bit count.
class BlockIdUnwrapper {
 public:
  uint64_t next(uint16_t block_id);

 private:
  std::optional<uint16_t> last_;
  uint64_t count_ = 0;
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
  Frame copy_frame(::_ArvBuffer* buffer, int64_t number) const;
  void push_buffers();
  int64_t frame_number_of(uint16_t block_id);

  AravisOptions options_;
  int camera_id_;
  std::unique_ptr<Camera> camera_;
  BlockIdUnwrapper block_ids_;
  std::optional<int64_t> number_offset_;  // frame number - unwrapped block id
  cv::Rect region_;                       // the sensor window frames come from
  cv::Size sensor_size_;
  ReadAheadFrame read_ahead_;  // a frame that arrived before its trigger was asked for
  int64_t stale_ = 0;
  int64_t incomplete_ = 0;
};

}  // namespace syncap::edge
