// syncap-hil-compare: what the system produced (the host's frame groups) against the simulator's
// ground truth; prints a summary and PASS or FAIL: reasons (hil/compare/README.md).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include "calibration_check.hpp"
#include "comparison.hpp"
#include "groups.hpp"
#include "input_error.hpp"
#include "markers_check.hpp"
#include "sensor/camera_file.hpp"
#include "summary.hpp"
#include "truth.hpp"

namespace {

const char* kUsage =
    "usage: syncap-hil-compare --truth DIR --groups FILE [--json FILE] [--max-rms-px 0.1]\n"
    "                          [--min-detection 0.98] [--match-radius-px 3] [--min-frames 0.99]\n"
    "                          [--min-iou 0.95] [--require-silhouettes]\n"
    "  --truth DIR            the simulator's output: DIR/cameras.json, DIR/truth/*.csv\n"
    "  --groups FILE          the host's frame groups (syncap-host --out), JSON lines\n"
    "  --json FILE            also write the figures as JSON\n"
    "  --max-rms-px PX        per camera: RMS centroid error of matched targets at most PX\n"
    "  --min-detection SHARE  per camera: matched / visible targets in reported frames\n"
    "  --match-radius-px PX   a blob matches the nearest free target within PX\n"
    "  --min-frames SHARE     complete groups / truth frames\n"
    "  --min-iou SHARE        per camera: mean IoU of its silhouettes against the true masks\n"
    "  --require-silhouettes  per camera: a silhouette in min-frames of the frames with a mask\n"
    "  When the groups carry 3D markers (syncap-host --calibration), against truth/targets.csv:\n"
    "  --marker-radius-mm MM  a marker finds the nearest free true target within MM (5)\n"
    "  --min-markers-found SHARE  found / targets seen by two or more cameras (0.995)\n"
    "  --max-ghosts SHARE     markers near no target / markers (0.005)\n"
    "  --max-marker-rms-mm MM 3D RMS error of the found markers (0.5)\n"
    "       syncap-hil-compare --truth DIR --cameras FILE [--max-reprojection-px 0.5]\n"
    "  --cameras FILE         a calibration (cameras.json) against DIR/cameras.json, aligned by\n"
    "                         a similarity; the true targets reprojected through both\n"
    "  --max-reprojection-px PX  RMS of that reprojection at most PX\n"
    "  Both --groups and --cameras: the groups' markers were measured through that calibration\n"
    "  (syncap markers --calibration FILE); they are moved into the truth's frame by the rigid\n"
    "  motion that best maps its projection centres onto the true ones (the scale is the\n"
    "  calibration's own) before they are checked; both checks must pass.\n"
    "exit 0 PASS, 1 FAIL, 2 unusable inputs\n";

// The host's 3D markers, when the groups carry them (syncap-host --calibration).
struct MarkerLimits {
  double match_radius_mm = 5;
  double min_found = 0.995;
  double max_ghosts = 0.005;
  double max_rms_mm = 0.5;
};

struct Options {
  std::string truth, groups, json, cameras;
  syncap::compare::Thresholds thresholds;
  MarkerLimits markers;
  double max_reprojection_px = 0.5;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "syncap-hil-compare: " << message << "\n" << kUsage;
  std::exit(2);
}

double positive_number(const std::string& option, const std::string& text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value < 0) {
    usage_error(option + " '" + text + "' is not a non-negative number");
  }
  return value;
}

Options parse(int argc, char** argv) {
  Options o;
  std::map<std::string, std::string*> paths{{"--truth", &o.truth},
                                            {"--groups", &o.groups},
                                            {"--json", &o.json},
                                            {"--cameras", &o.cameras}};
  std::map<std::string, double*> numbers{{"--max-rms-px", &o.thresholds.max_rms_px},
                                         {"--min-detection", &o.thresholds.min_detection},
                                         {"--match-radius-px", &o.thresholds.match_radius_px},
                                         {"--min-frames", &o.thresholds.min_frames},
                                         {"--min-iou", &o.thresholds.min_iou},
                                         {"--max-reprojection-px", &o.max_reprojection_px},
                                         {"--marker-radius-mm", &o.markers.match_radius_mm},
                                         {"--min-markers-found", &o.markers.min_found},
                                         {"--max-ghosts", &o.markers.max_ghosts},
                                         {"--max-marker-rms-mm", &o.markers.max_rms_mm}};
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (option == "--help" || option == "-h") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (option == "--require-silhouettes") {
      o.thresholds.require_silhouettes = true;
      continue;
    }
    const auto p = paths.find(option);
    const auto n = numbers.find(option);
    // Known before its value is looked for: an unknown last option is no missing value.
    if (p == paths.end() && n == numbers.end()) usage_error("unknown option '" + option + "'");
    if (i + 1 >= argc) usage_error("option '" + option + "' needs a value");
    const std::string value = argv[++i];
    if (p != paths.end()) {
      *p->second = value;
    } else {
      *n->second = positive_number(option, value);
    }
  }
  if (o.truth.empty() || (o.groups.empty() && o.cameras.empty())) {
    usage_error("--truth and --groups (or --cameras) are required");
  }
  if (o.thresholds.min_detection > 1 || o.thresholds.min_frames > 1 || o.thresholds.min_iou > 1) {
    usage_error("--min-detection, --min-frames and --min-iou are shares from 0 to 1");
  }
  return o;
}

