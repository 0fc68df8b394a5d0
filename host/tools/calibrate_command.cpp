#include "calibrate_command.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/observations.hpp"
#include "calibration/outputs.hpp"
#include "lcm_log_reader.hpp"
#include "subcommand.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/decode.hpp"
#include "syncap/proto/subscriber.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kPrefix = "syncap calibrate: ";

struct CalibrateArgs {
  std::string input;
  std::string out;
  std::optional<double> wand_length;
  bool led = false;
  std::set<int> cameras;
  long frames = 0;
  // Frame numbers to calibrate from (lcm:, lcmlog:): a log of a whole session holds the wand
  // phase and then the capture, whose markers are no wand.
  int64_t first_frame = 0;
  int64_t last_frame = std::numeric_limits<int64_t>::max();
  bool in_range(int64_t frame) const { return frame >= first_frame && frame <= last_frame; }
  double idle_timeout_s = 5.0;
  bool progress = false;
  std::optional<calibration::ImageSize> image_size;  // for sources without one (CSV)
  calibration::CalibrationOptions options;
};

struct UsageError {
  std::string message;
};

double number_arg(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw UsageError{option + " needs a number, got '" + text + "'"};
  }
  return v;
}

// "40,50,60" -> {40, 50, 60}; "none" -> {}.
std::vector<double> number_list(const std::string& option, const std::string& text) {
  std::vector<double> out;
  if (text == "none") return out;
  std::istringstream items(text);
  for (std::string item; std::getline(items, item, ',');) out.push_back(number_arg(option, item));
  if (out.empty()) throw UsageError{option + " needs a comma-separated list or 'none'"};
  return out;
}

std::set<int> camera_list(const std::string& text) {
  std::set<int> ids;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const double v = number_arg("--cameras", item);
    if (v < 0 || v > proto::kMaxCameraId || v != static_cast<int>(v)) {
      throw UsageError{"--cameras: '" + item + "' is not a camera id (0-99)"};
    }
    ids.insert(static_cast<int>(v));
  }
  if (ids.empty()) throw UsageError{"--cameras needs a list like 0,1,2"};
  return ids;
}

std::vector<int> interior_list(const std::string& text) {
  const auto& names = sensor::InteriorBlock::kNames;
  std::vector<int> free;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    int index = -1;
    for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
      if (item == names[i]) index = i;
    }
    if (index < 0) {
      throw UsageError{"--interior: '" + item + "' is not one of c,xp,yp,k1,k2,k3,p1,p2,sc,sh"};
    }
    free.push_back(index);
  }
  return free;
}

// "FIRST-LAST" (either may be left out: "300-", "-299") into a.first_frame, a.last_frame.
void parse_frame_range(const std::string& text, CalibrateArgs& a) {
  const auto dash = text.find('-');
  const auto bound = [&](const std::string& part, int64_t fallback) {
    if (part.empty()) return fallback;
    const double v = number_arg("--frame-range", part);
    if (v < 0 || v != std::floor(v) || v > 9e15) {
      throw UsageError{"--frame-range: '" + part + "' is not a frame number"};
    }
    return static_cast<int64_t>(v);
  };
  if (dash == std::string::npos || text == "-") {
    throw UsageError{"--frame-range needs FIRST-LAST (e.g. 0-299, or 300-), got '" + text + "'"};
  }
  a.first_frame = bound(text.substr(0, dash), 0);
  a.last_frame = bound(text.substr(dash + 1), std::numeric_limits<int64_t>::max());
  if (a.first_frame > a.last_frame) {
    throw UsageError{"--frame-range: " + text + " ends before it starts"};
  }
}

