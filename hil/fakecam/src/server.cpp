#include "server.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "syncap/fakecam/frame_number.hpp"
#include "syncap/proto/clock.hpp"
#include "syncap/trigger/gpiosim.h"

namespace syncap::fakecam {
namespace {

constexpr std::int64_t kNsPerMs = 1'000'000;
constexpr std::int64_t kWatchSliceNs = 50 * kNsPerMs;  // how often the watcher checks for stop
constexpr auto kSoftwarePollInterval = std::chrono::microseconds(500);
constexpr auto kStopCheckInterval = std::chrono::milliseconds(20);
constexpr std::uint64_t kMaxNoImageWarnings = 3;

std::int64_t monotonic_ns() { return proto::monotonic_now_ns(); }

// Sleeps until deadline_ns (CLOCK_MONOTONIC); false when a stop came first.
bool sleep_until(std::int64_t deadline_ns, const std::stop_token& stop) {
  const std::int64_t slice_ns = std::chrono::nanoseconds(kStopCheckInterval).count();
  for (std::int64_t now_ns = monotonic_ns(); now_ns < deadline_ns; now_ns = monotonic_ns()) {
    if (stop.stop_requested()) return false;
    const std::int64_t wake_ns = std::min(deadline_ns, now_ns + slice_ns);
    const timespec wake{static_cast<time_t>(wake_ns / 1'000'000'000),
                        static_cast<long>(wake_ns % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);
  }
  return !stop.stop_requested();
}

}  // namespace

cv::Mat crop_to_region(const cv::Mat& image, const Region& region) {
  cv::Mat out(static_cast<int>(region.height), static_cast<int>(region.width), CV_8UC1,
              cv::Scalar(0));
  const cv::Rect wanted(static_cast<int>(region.x), static_cast<int>(region.y),
                        static_cast<int>(region.width), static_cast<int>(region.height));
  const cv::Rect inside = wanted & cv::Rect(0, 0, image.cols, image.rows);
  if (inside.area() > 0) {
    image(inside).copyTo(out(inside - wanted.tl()));
  }
  return out;
}

namespace {

// The shared chip of a gpiosim trigger, created when missing; throws naming it.
syncap_gpiosim* open_chip(const TriggerSpec& trigger) {
  syncap_gpiosim* chip = syncap_gpiosim_open(trigger.chip.c_str(), true);
  if (chip == nullptr) {
    char why[256];
    throw std::runtime_error(
        syncap_gpiosim_describe_error(trigger.chip.c_str(), errno, why, sizeof why));
  }
  return chip;
}

}  // namespace

Server::Server(const Options& options, const ImageSet& images, FakeCamera& camera)
    : options_(options), images_(images), camera_(camera) {
  if (options.trigger.kind != TriggerSpec::Kind::gpiosim) return;
  chip_ = open_chip(options.trigger);
  syncap_gpiosim_line line{};
  if (syncap_gpiosim_read_line(chip_, options.trigger.line, &line) < 0) {
    syncap_gpiosim_close(chip_);
    throw std::runtime_error("reading shared GPIO chip '" + options.trigger.chip + "' failed");
  }
  // Edges up to now are not this camera's frames.
  last_rise_ = {line.run, line.count, line.last_rise_ns};
  run_ = line.run;
  expected_count_ = line.count + 1;
}

Server::~Server() {
  stop();
  syncap_gpiosim_close(chip_);
}

void Server::start() {
  if (chip_ != nullptr) {
    trigger_thread_ = std::jthread([this](std::stop_token stop) { watch_gpiosim(stop); });
  } else {
    trigger_thread_ = std::jthread([this](std::stop_token stop) { poll_software_trigger(stop); });
  }
  sender_thread_ = std::jthread([this](std::stop_token stop) { send_frames(stop); });
}

void Server::stop() {
  trigger_thread_.request_stop();
  sender_thread_.request_stop();
  if (trigger_thread_.joinable()) trigger_thread_.join();
  if (sender_thread_.joinable()) sender_thread_.join();
}

std::optional<std::string> Server::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

ServerStats Server::stats() const {
  return {stats_.triggers, stats_.sent,   stats_.dropped, stats_.idle,
          stats_.no_image, stats_.missed, stats_.errors};
}

void Server::fail(std::string why) {
  std::lock_guard lock(mutex_);
  if (!failure_) failure_ = std::move(why);
}

// Goes on from the line's state when the server was made: edges before are not its frames, every
// edge after is, even one that comes before this thread runs.
void Server::watch_gpiosim(std::stop_token stop) {
  while (!stop.stop_requested()) {
    if (syncap_gpiosim_wait_rising(chip_, options_.trigger.line, kWatchSliceNs, &last_rise_) == 0) {
      on_edge(last_rise_);
    } else if (errno != ETIMEDOUT) {
      fail("waiting for an edge on the shared GPIO chip failed");
      return;
    }
  }
}

// Rising edge `count` of the writer's run is frame start_frame + count - 1; with start frame 0
// that is syncap-trigger's frame number, the index of its pulse.
void Server::on_edge(const syncap_gpiosim_rise& rise) {
  if (rise.run != run_) {
    run_ = rise.run;
    expected_count_ = 1;
  }
  if (rise.count > expected_count_) stats_.missed += rise.count - expected_count_;
  expected_count_ = rise.count + 1;
  deliver({options_.start_frame + rise.count - 1, rise.time_ns});
}

void Server::poll_software_trigger(std::stop_token stop) {
  while (!stop.stop_requested()) {
    if (camera_.take_software_trigger()) {
      // Triggers while not acquiring are ignored, as by a real camera, and take no frame number.
      if (deliver({options_.start_frame + software_triggers_, monotonic_ns()})) {
        ++software_triggers_;
      }
    }
    std::this_thread::sleep_for(kSoftwarePollInterval);
  }
}

bool Server::deliver(Trigger trigger) {
  ++stats_.triggers;
  if (!camera_.is_acquiring()) {
    ++stats_.idle;
    return false;
  }
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(trigger);
  }
  queued_.notify_one();
  return true;
}

std::optional<Trigger> Server::next_trigger(std::stop_token stop) {
  std::unique_lock lock(mutex_);
  if (!queued_.wait(lock, stop, [this] { return !queue_.empty(); })) return std::nullopt;
  const Trigger trigger = queue_.front();
  queue_.pop_front();
  return trigger;
}

void Server::send_frames(std::stop_token stop) {
  while (const auto trigger = next_trigger(stop)) {
    if (!sleep_until(trigger->time_ns + options_.delay_ms * kNsPerMs, stop)) return;
    send_frame(*trigger);
  }
}

// The frame's image; nothing, counted and reported, when the set has none or it cannot be read.
std::optional<cv::Mat> Server::image_of(std::uint64_t frame) {
  try {
    const std::uint64_t first = images_.first_frame();
    const std::uint64_t span = images_.last_frame() - first + 1;
    const bool looped = options_.loop && frame >= first;
    auto image = images_.image(looped ? first + (frame - first) % span : frame);
    if (image) return image;
  } catch (const ImageSetError& error) {
    std::fprintf(stderr, "syncap-fakecam: %s\n", error.what());
    ++stats_.errors;
    return std::nullopt;
  }
  if (no_image_warnings_++ < kMaxNoImageWarnings) {
    std::fprintf(stderr, "syncap-fakecam: warning: no image for frame %llu in %s; not sent\n",
                 static_cast<unsigned long long>(frame), images_.directory().c_str());
  }
  ++stats_.no_image;
  return std::nullopt;
}

// The image of the trigger's frame, cropped to the client's region, stamped with the frame's
// block id and the trigger's time (docs/design/fakecam.md, "Frame numbers").
void Server::send_frame(const Trigger& trigger) {
  if (options_.drop.drops(trigger.frame)) {
    ++stats_.dropped;
    return;
  }
  const auto image = image_of(trigger.frame);
  if (!image) return;
  const Region region = camera_.region();
  const cv::Mat pixels = crop_to_region(*image, region);
  const GvspImage frame{.block_id = block_id_of(trigger.frame),
                        .timestamp = static_cast<std::uint64_t>(trigger.time_ns),
                        .pixel_format = kPixelFormatMono8,
                        .width = region.width,
                        .height = region.height,
                        .offset_x = region.x,
                        .offset_y = region.y,
                        .pixels = {pixels.data, pixels.total()}};
  if (camera_.send_frame(frame)) {
    ++stats_.sent;
  } else {
    ++stats_.errors;
  }
}

}  // namespace syncap::fakecam
