#include "app/edge_options.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cstdio>
#include <optional>
#include <set>

#include "segmentation/masking_options.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::edge {
namespace {

bool parse_bool(const std::string& text) {
  if (text == "true" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "no" || text == "off") return false;
  throw BadValue("'" + text + "': expected true or false");
}

cv::Rect parse_roi(const std::string& text) {
  int v[4];
  const char* at = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0) {
      if (at == end || *at != ',') at = nullptr;
      if (at) ++at;
    }
    auto [next, ec] = at ? std::from_chars(at, end, v[i]) : std::from_chars_result{};
    if (!at || ec != std::errc() || v[i] < 0 || v[i] > 32767) {
      throw BadValue("'" + text + "': expected X,Y,WIDTH,HEIGHT in sensor pixels");
    }
    at = next;
  }
  if (at != end) throw BadValue("'" + text + "': expected X,Y,WIDTH,HEIGHT in sensor pixels");
  return {v[0], v[1], v[2], v[3]};
}

bool is_flag(const std::string& option) {
  return option == "--udp-socket" || option == "--exit-after-last" || option == "--quiet" ||
         option == "--roi-follows-windows" || option == "--mask-no-shadows";
}

bool takes_value(const std::string& option) {
  static const std::set<std::string> kOptions{"--config",
                                              "--command-key",
                                              "--command-window-s",
                                              "--camera-id",
                                              "--source",
                                              "--trigger-source",
                                              "--exposure-us",
                                              "--gain-db",
                                              "--detection",
                                              "--full-scan-every",
                                              "--mode",
                                              "--train-frames",
                                              "--train-from-frame",
                                              "--contour-tolerance",
                                              "--mask-k",
                                              "--mask-min-difference",
                                              "--mask-shadow-test",
                                              "--mask-shadow-sigmas",
                                              "--mask-ncc",
                                              "--mask-fill-holes",
                                              "--mask-closing",
                                              "--mask-min-area",
                                              "--mask-update-rate",
                                              "--roi",
                                              "--threshold",
                                              "--min-area",
                                              "--max-area",
                                              "--lcm-url",
                                              "--heartbeat-s",
                                              "--publish-queue",
                                              "--reopen-first-s",
                                              "--reopen-max-s",
                                              "--camera-silent-s",
                                              "--match-tolerance-ms"};
  return kOptions.contains(option);
}

