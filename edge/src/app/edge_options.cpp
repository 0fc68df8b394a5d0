#include "app/edge_options.hpp"

#include <memory>

#include <charconv>
#include <optional>

#include "syncap/cli/config_file.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/mask_options.hpp"
#include "syncap/segmentation/masking_options.hpp"

namespace syncap::edge {
namespace {

constexpr const char* kAbout =
    "usage: syncap-edge --camera-id N --source SPEC [options]\n"
    "       syncap-edge --config FILE [options]\n"
    "Grabs the exposure of every trigger pulse, finds the bright targets (and with --mode mask\n"
    "the person's silhouette) and publishes them over LCM; obeys the host's signed commands.\n";

constexpr const char* kFooter =
    "Config file: YAML `key: value` lines, the keys the long options without dashes\n"
    "(camera-id: 3, quiet: true); options on the command line override it, before or after\n"
    "--config. Exit status: 0 after a run, 1 a failure while running, 2 a usage error or a bad\n"
    "config file (the option or file:line:column and key named, with the value).";

// " (default V)": a number's default as the help shows it, from the options' own defaults.
std::string by_default(double v) { return " (default " + cli::number_text(v) + ")"; }

constexpr const char* kRoiForm = "X,Y,WIDTH,HEIGHT in sensor pixels, each 0..32767";

// "X,Y,W,H", each a decimal 0..32767; nothing for any other text.
std::optional<cv::Rect> parse_roi(const std::string& text) {
  int v[4];
  const char* at = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0 && (at == end || *at++ != ',')) return std::nullopt;
    const auto [next, ec] = std::from_chars(at, end, v[i]);
    if (ec != std::errc() || v[i] < 0 || v[i] > 32767) return std::nullopt;
    at = next;
  }
  if (at != end) return std::nullopt;
  return cv::Rect(v[0], v[1], v[2], v[3]);
}

CLI::Validator roi_form() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return parse_roi(text) ? std::string() : "'" + text + "' is not " + kRoiForm;
      },
      kRoiForm);
}

// The parser of one EdgeOptions: every option bound to `o`. A parse sets only the options it is
// given, so parsing the config file's entries and then the command line into the same parser
// lets the command line override the file.
class Parser {
 public:
  Parser() : app_(std::make_unique<cli::App>("syncap-edge", kAbout, kFooter)) {
    o.lcm_url = proto::kDefaultLcmUrl;
    add_camera_options();
    add_detection_options();
    add_mask_options();
    add_network_options();
    add_run_options();
  }

  EdgeOptions o;
  std::string config;        // --config FILE
  bool have_camera = false;  // --camera-id given, on the command line or in the file

  // Throws UsageError: "help", or the problem naming the option and the value.
  void parse_command_line(const std::vector<std::string>& args) {
    if (const auto stop = cli::try_parse(*app_, args)) {
      throw UsageError(stop->help ? std::string("help") : "syncap-edge: " + stop->error);
    }
    have_camera = have_camera || app_->count("--camera-id") > 0;
  }

  std::string help() const { return app_->help(); }
  // The parser itself, for a caller that only needs the options bound (the config file's
  // checks); this Parser must outlive it.
  std::unique_ptr<CLI::App> release_app() { return std::move(app_); }

 private:
  void add_camera_options();
  void add_detection_options();
  void add_mask_options();
  void add_network_options();
  void add_run_options();

  std::unique_ptr<cli::App> app_;
};

void Parser::add_camera_options() {
  app_->add_option("--config", config,
                   "YAML file of `option: value` lines (below); the command line overrides it")
      ->option_text("FILE");
  cli::add_checked(*app_, "--camera-id", o.camera_id, "N",
                   cli::whole_in<int>(0, proto::kMaxCameraId),
                   "camera id 0..99 (channels SYNCAP_BLOBS_NN ...); required");
  app_->add_option(
          "--source", o.source,
          "replay:FOLDER  numbered 8-bit images, frame k = file number k\n"
          "replay:VIDEO   a video file, frame k = its k-th frame (from 0)\n"
          "aravis:ADDRESS GigE Vision camera at this IPv4 address\n"
          "v4l2:DEVICE    UVC camera, e.g. v4l2:/dev/video0 (docs/design/v4l2.md); required")
      ->option_text("SPEC");
  app_->add_option("--trigger-source", o.trigger_source,
                   "aravis: the camera's TriggerSource (Line1, Software, ...);\n"
                   "default: as the camera is configured")
      ->option_text("S");
  cli::add_checked(*app_, "--exposure-us", o.exposure_us, "US", cli::whole_in<int>(1, 10'000'000),
                   "aravis: exposure time, us 1..10000000; default: as configured");
  cli::add_checked(*app_, "--gain-db", o.gain_db, "DB", cli::number_in(0, 100),
                   "aravis: analog gain (Gain), dB 0..100; default: as configured");
  app_->add_flag("--udp-socket", o.udp_socket,
                 "aravis: receive with a UDP socket, not a packet socket (no\n"
                 "CAP_NET_RAW needed; its buffer grows only after the first frame)");
  app_->add_option_function<std::string>(
          "--roi", [this](const std::string& v) { o.roi = *parse_roi(v); },
          "sensor region of interest at start (blobs stay in sensor\n"
          "pixels); default: the whole sensor")
      ->option_text("X,Y,W,H")
      ->check(roi_form());
  cli::add_checked(*app_, "--camera-silent-s", o.camera_silent_s, "S", cli::number_in(0, 3600),
                   "aravis, v4l2: no frame for S s while triggered = camera lost\n"
                   "(0: only errors count)" +
                       by_default(o.camera_silent_s));
  cli::add_checked(*app_, "--reopen-first-s", o.reopen_first_s, "S", cli::number_in(0.01, 3600),
                   "a lost camera is reopened after S s, doubling up to --reopen-max-s" +
                       by_default(o.reopen_first_s));
  cli::add_checked(*app_, "--reopen-max-s", o.reopen_max_s, "S", cli::number_in(0.01, 3600),
                   "the longest wait between reopening attempts, s" + by_default(o.reopen_max_s));
  cli::add_checked(*app_, "--match-tolerance-ms", o.match_tolerance_ms, "MS",
                   cli::number_in(0.001, 10000),
                   "v4l2: a frame takes the number of the trigger closest in\n"
                   "time within MS ms" +
                       by_default(o.match_tolerance_ms));
}