void write_json(const std::string& file, const syncap::compare::Report& report) {
  std::ofstream out(file);
  out << syncap::compare::report_json(report).dump(2) << "\n";
  if (!out) throw syncap::compare::InputError(file + ": cannot write");
}

}  // namespace

// The host's markers against the true targets, when the groups carry them; true when within the
// limits (or when there are none).
bool check_markers(const Options& o, const syncap::compare::Truth& truth,
                   std::vector<syncap::compare::Group> groups) {
  const bool any = std::any_of(groups.begin(), groups.end(),
                               [](const auto& g) { return g.markers.has_value(); });
  if (!any) return true;
  if (!o.cameras.empty()) {
    namespace fs = std::filesystem;
    const auto motion = syncap::compare::fit_to_truth(
        syncap::sensor::read_cameras(fs::path(o.truth) / "cameras.json"),
        syncap::sensor::read_cameras(o.cameras), false);
    syncap::compare::move_markers(groups, motion);
    std::cout << "markers moved into the truth's frame by the rigid motion of " << o.cameras
              << "'s projection centres onto the true ones\n";
  }
  const auto positions = syncap::compare::read_true_positions(std::filesystem::path(o.truth) /
                                                              "truth" / "targets.csv");
  const auto check =
      syncap::compare::check_markers(truth, positions, groups, o.markers.match_radius_mm);
  std::cout << syncap::compare::format_markers_check(check);
  const bool pass = check.found_share() >= o.markers.min_found &&
                    check.ghost_share() <= o.markers.max_ghosts &&
                    check.rms_mm() <= o.markers.max_rms_mm;
  std::cout << (pass ? "PASS" : "FAIL") << ": markers (found >= " << o.markers.min_found
            << ", ghosts <= " << o.markers.max_ghosts << ", 3D RMS <= " << o.markers.max_rms_mm
            << " mm)\n";
  return pass;
}

// The calibration check: 0 when the true targets reproject within the limit.
int check_cameras(const Options& o) {
  namespace fs = std::filesystem;
  const auto truth = syncap::sensor::read_cameras(fs::path(o.truth) / "cameras.json");
  const auto estimated = syncap::sensor::read_cameras(o.cameras);
  std::vector<Eigen::Vector3d> targets;
  for (const auto& t :
       syncap::compare::read_target_positions(fs::path(o.truth) / "truth" / "targets.csv")) {
    targets.emplace_back(t[0], t[1], t[2]);
  }
  const auto check = syncap::compare::check_calibration(truth, estimated, targets);
  std::cout << syncap::compare::format_calibration_check(check);
  if (!check.missing.empty() || check.reprojection_rms_px > o.max_reprojection_px) {
    std::cout << "FAIL: reprojection RMS " << check.reprojection_rms_px << " px (limit "
              << o.max_reprojection_px << "), " << check.missing.size()
              << " cameras not calibrated\n";
    return 1;
  }
  std::cout << "PASS\n";
  return 0;
}

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  int cameras_status = 0;
  if (!o.cameras.empty()) {
    try {
      cameras_status = check_cameras(o);
    } catch (const std::exception& e) {
      std::cerr << "syncap-hil-compare: " << e.what() << "\n";
      return 2;
    }
    if (o.groups.empty()) return cameras_status;
  }
  try {
    const auto truth = syncap::compare::read_truth(o.truth);
    const auto groups = syncap::compare::read_groups(o.groups);
    const auto report = syncap::compare::compare(truth, groups, o.thresholds);
    const std::string heading = "syncap-hil-compare: truth " + o.truth + " (" +
                                std::to_string(truth.images.size()) + " cameras, " +
                                std::to_string(truth.frames.size()) + " frames), groups " +
                                o.groups + " (" + std::to_string(groups.size()) + " lines)";
    std::cout << syncap::compare::format_summary(report, heading) << std::flush;
    if (!o.json.empty()) write_json(o.json, report);
    const bool markers_pass = check_markers(o, truth, groups);
    return report.pass() && markers_pass && cameras_status == 0 ? 0 : 1;
  } catch (const syncap::compare::InputError& e) {
    std::cerr << "syncap-hil-compare: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // reading or aligning --cameras
    std::cerr << "syncap-hil-compare: " << e.what() << "\n";
    return 2;
  }
}
