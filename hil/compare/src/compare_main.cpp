// syncap-hil-compare: what the system produced (the host's frame groups) against the simulator's
// ground truth; prints a summary and PASS or FAIL: reasons (hil/compare/README.md).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "body_check.hpp"
#include "calibration_check.hpp"
#include "comparison.hpp"
#include "groups.hpp"
#include "hull_check.hpp"
#include "input_error.hpp"
#include "markers_check.hpp"
#include "sensor/camera_file.hpp"
#include "summary.hpp"
#include "syncap/cli/options.hpp"
#include "truth.hpp"

namespace {

namespace cli = syncap::cli;

// The host's 3D markers, when the groups carry them (syncap-host --calibration).
struct MarkerLimits {
  double match_radius_mm = 5;
  double min_found = 0.995;
  double max_ghosts = 0.005;
  double max_rms_mm = 0.5;
  // The 3D RMS over the best estimator's on the same whole views at most this; 0: not checked.
  double max_rms_over_reference = 0;
};

// The host's visual hulls, when --hull-meshes names their folder.
struct HullLimits {
  std::string meshes;
  double tolerance_mm = 5;
  double min_coverage = 0.99;
  double min_reference_coverage = 0.99;
  double min_view_iou = 0.9;
};

// The host's fitted body, when --body asks for it (the groups' "body" entries).
struct BodyLimits {
  bool check = false;
  double max_rms_mm = 20;
  double max_angle_deg = 4;
  long max_starts = 2;  // the first start and one restart
  // The joints' errors over their predicted sigmas, RMS, at most this (records with sigmas).
  double max_sigma_ratio = 2;
};

struct Options {
  std::string truth, groups, json, cameras;
  HullLimits hull;
  BodyLimits body;
  syncap::compare::Thresholds thresholds;
  MarkerLimits markers;
  double max_reprojection_px = 0.5;
};

constexpr const char* kDescription =
    "Compares the host's frame groups, or a calibration, with the simulator's ground truth;\n"
    "prints a summary and PASS or FAIL: reasons (hil/compare/README.md).\n"
    "usage: syncap-hil-compare --truth DIR --groups FILE [--json FILE] [thresholds]\n"
    "       syncap-hil-compare --truth DIR --calibration FILE [--max-reprojection-px 0.5]\n";

constexpr const char* kFooter =
    "Both --groups and --calibration: the groups' markers were measured through that calibration\n"
    "(syncap markers --calibration FILE); they are moved into the truth's frame by the rigid\n"
    "motion that best maps its projection centres onto the true ones (the scale is the\n"
    "calibration's own) before they are checked; both checks must pass.\n"
    "exit 0 PASS, 1 FAIL, 2 unusable inputs";

void add_group_options(CLI::App& app, Options& o) {
  auto& t = o.thresholds;
  app.add_option("--truth", o.truth, "the simulator's output: DIR/cameras.json, DIR/truth/*.csv")
      ->option_text("DIR")
      ->required();
  app.add_option("--groups", o.groups, "the host's frame groups (syncap-host --out), JSON lines")
      ->option_text("FILE");
  app.add_option("--json", o.json, "also write the figures as JSON")->option_text("FILE");
  cli::add_checked(app, "--max-rms-px", t.max_rms_px, "PX", cli::non_negative(),
                   "per camera: RMS centroid error of matched targets at most PX (0.1)");
  cli::add_checked(app, "--min-detection", t.min_detection, "SHARE", cli::number_in(0, 1),
                   "per camera: matched / visible targets in reported frames (0.98)");
  cli::add_checked(app, "--match-radius-px", t.match_radius_px, "PX", cli::non_negative(),
                   "a blob matches the nearest free target within PX (3)");
  cli::add_checked(app, "--min-frames", t.min_frames, "SHARE", cli::number_in(0, 1),
                   "complete groups / truth frames (0.99)");
  cli::add_checked(app, "--min-iou", t.min_iou, "SHARE", cli::number_in(0, 1),
                   "per camera: mean IoU of its silhouettes against the true masks (0.95)");
  app.add_flag("--require-silhouettes", t.require_silhouettes,
               "per camera: a silhouette in min-frames of the frames with a mask");
}

void add_marker_options(CLI::App& app, MarkerLimits& m) {
  const std::string group =
      "When the groups carry 3D markers (syncap-host --calibration), against truth/targets.csv";
  cli::add_checked(app, "--marker-radius-mm", m.match_radius_mm, "MM", cli::non_negative(),
                   "a marker finds the nearest free true target within MM (5)")
      ->group(group);
  cli::add_checked(app, "--min-markers-found", m.min_found, "SHARE", cli::non_negative(),
                   "found / targets seen by two or more cameras (0.995)")
      ->group(group);
  cli::add_checked(app, "--max-ghosts", m.max_ghosts, "SHARE", cli::non_negative(),
                   "markers near no target / markers (0.005)")
      ->group(group);
  cli::add_checked(app, "--max-marker-rms-mm", m.max_rms_mm, "MM", cli::non_negative(),
                   "3D RMS error of the found markers (0.5)")
      ->group(group);
  cli::add_checked(app, "--max-rms-over-reference", m.max_rms_over_reference, "R",
                   cli::non_negative(),
                   "3D RMS / the best estimator's on the same whole views and targets\n"
                   "(hil/compare/README.md) at most R (0: not checked)")
      ->group(group);
}

void add_hull_options(CLI::App& app, HullLimits& h) {
  const std::string group =
      "The host's visual hulls (syncap-host --hull), against truth/body.jsonl";
  app.add_option("--hull-meshes", h.meshes, "the hulls' meshes (syncap-host --hull-meshes DIR)")
      ->option_text("DIR")
      ->group(group);
  cli::add_checked(app, "--hull-tolerance-mm", h.tolerance_mm, "MM", cli::non_negative(),
                   "a body point outside a hull counts as covered within MM of it (5)")
      ->group(group);
  cli::add_checked(app, "--min-hull-coverage", h.min_coverage, "SHARE", cli::number_in(0, 1),
                   "covered / body surface points (0.99)")
      ->group(group);
  cli::add_checked(app, "--min-hull-reference-coverage", h.min_reference_coverage, "SHARE",
                   cli::number_in(0, 1),
                   "the same for the hulls of the true masks: the method's check (0.99)")
      ->group(group);
  cli::add_checked(app, "--min-hull-iou", h.min_view_iou, "SHARE", cli::number_in(0, 1),
                   "the worst view's reprojection IoU against its silhouette (0.9)")
      ->group(group);
}

void add_body_options(CLI::App& app, BodyLimits& b) {
  const std::string group =
      "The host's fitted body (syncap-host --body, syncap fit), against truth/body.jsonl's joints";
  app.add_flag("--body", b.check, "check the groups' fitted bodies")->group(group);
  cli::add_checked(app, "--max-body-rms-mm", b.max_rms_mm, "MM", cli::non_negative(),
                   "joint-centre RMS over all fitted frames (20)")
      ->group(group);
  cli::add_checked(app, "--max-body-angle-deg", b.max_angle_deg, "DEG", cli::non_negative(),
                   "mean error of the hips', knees', shoulders' and elbows' angles (4)")
      ->group(group);
  app.add_option("--max-body-starts", b.max_starts,
                 "automatic starts, the first included (2: one restart)")
      ->group(group);
  cli::add_checked(app, "--max-body-sigma-ratio", b.max_sigma_ratio, "R", cli::non_negative(),
                   "the joints' errors over the fit's predicted sigmas, RMS (2; 1 is honest)")
      ->group(group);
}

void add_calibration_options(CLI::App& app, Options& o) {
  const std::string group = "A calibration against the truth";
  app.add_option("--calibration", o.cameras,
                 "a calibration (cameras.json) against DIR/cameras.json, aligned by\n"
                 "a similarity; the true targets reprojected through both")
      ->option_text("FILE")
      ->group(group);
  cli::add_checked(app, "--max-reprojection-px", o.max_reprojection_px, "PX", cli::non_negative(),
                   "RMS of that reprojection at most PX (0.5)")
      ->group(group);
}

// Parses into `o`; the exit status when the run is over already (help, usage error).
std::optional<int> parse(int argc, char** argv, Options& o) {
  cli::App app("syncap-hil-compare", kDescription, kFooter);
  app.deprecated_name("--cameras", "--calibration");
  add_group_options(app, o);
  add_marker_options(app, o.markers);
  add_calibration_options(app, o);
  add_hull_options(app, o.hull);
  add_body_options(app, o.body);
  return cli::parse_main(app, argc, argv, [&o] {
    if (o.groups.empty() && o.cameras.empty())
      throw CLI::ValidationError("--groups FILE (or --calibration FILE) is required");
  });
}

// The report's figures, and the markers' when they were checked.
void write_json(const std::string& file, const syncap::compare::Report& report,
                const std::optional<nlohmann::ordered_json>& markers) {
  auto json = syncap::compare::report_json(report);
  if (markers) json["markers"] = *markers;
  std::ofstream out(file);
  out << json.dump(2) << "\n";
  if (!out) throw syncap::compare::InputError(file + ": cannot write");
}

}  // namespace