CalibrateArgs parse_args(std::span<const std::string> args) {
  CalibrateArgs a;
  auto& o = a.options;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 == args.size()) throw UsageError{arg + " needs a value"};
      return args[++i];
    };
    if (arg == "--input") {
      a.input = value();
    } else if (arg == "--out") {
      a.out = value();
    } else if (arg == "--wand-length") {
      a.wand_length = number_arg(arg, value());
    } else if (arg == "--led") {
      a.led = true;
    } else if (arg == "--wand-targets") {
      const double n = number_arg(arg, value());
      if (n != 2 && n != 3) throw UsageError{"--wand-targets must be 2 or 3"};
      o.wand.targets = static_cast<int>(n);
    } else if (arg == "--wand-ratio") {
      o.wand.middle_ratio = number_arg(arg, value());
    } else if (arg == "--wand-ends") {
      const std::string& v = value();
      if (v == "size") {
        o.wand.ends = calibration::EndIdentity::kSize;
      } else if (v == "continuity") {
        o.wand.ends = calibration::EndIdentity::kContinuity;
      } else {
        throw UsageError{"--wand-ends must be size or continuity, got '" + v + "'"};
      }
    } else if (arg == "--pixel-size") {
      o.pixel_size_mm = number_arg(arg, value());
      if (!(o.pixel_size_mm > 0)) throw UsageError{"--pixel-size must be > 0"};
    } else if (arg == "--fov") {
      o.field_of_view_deg = number_arg(arg, value());
    } else if (arg == "--start-fovs") {
      o.start_fields_of_view_deg = number_list(arg, value());
    } else if (arg == "--scale-from") {
      const std::vector<double> v = number_list(arg, value());
      if (v.size() != 3 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) || v[0] == v[1] ||
          !(v[2] > 0)) {
        throw UsageError{"--scale-from needs A,B,MM: two camera ids and their centres' distance"};
      }
      o.scale_from =
          calibration::KnownCameraDistance{static_cast<int>(v[0]), static_cast<int>(v[1]), v[2]};
    } else if (arg == "--principal-point-sigma") {
      o.principal_point_sigma_share = number_arg(arg, value());
      if (!(*o.principal_point_sigma_share >= 0)) {
        throw UsageError{"--principal-point-sigma must be >= 0"};
      }
    } else if (arg == "--check-share") {
      o.check_point_share = number_arg(arg, value());
      if (!(o.check_point_share >= 0 && o.check_point_share <= 0.5)) {
        throw UsageError{"--check-share must lie in [0, 0.5]"};
      }
    } else if (arg == "--sigma-px") {
      o.sigma_px = number_arg(arg, value());
    } else if (arg == "--wand-sigma") {
      o.wand_sigma_mm = number_arg(arg, value());
    } else if (arg == "--critical-w") {
      o.critical_snooping = number_arg(arg, value());
    } else if (arg == "--max-frames") {
      const std::string& v = value();
      const double n = number_arg(arg, v);
      if (!(n >= 1 && n <= 1e9 && n == std::floor(n))) {
        throw UsageError{"--max-frames must be a whole number >= 1, got '" + v + "'"};
      }
      o.max_frames = static_cast<int>(n);
    } else if (arg == "--bootstrap") {
      o.bootstrap_samples = static_cast<int>(number_arg(arg, value()));
    } else if (arg == "--image-size") {
      const std::string& v = value();
      const auto x = v.find('x');
      const double w = x == std::string::npos ? 0 : number_arg(arg, v.substr(0, x));
      const double h = x == std::string::npos ? 0 : number_arg(arg, v.substr(x + 1));
      if (!(w >= 1 && h >= 1 && w == static_cast<int>(w) && h == static_cast<int>(h))) {
        throw UsageError{"--image-size must be WIDTHxHEIGHT in pixels, got '" + v + "'"};
      }
      a.image_size = calibration::ImageSize{static_cast<int>(w), static_cast<int>(h)};
    } else if (arg == "--shared-interior") {
      o.shared_interior = true;
    } else if (arg == "--model") {
      const std::string& v = value();
      if (v != "auto" && v != "all")
        throw UsageError{"--model must be auto or all, got '" + v + "'"};
      o.select_model = v == "auto";
    } else if (arg == "--interior") {
      o.free_interior = interior_list(value());
    } else if (arg == "--cameras") {
      a.cameras = camera_list(value());
    } else if (arg == "--frame-range") {
      parse_frame_range(value(), a);
    } else if (arg == "--frames") {
      a.frames = static_cast<long>(number_arg(arg, value()));
    } else if (arg == "--idle-timeout") {
      a.idle_timeout_s = number_arg(arg, value());
    } else if (arg == "--progress") {
      a.progress = true;
    } else {
      throw UsageError{"unknown option '" + arg + "'"};
    }
  }
  if (a.input.empty()) throw UsageError{"--input SOURCE is required"};
  if (a.out.empty()) throw UsageError{"--out DIR is required"};
  if (a.led == a.wand_length.has_value()) {
    throw UsageError{"give exactly one of --wand-length MM and --led"};
  }
  o.wand.led = a.led;
  if (a.wand_length) {
    if (!(*a.wand_length > 0)) throw UsageError{"--wand-length must be > 0 mm"};
    o.wand.length_mm = *a.wand_length;
  }
  return a;
}

