#include "app/edge_options.hpp"

#include <charconv>

#include "syncap/proto/channels.hpp"

namespace syncap::edge {
namespace {

template <class T>
T parse_number(const std::string& option, const std::string& text, T low, T high) {
  T value{};
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < low || value > high) {
    throw UsageError("syncap-edge: " + option + " '" + text + "': expected a number in " +
                     std::to_string(low) + ".." + std::to_string(high));
  }
  return value;
}

}  // namespace

std::string edge_usage() {
  return "usage: syncap-edge --camera-id N --source replay:FOLDER [options]\n"
         "  --camera-id N       camera id 0..99 (channel SYNCAP_BLOBS_NN)\n"
         "  --source SPEC       replay:FOLDER  numbered 8-bit images, frame k = file number k\n"
         "                      aravis:ADDRESS GigE Vision camera at this IPv4 address\n"
         "                      v4l2:DEVICE    UVC camera, e.g. v4l2:/dev/video0 (docs/v4l2.md)\n"
         "  --trigger-source S  aravis: the camera's TriggerSource (Line1, Software, ...)\n"
         "  --exposure-us US    aravis: exposure time\n"
         "  --udp-socket        aravis: receive with a UDP socket, not a packet socket (no\n"
         "                      CAP_NET_RAW needed; its buffer grows only after the first frame)\n"
         "  --mode M            blobs (default), mask (silhouettes) or both\n"
         "  --train-frames N    mask: train the background on the first N frames (else on the\n"
         "                      host's TRAIN_BACKGROUND command)\n"
         "  --contour-tolerance PX  mask: polygon simplification (default 1)\n"
         "  --threshold DN      blob threshold 1..255 (default 128)\n"
         "  --min-area PX       smallest blob area (default 2)\n"
         "  --max-area PX       largest blob area (default 20000)\n"
         "  --lcm-url URL       LCM provider (default " +
         std::string(proto::kDefaultLcmUrl) +
         ")\n"
         "  --heartbeat-s S     status period in seconds (default 1)\n"
         "  --exit-after-last   exit after the frame of the trigger's last pulse\n"
         "  --quiet             no per-run log lines on stderr\n";
}

EdgeOptions parse_edge_options(const std::vector<std::string>& args) {
  EdgeOptions o;
  o.lcm_url = proto::kDefaultLcmUrl;
  bool have_camera = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError("syncap-edge: " + a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") throw UsageError("help");
    if (a == "--camera-id") {
      o.camera_id = parse_number<int>(a, value(), 0, proto::kMaxCameraId);
      have_camera = true;
    } else if (a == "--source") {
      o.source = value();
    } else if (a == "--trigger-source") {
      o.trigger_source = value();
    } else if (a == "--exposure-us") {
      o.exposure_us = parse_number<int>(a, value(), 1, 10'000'000);
    } else if (a == "--mode") {
      const std::string mode = value();
      if (mode != "blobs" && mode != "mask" && mode != "both") {
        throw UsageError("syncap-edge: --mode '" + mode + "': expected blobs, mask or both");
      }
      o.blobs = mode != "mask";
      o.mask = mode != "blobs";
    } else if (a == "--train-frames") {
      o.train_frames = parse_number<int>(a, value(), 1, 10000);
    } else if (a == "--contour-tolerance") {
      o.contour_tolerance_px = parse_number<int>(a, value(), 0, 100);
    } else if (a == "--udp-socket") {
      o.udp_socket = true;
    } else if (a == "--threshold") {
      o.detector.threshold = parse_number<int>(a, value(), 1, 255);
    } else if (a == "--min-area") {
      o.detector.min_area = static_cast<float>(parse_number<int>(a, value(), 1, 1 << 24));
    } else if (a == "--max-area") {
      o.detector.max_area = static_cast<float>(parse_number<int>(a, value(), 1, 1 << 24));
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--heartbeat-s") {
      o.heartbeat_s = parse_number<int>(a, value(), 1, 3600);
    } else if (a == "--exit-after-last") {
      o.exit_after_last = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      throw UsageError("syncap-edge: unknown option '" + a + "'");
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
  return o;
}

}  // namespace syncap::edge
