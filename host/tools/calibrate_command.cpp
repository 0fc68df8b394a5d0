#include "calibrate_command.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
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

#include "app/host_options.hpp"
#include "board_calibrate_command.hpp"
#include "calibration/calibrate.hpp"
#include "calibration/observations.hpp"
#include "calibration/outputs.hpp"
#include "io/lcm_log_reader.hpp"
#include "stop_request.hpp"
#include "subcommand.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/cli/options.hpp"
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
  bool progress = false;  // --progress, kept for old scripts: the default now
  bool quiet = false;
  std::optional<calibration::ImageSize> image_size;  // for sources without one (CSV)
  calibration::CalibrationOptions options;
};

struct UsageError {
  std::string message;
};

// --start-fovs: "40,50,60" -> {40, 50, 60}; "none" -> {}.
std::vector<double> number_list(const std::string& text) {
  std::vector<double> out;
  if (text == "none") return out;
  std::istringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    const std::optional<double> v = cli::finite_number(item);
    if (!v) throw CLI::ValidationError("--start-fovs", "'" + item + "' is not a number");
    out.push_back(*v);
  }
  if (out.empty()) throw CLI::ValidationError("--start-fovs", "needs a list like 40,50 or none");
  return out;
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
      throw CLI::ValidationError("--interior",
                                 "'" + item + "' is not one of c,xp,yp,k1,k2,k3,p1,p2,sc,sh");
    }
    free.push_back(index);
  }
  return free;
}

// --scale-from A,B,MM: two camera ids and their centres' distance.
calibration::KnownCameraDistance scale_from(const std::string& text) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) parts.push_back(item);
  const auto id = [&](std::size_t i) {
    return parts.size() == 3 ? cli::whole_number(parts[i], 0, proto::kMaxCameraId) : std::nullopt;
  };
  const std::optional<double> mm = parts.size() == 3 ? cli::finite_number(parts[2]) : std::nullopt;
  if (!id(0) || !id(1) || *id(0) == *id(1) || !mm || !(*mm > 0)) {
    throw CLI::ValidationError("--scale-from", "'" + text +
                                                   "': needs A,B,MM: two camera ids and their "
                                                   "centres' distance");
  }
  return {static_cast<int>(*id(0)), static_cast<int>(*id(1)), *mm};
}

calibration::ImageSize image_size(const std::string& text) {
  const auto x = text.find('x');
  const auto side = [&](std::string part) { return cli::whole_number(part, 1, 1 << 20); };
  const auto w = x == std::string::npos ? std::nullopt : side(text.substr(0, x));
  const auto h = x == std::string::npos ? std::nullopt : side(text.substr(x + 1));
  if (!w || !h) {
    throw CLI::ValidationError("--image-size",
                               "'" + text + "' is not WIDTHxHEIGHT in pixels (e.g. 1280x1024)");
  }
  return calibration::ImageSize{static_cast<int>(*w), static_cast<int>(*h)};
}

