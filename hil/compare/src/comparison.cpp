#include "comparison.hpp"

#include <cstdio>

#include "matcher.hpp"
#include "silhouettes.hpp"

namespace syncap::compare {
namespace {

// Two decimals more than the summary's tables, so that a failing figure never prints equal to
// its limit.
std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f%%", 100.0 * share);
  return text;
}

std::string pixels(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f px", value);
  return text;
}

void count_frames(FrameCounts& counts, const Group& g) {
  ++counts.at_host;
  counts.complete += g.complete ? 1 : 0;
}

// Truth targets, blobs, and matches counted into `tally` by the class of each target.
void tally_matching(const std::vector<TargetClass>& kinds, const Matching& m, Tally& tally) {
  for (const TargetClass kind : kinds) {
    ++(kind == TargetClass::counted ? tally.counted : tally.border).targets;
  }
  for (const Match& match : m.matches) {
    Detection& d = kinds[match.target] == TargetClass::counted ? tally.counted : tally.border;
    ++d.matched;
    d.errors.add(match.error);
  }
  tally.false_blobs += static_cast<long>(m.unmatched_blobs.size());
}

// The camera's silhouette against the true mask of the frame, when the truth has one.
SilhouetteTally compare_silhouette(const Truth& truth, long frame, int camera,
                                   const CameraBlobs& received) {
  SilhouetteTally tally;
  const auto image = truth.images.find(camera);
  if (image == truth.images.end()) return tally;
  const auto true_mask = read_truth_mask(truth.dir, frame, camera, image->second);
  if (!true_mask) return tally;
  ++tally.expected;
  if (!received.silhouette) return tally;
  ++tally.received;
  const cv::Mat mask = silhouette_mask(*received.silhouette, image->second);
  if (const auto iou = intersection_over_union(mask, *true_mask)) tally.iou.add(*iou);
  if (const int true_area = cv::countNonZero(*true_mask); true_area > 0)
    tally.area_ratio.add(static_cast<double>(cv::countNonZero(mask)) / true_area);
  return tally;
}

void compare_group(const Truth& truth, const Group& g, const std::string& phase_type,
                   Report& report) {
  static const std::vector<Projection> kNoTargets;
  for (const auto& [id, image] : truth.images) {
    if (!g.cameras.contains(id)) ++report.cameras[id].groups_without;
  }
  for (const auto& [id, camera] : g.cameras) {
    const auto targets = truth.projections.find({g.frame, id});
    const auto image = truth.images.find(id);
    // A camera the truth does not know has no targets: all its blobs are false.
    const Tally tally = compare_camera_frame(
        targets == truth.projections.end() ? kNoTargets : targets->second, camera.blobs,
        image == truth.images.end() ? ImageSize{} : image->second,
        report.thresholds.match_radius_px);
    CameraReport& c = report.cameras[id];
    ++c.groups_with;
    c.tally += tally;
    c.processing_us.add(camera.processing_us);
    report.phases[phase_type].tally += tally;
    report.overall.tally += tally;
    const SilhouetteTally silhouettes = compare_silhouette(truth, g.frame, id, camera);
    c.silhouettes += silhouettes;
    report.phases[phase_type].silhouettes += silhouettes;
    report.overall.silhouettes += silhouettes;
  }
}

void judge_frames(Report& r) {
  const FrameCounts& f = r.overall.frames;
  const double share = f.complete_share();
  if (share < r.thresholds.min_frames) {
    r.failures.push_back("frames: " + std::to_string(f.complete) + "/" + std::to_string(f.truth) +
                         " complete groups (" + percent(share) + " < " +
                         percent(r.thresholds.min_frames) + ")");
  }
}

void judge_silhouettes(const std::string& name, const SilhouetteTally& s, Report& r) {
  if (const auto iou = s.iou.mean(); iou && *iou < r.thresholds.min_iou) {
    r.failures.push_back(name + "silhouette IoU " + percent(*iou) + " < " +
                         percent(r.thresholds.min_iou));
  }
  if (!r.thresholds.require_silhouettes || s.expected == 0) return;
  const double share = static_cast<double>(s.received) / static_cast<double>(s.expected);
  if (share < r.thresholds.min_frames) {
    r.failures.push_back(name + "silhouettes in " + std::to_string(s.received) + "/" +
                         std::to_string(s.expected) + " frames with a true mask (" +
                         percent(share) + " < " + percent(r.thresholds.min_frames) + ")");
  }
}

void judge_camera(int id, const CameraReport& c, Report& r) {
  const std::string name = "camera " + std::to_string(id) + ": ";
  if (const auto rate = c.tally.counted.rate(); rate && *rate < r.thresholds.min_detection) {
    r.failures.push_back(name + "detection " + percent(*rate) + " < " +
                         percent(r.thresholds.min_detection));
  }
  if (const auto rms = c.tally.counted.errors.rms(); rms && *rms > r.thresholds.max_rms_px) {
    r.failures.push_back(name + "RMS " + pixels(*rms) + " > " + pixels(r.thresholds.max_rms_px));
  }
  judge_silhouettes(name, c.silhouettes, r);
}

}  // namespace

Tally compare_camera_frame(const std::vector<Projection>& targets, const std::vector<Blob>& blobs,
                           const ImageSize& image, double match_radius_px) {
  Tally tally;
  std::vector<Eigen::Vector2d> blob_points;
  for (const Blob& b : blobs) blob_points.emplace_back(b.x, b.y);
  std::vector<std::size_t> visible;  // indices into targets, in the matching's target order
  const Matching m = match_visible(targets, blob_points, match_radius_px, visible);
  std::vector<TargetClass> kinds;  // of the visible targets, in the same order
  for (const std::size_t i : visible) kinds.push_back(classify(targets[i], image));
  tally.hidden = static_cast<long>(targets.size() - visible.size());
  tally.blobs = static_cast<long>(blobs.size());
  tally_matching(kinds, m, tally);
  return tally;
}

Report compare(const Truth& truth, const std::vector<Group>& groups, const Thresholds& thresholds) {
  Report report;
  report.thresholds = thresholds;
  for (const auto& [number, f] : truth.frames) {
    ++report.overall.frames.truth;
    auto [phase, added] = report.phases.try_emplace(f.phase_type);
    if (added) report.phase_types.push_back(f.phase_type);
    ++phase->second.frames.truth;
  }
  for (const auto& [id, image] : truth.images) report.cameras[id];
  for (const Group& g : groups) {
    const auto f = truth.frames.find(g.frame);
    if (f == truth.frames.end()) {
      ++report.groups_outside_truth;
      continue;
    }
    count_frames(report.overall.frames, g);
    count_frames(report.phases[f->second.phase_type].frames, g);
    compare_group(truth, g, f->second.phase_type, report);
  }
  judge_frames(report);
  for (const auto& [id, camera] : report.cameras) judge_camera(id, camera, report);
  return report;
}

}  // namespace syncap::compare