// Applies one option. `value` is its argument (nullopt for a flag given on the command line,
// "true"/"false" for a flag from the config file). Returns false for an unknown option; throws
// BadValue.
bool apply_option(EdgeOptions& o, const std::string& a, const std::optional<std::string>& value,
                  bool& have_camera) {
  if (is_flag(a)) {
    const bool on = value ? parse_bool(*value) : true;
    if (a == "--udp-socket") o.udp_socket = on;
    if (a == "--exit-after-last") o.exit_after_last = on;
    if (a == "--quiet") o.quiet = on;
    if (a == "--roi-follows-windows") o.roi_follows_windows = on;
    if (a == "--mask-no-shadows") o.masking.remove_shadows = !on;
    return true;
  }
  // --mask-K: the medi-picture option K (docs/segmentation.md has what each does).
  if (a.rfind("--mask-", 0) == 0)
    return apply_masking_option(o.masking, a.substr(7), value.value());
  const std::string& v = value.value();
  if (a == "--camera-id") {
    o.camera_id = parse_number<int>(v, 0, proto::kMaxCameraId);
    have_camera = true;
  } else if (a == "--source") {
    o.source = v;
  } else if (a == "--trigger-source") {
    o.trigger_source = v;
  } else if (a == "--exposure-us") {
    o.exposure_us = parse_number<int>(v, 1, 10'000'000);
  } else if (a == "--gain-db") {
    o.gain_db = parse_number<double>(v, 0, 100);
  } else if (a == "--detection") {
    if (v != "full" && v != "windowed") throw BadValue("'" + v + "': expected full or windowed");
    o.detection = v == "full" ? DetectionMode::kFull : DetectionMode::kWindowed;
  } else if (a == "--full-scan-every") {
    o.full_scan_every = parse_number<int>(v, 1, 100000);
  } else if (a == "--mode") {
    if (v != "blobs" && v != "mask" && v != "both")
      throw BadValue("'" + v + "': expected blobs, mask or both");
    o.blobs = v != "mask";
    o.mask = v != "blobs";
  } else if (a == "--train-frames") {
    o.train_frames = parse_number<int>(v, 1, 10000);
  } else if (a == "--train-from-frame") {
    o.train_from_frame = parse_number<int64_t>(v, 0, int64_t{1} << 53);
  } else if (a == "--contour-tolerance") {
    o.contour_tolerance_px = parse_number<double>(v, 0, 100);
  } else if (a == "--roi") {
    o.roi = parse_roi(v);
  } else if (a == "--threshold") {
    o.detector.threshold = parse_number<int>(v, 1, 255);
  } else if (a == "--min-area") {
    o.detector.min_area = static_cast<float>(parse_number<int>(v, 1, 1 << 24));
  } else if (a == "--max-area") {
    o.detector.max_area = static_cast<float>(parse_number<int>(v, 1, 1 << 24));
  } else if (a == "--lcm-url") {
    o.lcm_url = v;
  } else if (a == "--command-key") {
    o.command_key_path = v;
  } else if (a == "--command-window-s") {
    o.command_window_s = parse_number<double>(v, 0.1, 3600);
  } else if (a == "--heartbeat-s") {
    o.heartbeat_s = parse_number<int>(v, 1, 3600);
  } else if (a == "--publish-queue") {
    o.publish_queue = parse_number<int>(v, 1, 100000);
  } else if (a == "--reopen-first-s") {
    o.reopen_first_s = parse_number<double>(v, 0.01, 3600);
  } else if (a == "--reopen-max-s") {
    o.reopen_max_s = parse_number<double>(v, 0.01, 3600);
  } else if (a == "--camera-silent-s") {
    o.camera_silent_s = parse_number<double>(v, 0, 3600);
  } else if (a == "--match-tolerance-ms") {
    o.match_tolerance_ms = parse_number<double>(v, 0.001, 10000);
  } else {
    return false;
  }
  return true;
}

// "FILE:LINE:COLUMN" of a YAML node (yaml-cpp counts from 0).
std::string place(const std::string& file, const YAML::Mark& mark) {
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

void apply_config_file(EdgeOptions& o, const std::string& file, bool& have_camera) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw UsageError("syncap-edge: --config " + file + ": cannot be read");
  } catch (const YAML::ParserException& e) {
    throw UsageError("syncap-edge: " + place(file, e.mark) + ": " + e.msg);
  }
  if (root.IsNull()) return;  // an empty file
  if (!root.IsMap()) {
    throw UsageError("syncap-edge: " + place(file, root.Mark()) +
                     ": expected `key: value` lines (the long option names)");
  }
  for (const auto& entry : root) {
    if (!entry.first.IsScalar()) {  // as<std::string>() would throw yaml-cpp's BadConversion
      throw UsageError("syncap-edge: " + place(file, entry.first.Mark()) + ": a key must be text");
    }
    const std::string key = entry.first.Scalar();
    const std::string where = "syncap-edge: " + place(file, entry.first.Mark()) + ": key '" + key;
    if (!entry.second.IsScalar()) throw UsageError(where + "': expected a single value");
    if (key == "config") throw UsageError(where + "': a config file cannot include another");
    try {
      if (!apply_option(o, "--" + key, entry.second.Scalar(), have_camera)) {
        throw UsageError(where + "': unknown key (keys are syncap-edge's long options)");
      }
    } catch (const BadValue& e) {
      throw UsageError(where + "' " + e.what());
    }
  }
}

}  // namespace