// The rigid motion of --calibration's frame onto the truth's (its projection centres onto the true
// ones: a wand calibration's scale is metric), said for `what` is moved by it.
syncap::compare::Similarity motion_to_truth(const Options& o, const char* what) {
  const auto motion = syncap::compare::fit_to_truth(
      syncap::sensor::read_cameras(std::filesystem::path(o.truth) / "cameras.json"),
      syncap::sensor::read_cameras(o.cameras), false);
  std::cout << what << " moved into the truth's frame by the rigid motion of " << o.cameras
            << "'s projection centres onto the true ones\n";
  return motion;
}

// The host's markers against the true targets, when the groups carry them: whether within the
// limits (true when there are none) and the figures for --json.
struct MarkersResult {
  bool pass = true;
  std::optional<nlohmann::ordered_json> json;
};

MarkersResult check_markers(const Options& o, const syncap::compare::Truth& truth,
                            std::vector<syncap::compare::Group> groups) {
  const bool any = std::any_of(groups.begin(), groups.end(),
                               [](const auto& g) { return g.markers.has_value(); });
  if (!any) return {};
  if (!o.cameras.empty()) syncap::compare::move_markers(groups, motion_to_truth(o, "markers"));
  const auto positions = syncap::compare::read_true_positions(std::filesystem::path(o.truth) /
                                                              "truth" / "targets.csv");
  const auto check = syncap::compare::check_markers(
      truth, positions, groups, o.markers.match_radius_mm, o.thresholds.match_radius_px);
  std::cout << syncap::compare::format_markers_check(check);
  const MarkerLimits& m = o.markers;
  // Without a reference (no found target with two whole views) the ratio has no figure and
  // cannot fail, as a camera without counted targets cannot fail its RMS.
  const auto ratio = check.reference.ratio();
  const bool ratio_pass =
      m.max_rms_over_reference <= 0 || !ratio || *ratio <= m.max_rms_over_reference;
  const bool pass = check.found_share() >= m.min_found && check.ghost_share() <= m.max_ghosts &&
                    check.rms_mm() <= m.max_rms_mm && ratio_pass;
  std::cout << (pass ? "PASS" : "FAIL") << ": markers (found >= " << m.min_found
            << ", ghosts <= " << m.max_ghosts << ", 3D RMS <= " << m.max_rms_mm << " mm";
  if (m.max_rms_over_reference > 0)
    std::cout << ", 3D RMS / best estimator's on the same whole views <= "
              << m.max_rms_over_reference;
  std::cout << ")\n";
  auto json = syncap::compare::markers_json(check);
  json["pass"] = pass;
  json["limits"] = {{"match_radius_mm", m.match_radius_mm},
                    {"min_found", m.min_found},
                    {"max_ghosts", m.max_ghosts},
                    {"max_rms_mm", m.max_rms_mm},
                    {"max_rms_over_reference",
                     m.max_rms_over_reference > 0 ? nlohmann::ordered_json(m.max_rms_over_reference)
                                                  : nlohmann::ordered_json(nullptr)}};
  return {pass, std::move(json)};
}