// The cameras' blob channels and the trigger go to the collector; everything else is ignored.
bool is_blob_channel(const std::string& channel) {
  return channel.rfind(proto::kBlobChannelPrefix, 0) == 0;
}

calibration::Observations read_lcm_log(const std::string& file, const CalibrateArgs& a,
                                       std::ostream& err) {
  std::set<int> cameras = a.cameras;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw calibration::ObservationError(file + ": cannot open for reading");
  if (cameras.empty()) {  // every camera in the log
    LcmLogReader scan(in);
    while (auto event = scan.next()) {
      if (!is_blob_channel(event->channel)) continue;
      blob_frame_t frame;
      if (proto::try_decode(event->data.data(), event->data.size(), frame).ok()) {
        cameras.insert(frame.camera_id);
      }
    }
    in.clear();
    in.seekg(0);
  }
  if (cameras.empty()) throw calibration::ObservationError(file + ": no blob frames in the log");
  calibration::BlobFrameCollector collector("lcmlog:" + file, cameras);
  LcmLogReader reader(in);
  long undecodable = 0;
  // A malformed record (the decoder throws on a negative array length) is skipped and named;
  // the records around it are kept.
  const auto decode = [&](const LogEvent& event, auto& msg) {
    const proto::DecodeResult decoded =
        proto::try_decode(event.data.data(), event.data.size(), msg);
    if (!decoded.ok() && undecodable++ < 5) {
      err << kPrefix << file << ": event " << event.event_number << " at offset " << event.offset
          << " on " << event.channel << " is not a " << msg.getTypeName() << " (" << decoded.error
          << "), skipped\n";
    }
    return decoded.ok();
  };
  while (auto event = reader.next()) {
    if (is_blob_channel(event->channel)) {
      blob_frame_t frame;
      if (decode(*event, frame) && a.in_range(frame.frame_number)) collector.add_blob_frame(frame);
    } else if (event->channel == proto::kTriggerChannel) {
      trigger_t trigger;
      if (decode(*event, trigger) && a.in_range(trigger.frame_number))
        collector.add_trigger(trigger);
    }
  }
  if (undecodable > 0) {
    err << kPrefix << file << ": " << undecodable << " malformed records skipped\n";
  }
  for (const LogError& e : reader.take_errors())
    err << kPrefix << file << ": " << e.message << '\n';
  for (const std::string& p : collector.problems()) err << kPrefix << p << '\n';
  return collector.finish();
}

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

calibration::Observations read_live(const std::string& url, const CalibrateArgs& a,
                                    std::ostream& err, bool progress) {
  if (a.cameras.empty()) throw UsageError{"lcm: needs --cameras (the ids to wait for)"};
  lcm::LCM lcm(proto::receiving_lcm_url(url));
  if (!lcm.good()) throw calibration::ObservationError("lcm:" + url + ": cannot open LCM");
  calibration::BlobFrameCollector collector("lcm:" + url, a.cameras);
  proto::Subscriber sub(lcm, [&](const std::string& m) { err << kPrefix << m << '\n'; });
  using Clock = std::chrono::steady_clock;
  std::optional<Clock::time_point> last_blob;
  bool past_range = false;  // a blob frame after --frame-range's last: the range is complete
  sub.subscribe<trigger_t>(proto::kTriggerChannel, [&](const trigger_t& t, const std::string&) {
    if (a.in_range(t.frame_number)) collector.add_trigger(t);
  });
  sub.subscribe<blob_frame_t>(std::string(proto::kBlobChannelPrefix) + ".*",
                              [&](const blob_frame_t& f, const std::string&) {
                                past_range = past_range || f.frame_number > a.last_frame;
                                if (!a.in_range(f.frame_number)) return;
                                collector.add_blob_frame(f);
                                last_blob = Clock::now();
                              });
  g_stop = 0;
  auto previous_int = std::signal(SIGINT, on_signal);
  auto previous_term = std::signal(SIGTERM, on_signal);
  if (progress) err << kPrefix << "listening on " << url << " (Ctrl-C ends the collection)\n";
  long reported = 0;
  while (!g_stop) {
    lcm.handleTimeout(100);
    if (a.frames > 0 && collector.frame_groups() >= a.frames) break;
    if (past_range) break;
    if (last_blob && Clock::now() - *last_blob > std::chrono::duration<double>(a.idle_timeout_s)) {
      break;
    }
    if (progress && collector.frame_groups() >= reported + 30) {
      reported = collector.frame_groups();
      err << kPrefix << reported << " frame groups\n";
    }
  }
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
  return collector.finish();
}