void Parser::add_detection_options() {
  app_->add_option_function<std::string>(
          "--detection",
          [this](const std::string& v) {
            o.detection = v == "full" ? DetectionMode::kFull : DetectionMode::kWindowed;
          },
          "full (default): every frame whole; windowed: tracked blobs\n"
          "searched around their prediction (docs/design/edge.md)")
      ->option_text("D")
      ->check(cli::one_of({"full", "windowed"}));
  cli::add_checked(
      *app_, "--full-scan-every", o.full_scan_every, "N", cli::whole_in<int>(1, 100000),
      "windowed: a full scan for new blobs every N frames" + by_default(o.full_scan_every));
  app_->add_flag("--roi-follows-windows", o.roi_follows_windows,
                 "windowed: the sensor ROI follows the union of the windows");
  cli::add_checked(*app_, "--threshold-dn", o.detector.threshold, "DN", cli::whole_in<int>(1, 255),
                   "blob threshold, DN 1..255" + by_default(o.detector.threshold));
  cli::add_checked(*app_, "--min-area-px", o.detector.min_area, "PX",
                   cli::whole_in<int>(1, 1 << 24),
                   "smallest blob area, pixels" + by_default(o.detector.min_area));
  cli::add_checked(*app_, "--max-area-px", o.detector.max_area, "PX",
                   cli::whole_in<int>(1, 1 << 24),
                   "largest blob area, pixels" + by_default(o.detector.max_area));
  app_->deprecated_name("--threshold", "--threshold-dn");
  app_->deprecated_name("--min-area", "--min-area-px");
  app_->deprecated_name("--max-area", "--max-area-px");
}

void Parser::add_mask_options() {
  app_->add_option_function<std::string>(
          "--mode",
          [this](const std::string& v) {
            o.blobs = v != "mask";
            o.mask = v != "blobs";
          },
          "blobs (default), mask (silhouettes) or both")
      ->option_text("M")
      ->check(cli::one_of({"blobs", "mask", "both"}));
  cli::add_checked(*app_, "--train-frames", o.train_frames, "N", cli::whole_in<int>(1, 10000),
                   "mask: train the background on N frames (default: on the\n"
                   "host's TRAIN_BACKGROUND command) ...");
  app_->add_option("--background", o.background,
                   "mask: a recording of the empty scene, a video file or a folder of\n"
                   "numbered images: the model trains on --train-frames N of its frames\n"
                   "(default " +
                       std::to_string(segmentation::kBackgroundClipFrames) +
                       ", spread over it) before the first frame, for a capture\n"
                       "that starts with the person in view")
      ->option_text("FILE|DIR");
  cli::add_checked(*app_, "--train-from-frame", o.train_from_frame, "F",
                   cli::whole_in<int64_t>(0, int64_t{1} << 53),
                   "... numbered F..F+N-1 (default: the first N frames)");
  cli::add_checked(*app_, "--contour-tolerance-px", o.contour_tolerance_px, "PX",
                   cli::number_in(0, 100),
                   "mask: polygon simplification, pixels" + by_default(o.contour_tolerance_px));
  app_->deprecated_name("--contour-tolerance", "--contour-tolerance-px");
  // --mask-NAME: the medi-picture option NAME, from the defaults (docs/design/segmentation.md),
  // checked by apply_masking_option as segment-eval's are.
  syncap::segmentation::add_mask_options(*app_, o.masking, "mask: ");
  cli::add_checked(*app_, "--patch-every", o.patch_every, "N", cli::whole_in<int>(0, 100000),
                   "mask: send the person's grey values (image_patch_t) every Nth frame\n"
                   "(frame_number % N == 0) for the host's surface matching; 0: never" +
                       by_default(o.patch_every));
  cli::add_checked(
      *app_, "--patch-margin-px", o.patch_margin_px, "PX", cli::whole_in<int>(0, 64),
      "mask: pixels beyond the silhouette a patch holds" + by_default(o.patch_margin_px));
  app_->deprecated_name("--patch-margin", "--patch-margin-px");
  app_->add_flag_callback(
      "--mask-no-shadows", [this] { o.masking.remove_shadows = false; },
      "mask: skip the shadow test");
}