// "FIRST-LAST" (either may be left out: "300-", "-299") into a.first_frame, a.last_frame.
void parse_frame_range(const std::string& text, CalibrateArgs& a) {
  const auto dash = text.find('-');
  const auto bound = [&](const std::string& part, int64_t fallback) {
    if (part.empty()) return fallback;
    const std::optional<long long> v = cli::whole_number(part, 0, 9'000'000'000'000'000);
    if (!v) throw CLI::ValidationError("--frame-range", "'" + part + "' is not a frame number");
    return static_cast<int64_t>(*v);
  };
  if (dash == std::string::npos || text == "-") {
    throw CLI::ValidationError("--frame-range",
                               "needs FIRST-LAST (e.g. 0-299, or 300-), got '" + text + "'");
  }
  a.first_frame = bound(text.substr(0, dash), 0);
  a.last_frame = bound(text.substr(dash + 1), std::numeric_limits<int64_t>::max());
  if (a.first_frame > a.last_frame)
    throw CLI::ValidationError("--frame-range", "'" + text + "' ends before it starts");
}

// SOURCE and what is written, above the options in --help.
constexpr const char* kDescription =
    "Calibrates the cameras from wand (or LED) observations and writes the calibration folder "
    "(docs/design/calibration.md).\n"
    "usage: syncap calibrate --input SOURCE (--wand-length-mm MM | --led) --out-dir DIR [options]\n"
    "       syncap calibrate --board COLSxROWSxMM --clip FILE|DIR... --intrinsics FILE... "
    "--out-dir DIR\n"
    "                        (from a checkerboard in the scene: syncap calibrate --board --help)\n"
    "SOURCE:\n"
    "  lcm:URL        blob frames live (udpm://239.255.76.67:7667?ttl=0); needs --camera-ids; "
    "stops\n"
    "                 at Ctrl-C, after --frames groups, or --idle-timeout-s without blob frames\n"
    "  lcmlog:FILE    blob frames recorded by lcm-logger (hil/run: OUT/traffic.lcmlog)\n"
    "  csv:FILE       frame,camera,x,y[,point] in pixels (point: target index from end A)\n"
    "  mcsc:DIR       a MultiCamSelfCal folder (points.dat, Res.dat, camera_order.txt)\n"
    "Writes DIR/cameras.json (with a \"quality\" block), report.txt, report.html,\n"
    "cameras.opencv.yaml, calibration.toml and, when built with the SDL writer, scene.sdl.\n"
    "DIR is created and checked writable before SOURCE is read.\n";

// What the run prints and its exit status, below the options in --help.
constexpr const char* kFooter =
    "A malformed record in lcmlog:FILE is named (event, offset, channel), counted and skipped.\n"
    "The summary and report.txt start with the verdict: good, weak (usable; the reasons say\n"
    "what the data could not determine) or failed (the geometry is wrong).\n"
    "Exit status: 0 calibrated (good or weak), 1 the calibration failed (did not converge, or its\n"
    "verdict is failed; the outputs are written for inspection), 2 usage error or unusable "
    "input.";

void add_source_options(CLI::App& app, CalibrateArgs& a) {
  app.add_option("--input", a.input, "lcm:URL, lcmlog:FILE, csv:FILE or mcsc:DIR (above)")
      ->option_text("SOURCE")
      ->required();
  app.add_option("--out-dir", a.out, "the calibration folder")->option_text("DIR")->required();
  app.add_option_function<std::string>(
         "--camera-ids", [&a](const std::string& t) { a.cameras = host_app::parse_camera_list(t); },
         "camera ids to wait for in each frame group (lcm:, lcmlog:; for a\n"
         "log default: every camera in it)")
      ->option_text("LIST");
  app.add_option_function<std::string>(
         "--frame-range", [&a](const std::string& t) { parse_frame_range(t, a); },
         "lcm:, lcmlog: only frames A to B (\"300-\", \"-299\": open ends);\n"
         "lcm: stops after frame B")
      ->option_text("A-B");
  cli::add_checked(app, "--frames", a.frames, "N", cli::whole_in(0, 1'000'000'000'000),
                   "lcm: stop after N frame groups (default 0: no limit)");
  cli::add_checked(app, "--idle-timeout-s", a.idle_timeout_s, "S", cli::finite(),
                   "lcm: stop S seconds after the last blob frame (default 5)");
  // Progress goes to stderr by default, on a terminal or not (a 20-camera rig takes minutes).
  app.add_flag("--quiet", a.quiet,
               "no progress on stderr (default: every step, and a line a "
               "second while an adjustment runs long)");
  app.add_flag("--progress", a.progress, "progress on stderr (the default)")->group("");
}

void add_wand_options(CLI::App& app, CalibrateArgs& a) {
  auto& w = a.options.wand;
  app.add_option_function<double>(
         "--wand-length-mm", [&a](double mm) { a.wand_length = mm; },
         "distance between the wand's end targets")
      ->option_text("MM")
      ->check(cli::positive());
  app.add_flag("--led", a.led, "one point per frame (no scale: the result is in arbitrary units)");
  app.add_option_function<std::string>(
         "--scale-from", [&a](const std::string& t) { a.options.scale_from = scale_from(t); },
         "--led: the scale from the distance of cameras A and B's centres")
      ->option_text("A,B,MM");
  cli::add_checked(app, "--wand-targets", w.targets, "N", cli::whole_in(2, 3),
                   "2 or 3 (default 3)");
  cli::add_checked(app, "--wand-ratio", w.middle_ratio, "R", cli::finite(),
                   "middle target's distance from end A / length (default 0.4)");
  app.add_option_function<std::string>(
         "--wand-ends",
         [&w](const std::string& t) {
           w.ends = t == "size" ? calibration::EndIdentity::kSize
                                : calibration::EndIdentity::kContinuity;
         },
         "how a 2-target (or symmetric) wand's ends are told apart\n"
         "(default continuity: the upper spot starts as end A)")
      ->option_text("size|continuity")
      ->check(cli::one_of({"size", "continuity"}));
  cli::add_checked(app, "--wand-sigma", a.options.wand_sigma_mm, "MM", cli::finite(),
                   "standard deviation of a wand distance (0.2)");
}

void add_camera_options(CLI::App& app, CalibrateArgs& a) {
  auto& o = a.options;
  cli::add_checked(app, "--pixel-size", o.pixel_size_mm, "MM", cli::positive(),
                   "the sensors' pixel pitch (default 0.005, nominal)");
  app.add_option_function<std::string>(
         "--image-size", [&a](const std::string& t) { a.image_size = image_size(t); },
         "the image size of cameras the source gives none for (csv:)")
      ->option_text("WxH");
  cli::add_checked(app, "--fov", o.field_of_view_deg, "DEG", cli::finite(),
                   "horizontal field of view for the start value of c, tried first\n(default 60)");
  app.add_option_function<std::string>(
         "--start-fovs",
         [&o](const std::string& t) { o.start_fields_of_view_deg = number_list(t); },
         "the fields of view the start is also searched from, each run on\n"
         "200 frames, the best (plausible, lowest median residual) kept\n"
         "(default 40,50,60,70,80,90,100; none: --fov alone)")
      ->option_text("LIST");
  app.add_option_function<double>(
         "--principal-point-sigma", [&o](double s) { o.principal_point_sigma_share = s; },
         "the principal point is observed at the image centre with\n"
         "S x the sensor width as its sigma (default 0.03 with --led, none\n"
         "with a wand; 0: no prior, e.g. for images cropped off-centre)")
      ->option_text("S")
      ->check(cli::non_negative());
  app.add_option_function<std::string>(
         "--interior", [&o](const std::string& t) { o.free_interior = interior_list(t); },
         "interior values that may be estimated, of c,xp,yp,k1,k2,k3,p1,p2,\n"
         "sc,sh (default c,xp,yp,k1,k2,k3,p1,p2; --led without k3)")
      ->option_text("LIST");
  app.add_flag("--shared-interior", o.shared_interior,
               "one interior orientation for all cameras (identical cameras and\n"
               "lenses; their image and pixel sizes must agree)");
}

void add_adjustment_options(CLI::App& app, CalibrateArgs& a) {
  auto& o = a.options;
  app.add_option_function<std::string>(
         "--model", [&o](const std::string& t) { o.select_model = t == "auto"; },
         "auto (default with --led): the base model (c, xp, yp, k1, k2 of\n"
         "--interior) first, then each further group (p1+p2, k3, sc, sh) only\n"
         "where it improves the fit significantly, is significant and not too\n"
         "correlated; all (default with a wand): every --interior value")
      ->option_text("auto|all")
      ->check(cli::one_of({"auto", "all"}));
  cli::add_checked(app, "--sigma-px", o.sigma_px, "PX", cli::finite(),
                   "a priori standard deviation of a measured coordinate (0.1)");
  cli::add_checked(app, "--critical-w", o.critical_snooping, "W", cli::finite(),
                   "data snooping's critical value (3.29)");
  cli::add_checked(app, "--check-share", o.check_point_share, "S", cli::number_in(0, 0.5),
                   "share of the frames held out and predicted as check points\n"
                   "(default 0.1; 0: none)");
  cli::add_checked(app, "--max-frames", o.max_frames, "N", cli::whole_in(1, 1'000'000'000),
                   "use at most N frames (N >= 1), evenly spread (default all)");
  cli::add_checked(app, "--bootstrap", o.bootstrap_samples, "N", cli::whole_in(0, 1'000'000),
                   "also the interior sigmas of N re-adjustments of simulated\n"
                   "measurements (a parametric bootstrap: honest in weak networks;\n"
                   "default 0)");
  cli::add_checked(app, "--stretches", o.covariance_stretches, "N", cli::whole_in(0, 100'000),
                   "sigmas also from the scatter over N stretches of the recording,\n"
                   "the larger of that and the linearised each: systematic errors\n"
                   "along the recording (default 30; 0: not from those)");
  cli::add_checked(app, "--cells", o.covariance_cells, "N", cli::whole_in(0, 1'000),
                   "sigmas also from the scatter over the cells of an N-wide grid on\n"
                   "each image: systematic errors by place in the image (default 8;\n"
                   "0: not from those)");
}

// The checks that span options, after parsing.
void check_args(CalibrateArgs& a) {
  if (a.led == a.wand_length.has_value())
    throw CLI::ValidationError("give exactly one of --wand-length-mm MM and --led");
  a.options.wand.led = a.led;
  if (a.wand_length) a.options.wand.length_mm = *a.wand_length;
}

// Parses into `a`; an exit status when the run is over already (help, usage error).
std::optional<int> parse_args(std::span<const std::string> args, CalibrateArgs& a,
                              std::ostream& out, std::ostream& err) {
  cli::App app("syncap calibrate", kDescription, kFooter);
  app.deprecated_name("--cameras", "--camera-ids");
  app.deprecated_name("--out", "--out-dir");
  app.deprecated_name("--idle-timeout", "--idle-timeout-s");
  app.deprecated_name("--wand-length", "--wand-length-mm");
  app.get_formatter()->column_width(34);
  add_source_options(app, a);
  add_wand_options(app, a);
  add_camera_options(app, a);
  add_adjustment_options(app, a);
  return cli::parse(app, args, out, err, [&a] { check_args(a); });
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
    io::LcmLogReader scan(in);
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
  io::LcmLogReader reader(in);
  long undecodable = 0;
  // A malformed record (the decoder throws on a negative array length) is skipped and named;
  // the records around it are kept.
  const auto decode = [&](const io::LogEvent& event, auto& msg) {
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
  for (const io::LogError& e : reader.take_errors())
    err << kPrefix << file << ": " << e.message << '\n';
  for (const std::string& p : collector.problems()) err << kPrefix << p << '\n';
  return collector.finish();
}

calibration::Observations read_live(const std::string& url, const CalibrateArgs& a,
                                    std::ostream& err, bool progress) {
  if (a.cameras.empty()) throw UsageError{"lcm: needs --camera-ids (the ids to wait for)"};
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
  {
    const StopRequest stop;
    if (progress) err << kPrefix << "listening on " << url << " (Ctrl-C ends the collection)\n";
    long reported = 0;
    while (!stop.requested()) {
      lcm.handleTimeout(100);
      if (a.frames > 0 && collector.frame_groups() >= a.frames) break;
      if (past_range) break;
      if (last_blob &&
          Clock::now() - *last_blob > std::chrono::duration<double>(a.idle_timeout_s)) {
        break;
      }
      if (progress && collector.frame_groups() >= reported + 30) {
        reported = collector.frame_groups();
        err << kPrefix << reported << " frame groups\n";
      }
    }
  }
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
  if (is_board_calibration(args)) return board_calibrate_command(args, out, err);
  CalibrateArgs a;
  if (const auto status = parse_args(args, a, out, err)) return *status;
  // Checked before the input is read: a calibration can take minutes.
  if (const std::string problem = unwritable_folder(a.out); !problem.empty()) {
    err << kPrefix << "--out-dir " << a.out << ": " << problem << '\n';
    return kExitUsage;
  }
  const bool progress = !a.quiet;
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
