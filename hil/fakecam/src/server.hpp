// The frame loop of syncap-fakecam: a trigger thread turns rising edges of a shared GPIO line or
// TriggerSoftware commands into numbered triggers; a sender thread turns each trigger into a
// frame (the image with the trigger's frame number, cropped to the region of interest, after the
// delay, unless dropped) and sends it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "fake_camera.hpp"
#include "image_set.hpp"
#include "options.hpp"
#include "syncap/trigger/gpiosim.h"

namespace syncap::fakecam {

struct Trigger {
  std::uint64_t frame = 0;
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC: the rising edge, or when TriggerSoftware was seen
};

struct ServerStats {
  std::uint64_t triggers = 0;  // rising edges / TriggerSoftware commands seen
  std::uint64_t sent = 0;      // frames sent
  std::uint64_t dropped = 0;   // left out by --drop
  std::uint64_t idle = 0;      // triggers while the client was not acquiring: no frame
  std::uint64_t no_image = 0;  // frame numbers the image set has no image for
  std::uint64_t missed = 0;    // rising edges that went by unseen (watcher too far behind)
  std::uint64_t errors = 0;    // frames that could not be sent or read
};

// The image cropped to the region; pixels outside the image are black.
cv::Mat crop_to_region(const cv::Mat& image, const Region& region);

class Server {
 public:
  // Opens the shared chip for a gpiosim trigger (creating it when missing) and takes the line's
  // state now as the starting point: the edges after this are the camera's. Throws
  // std::runtime_error naming the chip when it cannot.
  Server(const Options& options, const ImageSet& images, FakeCamera& camera);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  void start();
  // Stops both threads; frames waiting for their delay are not sent. Idempotent.
  void stop();

  // Set when a thread hit an error it cannot go on after.
  std::optional<std::string> failure() const;
  ServerStats stats() const;

 private:
  void watch_gpiosim(std::stop_token stop);
  void poll_software_trigger(std::stop_token stop);
  void on_edge(const syncap_gpiosim_rise& rise);
  // Queues the trigger's frame; false (and counted idle) when the client is not acquiring.
  bool deliver(Trigger trigger);
  void send_frames(std::stop_token stop);
  std::optional<cv::Mat> image_of(std::uint64_t frame);
  void send_frame(const Trigger& trigger);
  std::optional<Trigger> next_trigger(std::stop_token stop);
  void fail(std::string why);

  const Options& options_;
  const ImageSet& images_;
  FakeCamera& camera_;
  syncap_gpiosim* chip_ = nullptr;

  mutable std::mutex mutex_;
  std::condition_variable_any queued_;
  std::deque<Trigger> queue_;
  std::optional<std::string> failure_;

  syncap_gpiosim_rise last_rise_{};   // gpiosim: the last edge seen, where waiting goes on
  std::uint64_t run_ = 0;             // gpiosim: the line's run being followed
  std::uint64_t expected_count_ = 1;  // gpiosim: the next edge count expected in it
  std::uint64_t software_triggers_ = 0;
  std::atomic<std::uint64_t> no_image_warnings_ = 0;

  struct AtomicStats {
    std::atomic<std::uint64_t> triggers = 0, sent = 0, dropped = 0, idle = 0, no_image = 0,
                               missed = 0, errors = 0;
  } stats_;

  std::jthread trigger_thread_;
  std::jthread sender_thread_;
};

}  // namespace syncap::fakecam