void Parser::add_network_options() {
  app_->add_option("--lcm-url", o.lcm_url,
                   std::string("LCM provider (default ") + proto::kDefaultLcmUrl + ")")
      ->option_text("URL");
  app_->add_option("--command-key", o.command_key_path,
                   "the installation's key (syncap keygen): only commands and clip\n"
                   "polygons signed with it are obeyed; without it none are\n"
                   "(docs/design/security.md)")
      ->option_text("FILE");
  cli::add_checked(*app_, "--command-window-s", o.command_window_s, "S", cli::number_in(0.1, 3600),
                   "a command is obeyed only when sent within S s of this\n"
                   "board's clock (the clocks must agree that well)" +
                       by_default(o.command_window_s));
  cli::add_checked(*app_, "--heartbeat-s", o.heartbeat_s, "S", cli::whole_in<int>(1, 3600),
                   "status period, whole seconds" + by_default(o.heartbeat_s));
  cli::add_checked(
      *app_, "--publish-queue", o.publish_queue, "N", cli::whole_in<int>(1, 100000),
      "messages waiting to be sent before the oldest is dropped" + by_default(o.publish_queue));
}

void Parser::add_run_options() {
  app_->add_flag("--exit-after-last", o.exit_after_last,
                 "exit after the frame of the trigger's last pulse");
  app_->add_flag("--quiet", o.quiet, "no per-run log lines on stderr");
}

// What no single option can check: the required ones and the combinations.
void check_combination(const EdgeOptions& o, bool have_camera) {
  if (!have_camera) throw UsageError("syncap-edge: --camera-id is required");
  const bool replay = o.source.starts_with("replay:") && o.source.size() > 7;
  const bool aravis = o.source.starts_with("aravis:") && o.source.size() > 7;
  const bool v4l2 = o.source.starts_with("v4l2:") && o.source.size() > 5;
  if (!replay && !aravis && !v4l2) {
    throw UsageError("syncap-edge: --source '" + o.source +
                     "': expected replay:FOLDER, aravis:ADDRESS or v4l2:DEVICE");
  }
  if (o.train_from_frame >= 0 && o.train_frames <= 0) {
    throw UsageError("syncap-edge: --train-from-frame needs --train-frames N");
  }
  if (o.patch_every > 0 && !o.mask) {
    throw UsageError(
        "syncap-edge: --patch-every needs --mode mask or both (a patch is where "
        "the silhouette is)");
  }
  if (!o.background.empty() && !o.mask) {
    throw UsageError("syncap-edge: --background needs --mode mask or both");
  }
  if (!o.background.empty() && o.train_from_frame >= 0) {
    throw UsageError(
        "syncap-edge: --background and --train-from-frame are two ways to train: give one");
  }
  if (o.train_frames > 0 && !o.mask) {
    throw UsageError("syncap-edge: --train-frames needs --mode mask or both");
  }
  if (o.roi_follows_windows && o.detection != DetectionMode::kWindowed) {
    throw UsageError("syncap-edge: --roi-follows-windows needs --detection windowed");
  }
  if (o.roi_follows_windows && o.mask) {
    // The silhouette needs the whole sensor every frame.
    throw UsageError("syncap-edge: --roi-follows-windows needs --mode blobs");
  }
}

}  // namespace

std::string edge_usage() { return Parser().help(); }

EdgeOptions parse_edge_options(const std::vector<std::string>& args) {
  // A first parse finds --help, a bad command line and the config file; the file's values then
  // go first and the command line's over them, wherever --config stands.
  Parser scan;
  scan.parse_command_line(args);
  std::vector<std::string> all;
  if (!scan.config.empty()) {
    // A rig file: its edges: section and the entry of this camera (the command line's id).
    const cli::RigPart part{"edges",
                            scan.have_camera ? std::optional(scan.o.camera_id) : std::nullopt, ""};
    std::vector<std::unique_ptr<Parser>> scratch;  // the factory's parsers live until done
    try {
      all = cli::config_arguments("syncap-edge", scan.config, part, [&scratch] {
        scratch.push_back(std::make_unique<Parser>());
        return scratch.back()->release_app();
      });
    } catch (const cli::ConfigError& e) {
      throw UsageError(e.what());
    }
  }
  all.insert(all.end(), args.begin(), args.end());
  Parser parser;
  parser.parse_command_line(all);
  check_combination(parser.o, parser.have_camera);
  return parser.o;
}

}  // namespace syncap::edge