calibration::Observations read_source(const CalibrateArgs& a, std::ostream& err, bool progress) {
  const auto colon = a.input.find(':');
  if (colon == std::string::npos) {
    throw UsageError{"--input '" + a.input +
                     "': expected lcm:URL, lcmlog:FILE, csv:FILE or mcsc:DIR"};
  }
  const std::string kind = a.input.substr(0, colon);
  const std::string where = a.input.substr(colon + 1);
  if (kind == "csv") return calibration::read_csv_observations(where);
  if (kind == "mcsc") return calibration::read_mcsc_observations(where);
  if (kind == "lcmlog") return read_lcm_log(where, a, err);
  if (kind == "lcm") return read_live(where, a, err, progress);
  throw UsageError{"--input '" + a.input + "': unknown source '" + kind +
                   "' (lcm, lcmlog, csv, mcsc)"};
}

// Empty when `dir` exists (or is created) and takes a file; else why not.
std::string unwritable_folder(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return "cannot create the folder (" + ec.message() + ")";
  const std::filesystem::path probe = std::filesystem::path(dir) / ".syncap-write-check";
  std::ofstream file(probe);
  const bool written = file && (file << "x") && file.flush();
  file.close();
  std::filesystem::remove(probe, ec);
  if (!written) return std::string("cannot write in it (") + std::strerror(errno) + ")";
  return {};
}

void print_summary(const calibration::CalibrationResult& r, std::ostream& out) {
  const auto& q = r.quality;
  out << std::fixed << std::setprecision(4);
  out << "calibrated " << r.cameras.size() << " cameras: sigma0 " << q.sigma0_px << " px, RMS "
      << q.rms_px << " px, " << q.observations << " observations, " << q.outliers_removed
      << " outliers removed";
  if (q.wand_length_mean_mm) {
    out << ", wand " << *q.wand_length_mean_mm << " +- " << *q.wand_length_sd_mm << " mm";
  }
  out << (r.adjustment.converged ? "" : " (NOT CONVERGED)") << '\n';
  out << "verdict: " << q.verdict << '\n';
  for (const std::string& reason : r.report.verdict_reasons) out << "  " << reason << '\n';
  for (const auto& c : r.cameras) {
    out << "  camera " << c.id << ": c " << c.interior.c << " mm, RMS "
        << q.per_camera_rms_px.at(c.id) << " px\n";
  }
}

}  // namespace

int calibrate_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  for (const std::string& arg : args) {
    if (arg == "--help" || arg == "-h") {
      out << kCalibrateUsage;
      return kExitOk;
    }
  }
  CalibrateArgs a;
  try {
    a = parse_args(args);
  } catch (const UsageError& e) {
    err << kPrefix << e.message << '\n' << kCalibrateUsage;
    return kExitUsage;
  }
  // Checked before the input is read: a calibration can take minutes.
  if (const std::string problem = unwritable_folder(a.out); !problem.empty()) {
    err << kPrefix << "--out " << a.out << ": " << problem << '\n';
    return kExitUsage;
  }
  const bool progress = a.progress || (&err == &std::cerr && ::isatty(STDERR_FILENO));
  if (progress)
    a.options.progress = [&err](const std::string& line) { err << kPrefix << line << '\n'; };
  calibration::Observations observations;
  try {
    observations = read_source(a, err, progress);
  } catch (const UsageError& e) {
    err << kPrefix << e.message << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    err << kPrefix << e.what() << '\n';
    return kExitUsage;
  }
  if (a.image_size) {
    for (int id : observations.cameras()) observations.image_sizes.try_emplace(id, *a.image_size);
  }
  try {
    const calibration::CalibrationResult result = calibration::calibrate(observations, a.options);
    const auto files = calibration::write_calibration(result, a.out);
    print_summary(result, out);
    for (const auto& f : files) out << "wrote " << f.string() << '\n';
    if (!result.adjustment.converged) {
      err << kPrefix << "the adjustment did not converge: " << result.adjustment.termination
          << '\n';
      return kExitReportedErrors;
    }
    if (result.verdict == calibration::Verdict::kFailed) {
      err << kPrefix << "the calibration failed its checks (report.txt says why): "
          << result.quality.verdict_reasons.front() << '\n';
      return kExitReportedErrors;
    }
  } catch (const std::exception& e) {
    err << kPrefix << e.what() << '\n';
    return kExitReportedErrors;
  }
  return kExitOk;
}

}  // namespace syncap::tools
