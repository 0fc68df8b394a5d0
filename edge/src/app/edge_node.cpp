#include "app/edge_node.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>

#include "detection/blob_detector.hpp"
#include "syncap/proto/blob_parts.hpp"
#include "syncap/proto/clock.hpp"
#include "syncap/proto/image_patch.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/image_sequence.hpp"

namespace syncap::edge {
namespace {

using proto::clock_now_ns;

const char* command_name(int8_t command) {
  switch (command) {
    case edge_command_t::START:
      return "START";
    case edge_command_t::STOP:
      return "STOP";
    case edge_command_t::SET_EXPOSURE:
      return "SET_EXPOSURE";
    case edge_command_t::SET_GAIN:
      return "SET_GAIN";
    case edge_command_t::SET_PATCH_EVERY:
      return "SET_PATCH_EVERY";
    case edge_command_t::SET_THRESHOLD:
      return "SET_THRESHOLD";
    case edge_command_t::SET_ROI:
      return "SET_ROI";
    case edge_command_t::TRAIN_BACKGROUND:
      return "TRAIN_BACKGROUND";
    case edge_command_t::SHUTDOWN:
      return "SHUTDOWN";
    default:
      return nullptr;
  }
}

// What a command asks, with the value it carries: "SET_THRESHOLD 40".
std::string command_text(const edge_command_t& c) {
  const char* name = command_name(c.command);
  if (name == nullptr) return "unknown command code " + std::to_string(c.command) + " (ignored)";
  std::string text = name;
  switch (c.command) {
    case edge_command_t::SET_THRESHOLD:
    case edge_command_t::TRAIN_BACKGROUND:
    case edge_command_t::SET_PATCH_EVERY:
      text += " " + std::to_string(c.int_value);
      break;
    case edge_command_t::SET_EXPOSURE:
    case edge_command_t::SET_GAIN:
      text += " " + std::to_string(c.real_value);
      break;
    case edge_command_t::SET_ROI:
      text += " " + std::to_string(c.roi_width) + "x" + std::to_string(c.roi_height) + " at (" +
              std::to_string(c.roi_x) + ", " + std::to_string(c.roi_y) + ")";
      break;
    default:
      break;
  }
  return text;
}

// UTC wall-clock time with microseconds, for the command log.
std::string utc_now() {
  const int64_t ns = clock_now_ns(CLOCK_REALTIME);
  const std::time_t seconds = static_cast<std::time_t>(ns / 1'000'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[40];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(text + n, sizeof text - n, ".%06lldZ",
                static_cast<long long>((ns % 1'000'000'000) / 1000));
  return text;
}

}  // namespace

EdgeNode::EdgeNode(const EdgeOptions& options, FrameSource& source, EdgePublisher publisher,
                   std::optional<proto::CommandKey> command_key)
    : options_(options),
      source_(source),
      publish_(std::move(publisher)),
      interval_start_ns_(clock_now_ns(CLOCK_MONOTONIC)),
      command_guard_(command_key, static_cast<int64_t>(options.command_window_s * 1e9),
                     clock_now_ns(CLOCK_REALTIME)),
      clip_guard_(command_key, static_cast<int64_t>(options.command_window_s * 1e9),
                  clock_now_ns(CLOCK_REALTIME)),
      detection_({options.detection, options.detector, options.full_scan_every,
                  options.roi_follows_windows}) {
  if (options_.mask) {
    silhouettes_.emplace(options_.contour_tolerance_px, options_.masking,
                         options_.train_in_background);
    if (!options_.background.empty()) {
      const int frames =
          options_.train_frames > 0 ? options_.train_frames : segmentation::kBackgroundClipFrames;
      try {
        silhouettes_->train_on(
            segmentation::read_background_clip(options_.background, frames, options_.roi));
      } catch (const segmentation::ImageSequenceError& e) {  // as the edge's sources name theirs
        throw FrameSourceError(e.what());
      }
    } else if (options_.train_frames > 0) {
      silhouettes_->start_training(options_.train_frames, options_.train_from_frame);
    }
  }
  if (!options_.roi.empty()) source_.set_roi(options_.roi);
}

template <class Message>
bool EdgeNode::admit(const Message& message, proto::CommandGuard& guard, const std::string& what) {
  const proto::CommandCheck check = guard.check(message, clock_now_ns(CLOCK_REALTIME));
  const bool accepted = check == proto::CommandCheck::kAccepted;
  last_command_sender_ = message.sender;
  last_command_sequence_ = message.sequence;
  last_command_result_ = static_cast<int8_t>(check);
  // Every command is logged, also with --quiet; refusals only the first ten and then one in a
  // thousand, so that a flood of forgeries cannot fill the journal (the heartbeat counts them).
  const int64_t count = accepted ? ++commands_accepted_ : ++commands_rejected_;
  if (accepted || count <= 10 || count % 1000 == 0) {
    std::cerr << "syncap-edge camera " << options_.camera_id << ": " << what << " (sender "
              << message.sender << ", sequence " << message.sequence << ") at " << utc_now() << ": "
              << proto::describe(check);
    if (!accepted) std::cerr << " [" << count << " refused so far]";
    std::cerr << std::endl;
  }
  return accepted;
}

bool EdgeNode::on_command(const edge_command_t& c) {
  if (c.camera_id != edge_command_t::ALL_CAMERAS && c.camera_id != options_.camera_id) return false;
  const std::string what =
      "command " + command_text(c) +
      (c.camera_id == edge_command_t::ALL_CAMERAS ? " to all cameras" : " to this camera");
  if (!admit(c, command_guard_, what)) return false;
  const bool shutdown = obey(c);
  // The sender's acknowledgement (syncap ctl); SHUTDOWN's is the final status.
  if (!shutdown) publish_status();
  return shutdown;
}

bool EdgeNode::obey(const edge_command_t& c) {
  switch (c.command) {
    case edge_command_t::SHUTDOWN:
      return true;
    case edge_command_t::START:
    case edge_command_t::STOP:
      acquiring_ = c.command == edge_command_t::START;
      break;
    case edge_command_t::SET_EXPOSURE:
    case edge_command_t::SET_GAIN:
      set_camera_control(c);
      break;
    case edge_command_t::TRAIN_BACKGROUND:
      if (silhouettes_ && c.int_value > 0)
        silhouettes_->start_training(static_cast<int>(c.int_value));
      break;
    case edge_command_t::SET_PATCH_EVERY:
      if (c.int_value >= 0 && c.int_value <= 100000 && silhouettes_) {
        options_.patch_every = static_cast<int>(c.int_value);
      } else {
        note_error("SET_PATCH_EVERY " + std::to_string(c.int_value) + " refused: " +
                   (silhouettes_ ? "outside 0..100000" : "no silhouettes (--mode blobs)"));
      }
      break;
    case edge_command_t::SET_THRESHOLD:
      if (c.int_value >= 0 && c.int_value <= 255) {
        options_.detector.threshold = static_cast<int>(c.int_value);
        detection_.set_threshold(options_.detector.threshold);
      }
      break;
    case edge_command_t::SET_ROI: {
      const cv::Rect roi(c.roi_x, c.roi_y, c.roi_width, c.roi_height);
      try {
        const cv::Rect applied =
            source_.set_roi(roi.width > 0 && roi.height > 0 ? roi : cv::Rect());
        if (!options_.quiet) {
          std::cerr << "syncap-edge camera " << options_.camera_id << ": region of interest "
                    << (applied.empty()
                            ? "the whole sensor"
                            : std::to_string(applied.width) + "x" + std::to_string(applied.height) +
                                  " at (" + std::to_string(applied.x) + ", " +
                                  std::to_string(applied.y) + ")")
                    << "\n";
        }
      } catch (const FrameSourceError& e) {
        note_error(std::string("SET_ROI refused: ") + e.what());
      }
      break;
    }
    default:
      break;
  }
  return false;
}

void EdgeNode::set_camera_control(const edge_command_t& c) {
  const bool exposure = c.command == edge_command_t::SET_EXPOSURE;
  const std::string what = exposure ? "SET_EXPOSURE " : "SET_GAIN ";
  if (!std::isfinite(c.real_value) || (exposure ? c.real_value <= 0 : c.real_value < 0)) {
    note_error(what + "refused: " + std::to_string(c.real_value) + " is out of range");
    return;
  }
  try {
    if (exposure) {
      source_.set_exposure_us(c.real_value);
    } else {
      source_.set_gain_db(c.real_value);
    }
  } catch (const FrameSourceError& e) {
    note_error(what + "refused: " + e.what());
  }
}

void EdgeNode::on_trigger(const trigger_t& trigger) {
  if (trigger.flags & trigger_t::FLAG_LAST) saw_last_pulse_ = true;
  // Stopped by the host: the pulses' exposures are left to the camera and counted nowhere.
  if (!acquiring_) return;
  source_.note_trigger(trigger.frame_number, trigger.monotonic_ns);
  std::optional<Frame> frame;
  try {
    frame = source_.grab(trigger.frame_number);
  } catch (const FrameSourceError& e) {
    note_error(e.what());
  }
  if (!frame) {
    ++frames_lost_;
    if (last_error_.empty()) {
      const std::string problem = source_.problem();
      note_error(problem.empty() ? "no exposure for frame " + std::to_string(trigger.frame_number) +
                                       " in " + source_.describe()
                                 : problem);
    }
    return;
  }
  const int64_t start_ns = clock_now_ns(CLOCK_MONOTONIC);  // processing only, not the wait
  const cv::Size sensor = frame->full_size();
  blob_frame_t out{};
  out.camera_id = static_cast<int16_t>(options_.camera_id);
  out.frame_number = trigger.frame_number;
  out.monotonic_ns = frame->monotonic_ns;
  out.exposure_us = frame->exposure_us;
  out.image_width = static_cast<int16_t>(sensor.width);
  out.image_height = static_cast<int16_t>(sensor.height);
  if (options_.blobs) {
    out.blobs = detection_.process(*frame);
    follow_windows(sensor);
  }
  std::vector<silhouette_part_t> silhouette;
  if (silhouettes_) {
    silhouette = silhouettes_->process(frame->image, options_.camera_id, trigger.frame_number,
                                       frame->origin, frame->sensor_size);
  }
  const std::vector<image_patch_t> patch = patch_of(*frame, trigger.frame_number);
  const int64_t done_ns = clock_now_ns(CLOCK_MONOTONIC);
  out.processing_us = static_cast<int32_t>((done_ns - start_ns) / 1000);
  // The blob frame is the frame's record, sent in every mode (no blobs in mask-only mode): it
  // tells the host how many silhouette parts to wait for.
  if (!publish_.silhouette) silhouette.clear();
  out.silhouette_parts = static_cast<int16_t>(silhouette.size());
  // The patch goes first: its parts are in the host before the record that completes the frame.
  for (const image_patch_t& part : patch) publish_.patch(part);
  if (!patch.empty()) ++patches_sent_;
  for (const blob_frame_t& part : proto::split_blob_frame(out)) publish_.blobs(part);
  for (const silhouette_part_t& part : silhouette) publish_.silhouette(part);

  ++frames_received_;
  ++interval_frames_;
  interval_processing_us_ += out.processing_us;
  last_frame_number_ = trigger.frame_number;
}

std::vector<image_patch_t> EdgeNode::patch_of(const Frame& frame, int64_t frame_number) {
  if (!silhouettes_ || !publish_.patch || options_.patch_every <= 0 ||
      frame_number % options_.patch_every != 0 || silhouettes_->last_mask().empty())
    return {};
  cv::Mat grey = frame.image;
  if (grey.type() != CV_8UC1) frame.image.convertTo(grey, CV_8U);  // one channel: the sources'
  try {
    proto::PatchEncoding encoding;
    encoding.margin_px = options_.patch_margin_px;
    return proto::encode_image_patch(options_.camera_id, frame_number, grey,
                                     silhouettes_->last_mask(), frame.origin, frame.sensor_size,
                                     encoding);
  } catch (const std::exception& e) {  // a mask of another size, an encoder failure
    note_error(std::string("image patch not sent: ") + e.what());
    return {};
  }
}

void EdgeNode::on_clip(const clip_polygon_t& clip) {
  if (clip.camera_id != options_.camera_id) return;
  if (!admit(clip, clip_guard_, "clip polygon of " + std::to_string(clip.num_points) + " points"))
    return;
  const auto points = static_cast<std::size_t>(std::max<int16_t>(clip.num_points, 0));
  if ((clip.num_points != 0 && clip.num_points < 3) || clip.x.size() != points ||
      clip.y.size() != points || clip.image_width <= 0 || clip.image_height <= 0) {
    note_error("clip polygon " + std::to_string(clip.sequence) +
               " refused: " + std::to_string(clip.num_points) + " points for a " +
               std::to_string(clip.image_width) + "x" + std::to_string(clip.image_height) +
               " sensor (0, or at least 3, and a sensor size)");
    return;
  }
  if (clip.region < clip_polygon_t::REGION_CLIP || clip.region > clip_polygon_t::REGION_SEARCH ||
      (clip.region == clip_polygon_t::REGION_SEARCH && clip.num_points > 0 &&
       clip.valid_frames < 1)) {
    note_error("clip polygon " + std::to_string(clip.sequence) + " refused: region " +
               std::to_string(clip.region) + " with valid_frames " +
               std::to_string(clip.valid_frames) +
               " (0 clip, 1 floor, 2 search with valid_frames >= 1)");
    return;
  }
  if (!silhouettes_) return;  // blobs only: nothing to clip
  std::vector<cv::Point> polygon;
  for (std::size_t i = 0; i < points; ++i) polygon.emplace_back(clip.x[i], clip.y[i]);
  silhouettes_->set_region(static_cast<SilhouetteStage::Region>(clip.region), std::move(polygon),
                           {clip.image_width, clip.image_height}, clip.frame_number,
                           clip.valid_frames);
}

void EdgeNode::follow_windows(cv::Size sensor) {
  const std::optional<cv::Rect> wanted = detection_.next_roi();
  if (!wanted) return;
  // Reprogramming the sensor costs the camera a restart of its acquisition: only when the
  // windows leave the current region, or it has become far larger than they need.
  const bool whole = wanted->empty();
  const bool inside = !whole && !sensor_roi_.empty() && (*wanted & sensor_roi_) == *wanted;
  const bool far_larger = inside && sensor_roi_.area() > 4 * wanted->area();
  if (whole ? sensor_roi_.empty() : (inside && !far_larger)) return;
  // Some slack around the windows, so that the next small moves stay inside.
  const cv::Rect slack(wanted->tl() - cv::Point(16, 16), wanted->size() + cv::Size(32, 32));
  const cv::Rect request = whole ? cv::Rect() : slack & cv::Rect({0, 0}, sensor);
  try {
    sensor_roi_ = source_.set_roi(request);
  } catch (const FrameSourceError& e) {
    note_error(std::string("region of interest refused: ") + e.what());
  }
}

void EdgeNode::publish_status(bool final) {
  const int64_t now = clock_now_ns(CLOCK_MONOTONIC);
  camera_status_t s{};
  s.camera_id = static_cast<int16_t>(options_.camera_id);
  const std::string problem = source_.problem();
  if (!problem.empty()) last_error_ = problem;  // the source's state outranks a lost frame
  s.state = final                  ? camera_status_t::STATE_STOPPED
            : !last_error_.empty() ? camera_status_t::STATE_ERROR
            : acquiring_           ? camera_status_t::STATE_ACQUIRING
                                   : camera_status_t::STATE_IDLE;
  s.monotonic_ns = now;
  s.realtime_ns = clock_now_ns(CLOCK_REALTIME);
  s.last_frame_number = last_frame_number_;
  s.frames_received = frames_received_;
  s.frames_lost = frames_lost_;
  s.frames_incomplete = source_.frames_incomplete();
  const double interval_s = static_cast<double>(now - interval_start_ns_) * 1e-9;
  s.frame_rate_hz = interval_s > 0 ? static_cast<float>(interval_frames_ / interval_s) : 0.0f;
  s.processing_us_mean =
      interval_frames_ > 0 ? static_cast<float>(interval_processing_us_ / interval_frames_) : 0.0f;
  std::string note = last_error_.empty() ? source_.note() : last_error_;
  if (silhouettes_ && note.empty()) note = silhouettes_->state();
  if (publish_.queue) {
    // camera_status_t has no fields for the publishing queue: its state goes in the text, last
    // so that a long error cuts nothing else.
    const PublishQueueStats q = publish_.queue();
    const std::string queue = "queue " + std::to_string(q.depth) + "/" +
                              std::to_string(q.capacity) + ", " + std::to_string(q.dropped) +
                              " dropped";
    const std::size_t room = camera_status_t::MAX_MESSAGE - queue.size() - 2;
    note = note.empty() ? queue : note.substr(0, room) + "; " + queue;
  }
  s.message = note.substr(0, camera_status_t::MAX_MESSAGE);
  s.commands_accepted = static_cast<int32_t>(std::min<int64_t>(commands_accepted_, INT32_MAX));
  s.commands_rejected = static_cast<int32_t>(std::min<int64_t>(commands_rejected_, INT32_MAX));
  s.last_command_sender = last_command_sender_;
  s.last_command_sequence = last_command_sequence_;
  s.last_command_result = last_command_result_;
  if (publish_.status) publish_.status(s);
  interval_frames_ = 0;
  interval_processing_us_ = 0;
  interval_start_ns_ = now;
  last_error_.clear();
}

void EdgeNode::note_error(const std::string& message) {
  last_error_ = message;
  if (!options_.quiet)
    std::cerr << "syncap-edge camera " << options_.camera_id << ": " << message << "\n";
}

}  // namespace syncap::edge