// The hulls against the true body, when asked; true when within the limits. The reference (the
// true masks' hulls) checks the method: it must cover the body to --min-hull-coverage too.
bool check_hulls(const Options& o) {
  if (o.hull.meshes.empty()) return true;
  std::optional<syncap::compare::Similarity> to_truth;
  if (!o.cameras.empty()) to_truth = motion_to_truth(o, "hulls");
  const auto checks =
      syncap::compare::check_hulls(o.truth, o.groups, o.hull.meshes, o.hull.tolerance_mm, to_truth);
  std::cout << syncap::compare::format_hull_checks(checks, o.hull.tolerance_mm);
  const auto& live = checks.live;
  const double min_iou = live.view_ious.empty()
                             ? 1.0
                             : *std::min_element(live.view_ious.begin(), live.view_ious.end());
  const bool pass = live.meshes > 0 && live.failed == 0 && live.coverage() >= o.hull.min_coverage &&
                    checks.reference.coverage() >= o.hull.min_reference_coverage &&
                    min_iou >= o.hull.min_view_iou;
  std::cout << (pass ? "PASS" : "FAIL")
            << ": hull (meshes > 0, none failed, coverage >= " << o.hull.min_coverage
            << ", reference coverage >= " << o.hull.min_reference_coverage
            << ", reprojection IoU >= " << o.hull.min_view_iou << ")\n";
  return pass;
}

