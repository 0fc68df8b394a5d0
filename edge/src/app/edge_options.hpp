// Command line and config file of syncap-edge.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "app/detection_stage.hpp"
#include "detection/blob_detector.hpp"
#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::edge {

struct EdgeOptions {
  int camera_id = 0;
  std::string source;          // "replay:FOLDER", "aravis:ADDRESS" or "v4l2:DEVICE"
  std::string trigger_source;  // aravis: camera TriggerSource; empty: as configured
  double exposure_us = 0;      // aravis: 0 = as configured
  double gain_db = -1;         // aravis: analog gain; < 0 = as configured
  bool udp_socket = false;     // aravis: plain UDP socket instead of a packet socket
  bool blobs = true;           // --mode blobs|mask|both
  bool mask = false;
  int train_frames = 0;           // mask: train on N frames (0: wait for the command) ...
  int64_t train_from_frame = -1;  // ... numbered from this one (-1: the first N frames)
  // mask: a recording of the empty scene (a video file or an image folder) to train on before
  // the first frame, N frames of it spread over it (--train-frames, default
  // kBackgroundClipFrames, sensor/background_clip.hpp); empty: train on the capture's own frames.
  std::string background;
  // The background model is computed on a thread of its own (not an option: tests turn it off to
  // see the model at once).
  bool train_in_background = true;
  double contour_tolerance_px = 0.5;  // 1 px costs ~1 % IoU on a 300 px tall person
  // mask: the medi-picture classification (--mask-* options change its defaults).
  segmentation::MediPictureOptions masking;
  // mask: the grey values where the person is (image_patch_t) every Nth frame, for the host's
  // surface matching; 0: none (the host's SET_PATCH_EVERY command changes it).
  int patch_every = 0;
  int patch_margin_px = 4;  // pixels beyond the silhouette sent with it
  cv::Rect roi;             // sensor region of interest at start; empty: the whole sensor
  std::string lcm_url;
  std::string command_key_path;  // the installation's key; empty: every command is refused
  double command_window_s = 5;   // a command sent longer ago (or ahead) than this is refused
  BlobDetectorConfig detector;
  DetectionMode detection = DetectionMode::kFull;  // --detection full|windowed
  int full_scan_every = 30;                        // windowed: frames between full scans
  bool roi_follows_windows = false;  // windowed: the sensor ROI follows the search windows
  double heartbeat_s = 1.0;
  int publish_queue = 64;          // messages waiting to be sent before the oldest is dropped
  double reopen_first_s = 0.5;     // camera lost: first wait before reopening, doubling ...
  double reopen_max_s = 10;        // ... up to this
  double camera_silent_s = 5;      // no frame for this long while triggered: camera lost
  double match_tolerance_ms = 10;  // v4l2: frame-to-trigger time tolerance
  bool exit_after_last = false;    // leave after the trigger's last pulse of a run
  bool quiet = false;
};

// A bad command line or config file; what() names the option (or file:line:column and key) and
// the value.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses argv[1..] with CLI11 (syncap/cli/options.hpp, as every program); throws UsageError.
// --help is reported as UsageError("help"). With `--config FILE` the file's keys (the long option
// names: `camera-id: 3`) are read first, each checked as its option is, and the other
// command-line options override them.
EdgeOptions parse_edge_options(const std::vector<std::string>& args);

// The --help text: every option with its value's name, unit and default; the config file; the
// exit statuses.
std::string edge_usage();

}  // namespace syncap::edge