std::string edge_usage() {
  return "usage: syncap-edge --camera-id N --source replay:FOLDER [options]\n"
         "       syncap-edge --config FILE [options]\n"
         "  --config FILE       YAML file of `option: value` lines, keys = the long options\n"
         "                      below (camera-id: 3); options on the command line override it\n"
         "  --camera-id N       camera id 0..99 (channel SYNCAP_BLOBS_NN)\n"
         "  --source SPEC       replay:FOLDER  numbered 8-bit images, frame k = file number k\n"
         "                      replay:VIDEO   a video file, frame k = its k-th frame (from 0)\n"
         "                      aravis:ADDRESS GigE Vision camera at this IPv4 address\n"
         "                      v4l2:DEVICE    UVC camera, e.g. v4l2:/dev/video0 (docs/v4l2.md)\n"
         "  --trigger-source S  aravis: the camera's TriggerSource (Line1, Software, ...)\n"
         "  --exposure-us US    aravis: exposure time\n"
         "  --gain-db DB        aravis: analog gain (Gain, in dB)\n"
         "  --udp-socket        aravis: receive with a UDP socket, not a packet socket (no\n"
         "                      CAP_NET_RAW needed; its buffer grows only after the first frame)\n"
         "  --roi X,Y,W,H       sensor region of interest at start (blobs stay in sensor pixels)\n"
         "  --detection D       full (default): every frame whole; windowed: tracked blobs\n"
         "                      searched around their prediction (docs/edge.md)\n"
         "  --full-scan-every N windowed: a full scan for new blobs every N frames (30)\n"
         "  --roi-follows-windows  windowed: the sensor ROI follows the union of the windows\n"
         "  --mode M            blobs (default), mask (silhouettes) or both\n"
         "  --train-frames N    mask: train the background on N frames (else on the host's\n"
         "                      TRAIN_BACKGROUND command) ...\n"
         "  --train-from-frame F  ... numbered F..F+N-1 (default: the first N frames)\n"
         "  --contour-tolerance PX  mask: polygon simplification (default 0.5)\n"
         "  --mask-k K, --mask-min-difference DN, --mask-shadow-test correlation|common-ratio,\n"
         "  --mask-shadow-sigmas S, --mask-ncc L, --mask-no-shadows, --mask-fill-holes PX,\n"
         "  --mask-closing PX, --mask-min-area PX, --mask-update-rate R\n"
         "                      mask: change the person preset (k 1, min difference 6,\n"
         "                      common-ratio at 3 sigmas, closing 5, holes to 100 px filled;\n"
         "                      docs/segmentation.md), as segment-eval --person takes them\n"
         "  --threshold DN      blob threshold 1..255 (default 128)\n"
         "  --min-area PX       smallest blob area (default 2)\n"
         "  --max-area PX       largest blob area (default 20000)\n"
         "  --lcm-url URL       LCM provider (default " +
         std::string(proto::kDefaultLcmUrl) +
         ")\n"
         "  --command-key FILE  the installation's key (syncap keygen): only commands and clip\n"
         "                      polygons signed with it are obeyed; without it none are\n"
         "                      (docs/security.md)\n"
         "  --command-window-s S  a command is obeyed only when sent within S s of this\n"
         "                      board's clock (default 5; the clocks must agree that well)\n"
         "  --heartbeat-s S     status period in seconds (default 1)\n"
         "  --publish-queue N   messages waiting to be sent before the oldest is dropped (64)\n"
         "  --camera-silent-s S aravis, v4l2: no frame for S s while triggered = camera lost\n"
         "                      (default 5; 0: only errors count)\n"
         "  --reopen-first-s S  a lost camera is reopened after S s (0.5), doubling up to\n"
         "  --reopen-max-s S    S s (10)\n"
         "  --match-tolerance-ms MS  v4l2: a frame takes the number of the trigger closest in\n"
         "                      time within MS (default 10)\n"
         "  --exit-after-last   exit after the frame of the trigger's last pulse\n"
         "  --quiet             no per-run log lines on stderr\n";
}

EdgeOptions parse_edge_options(const std::vector<std::string>& args) {
  EdgeOptions o;
  o.lcm_url = proto::kDefaultLcmUrl;
  bool have_camera = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") throw UsageError("help");
    if (args[i] != "--config") continue;
    if (i + 1 >= args.size()) throw UsageError("syncap-edge: --config needs a value");
    apply_config_file(o, args[i + 1], have_camera);
  }
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    std::optional<std::string> value;
    if (!is_flag(a)) {
      if (!takes_value(a)) throw UsageError("syncap-edge: unknown option '" + a + "'");
      if (i + 1 >= args.size()) throw UsageError("syncap-edge: " + a + " needs a value");
      value = args[++i];
    }
    if (a == "--config") continue;
    try {
      if (!apply_option(o, a, value, have_camera))
        throw UsageError("syncap-edge: unknown option '" + a + "'");
    } catch (const BadValue& e) {
      throw UsageError("syncap-edge: " + a + " " + e.what());
    }
  }
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
  return o;
}

}  // namespace syncap::edge