// The fitted body against the true joints, when asked; true when within the limits.
bool check_body(const Options& o) {
  if (!o.body.check) return true;
  std::optional<syncap::compare::Similarity> to_truth;
  if (!o.cameras.empty()) to_truth = motion_to_truth(o, "body joints");
  const auto check = syncap::compare::check_body(o.truth, o.groups, to_truth);
  std::cout << syncap::compare::format_body_check(check);
  const bool pass =
      check.fitted > 0 && check.fitted == check.frames && check.rms_mm() <= o.body.max_rms_mm &&
      check.mean_angle_error_deg() <= o.body.max_angle_deg && check.starts <= o.body.max_starts &&
      check.sigma_ratio() <= o.body.max_sigma_ratio;
  std::cout << (pass ? "PASS" : "FAIL")
            << ": body (every frame fitted, joint-centre RMS <= " << o.body.max_rms_mm
            << " mm, joint-angle error <= " << o.body.max_angle_deg
            << " deg, starts <= " << o.body.max_starts
            << ", errors / predicted sigmas <= " << o.body.max_sigma_ratio << ")\n";
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
  Options o;
  if (const auto status = parse(argc, argv, o)) return *status;
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
    const MarkersResult markers = check_markers(o, truth, groups);
    if (!o.json.empty()) write_json(o.json, report, markers.json);
    const bool markers_pass = markers.pass;
    const bool hull_pass = check_hulls(o);
    const bool body_pass = check_body(o);
    return report.pass() && markers_pass && hull_pass && body_pass && cameras_status == 0 ? 0 : 1;
  } catch (const syncap::compare::InputError& e) {
    std::cerr << "syncap-hil-compare: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // reading or aligning --calibration
    std::cerr << "syncap-hil-compare: " << e.what() << "\n";
    return 2;
  }
}
