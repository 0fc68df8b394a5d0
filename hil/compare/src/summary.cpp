#include "summary.hpp"
#include "util/printf_string.hpp"

#include <cstdio>
#include <optional>

namespace syncap::compare {
namespace {

using nlohmann::ordered_json;

using util::printf_string;

// A number right-aligned in `width` columns after a space, or "-" when there is none.
std::string cell(std::optional<double> value, int width, int decimals, bool sign = false) {
  if (!value) return printf_string(" %*s", width, "-");
  return sign ? printf_string(" %+*.*f", width, decimals, *value)
              : printf_string(" %*.*f", width, decimals, *value);
}

std::string percent_cell(std::optional<double> share) {
  if (!share) return printf_string(" %7s", "-");
  return printf_string(" %6.1f%%", 100.0 * *share);
}

// The target columns both tables share; every cell starts with a space, so that wide numbers
// never run into each other.
const char* const kTallyHeader =
    " targets matched  detect   false   rms_px   max_px   bias_x   bias_y    border  brd_rms "
    "hidden";

std::string tally_cells(const Tally& t) {
  const Detection& c = t.counted;
  const auto bias = c.errors.bias();
  const std::string border =
      std::to_string(t.border.matched) + "/" + std::to_string(t.border.targets);
  return printf_string(" %7ld %7ld", c.targets, c.matched) + percent_cell(c.rate()) +
         printf_string(" %7ld", t.false_blobs) + cell(c.errors.rms(), 8, 4) +
         cell(c.errors.max(), 8, 4) +
         cell(bias ? std::optional(bias->x()) : std::nullopt, 8, 4, true) +
         cell(bias ? std::optional(bias->y()) : std::nullopt, 8, 4, true) +
         printf_string(" %9s", border.c_str()) + cell(t.border.errors.rms(), 8, 4) +
         printf_string(" %6ld", t.hidden);
}

std::string camera_table(const Report& r) {
  std::string out = "per camera (targets: visible, disc wholly inside the image):\n";
  out += printf_string("  %-6s %7s %7s %8s", "camera", "groups", "missing", "proc_us") +
         kTallyHeader + "\n";
  for (const auto& [id, c] : r.cameras) {
    out += printf_string("  %-6d %7ld %7ld", id, c.groups_with, c.groups_without) +
           cell(c.processing_us.mean(), 8, 1) + tally_cells(c.tally) + "\n";
  }
  return out;
}

std::string phase_row(const std::string& name, const PhaseReport& p) {
  return printf_string("  %-6s %7ld %7ld %8ld", name.c_str(), p.frames.truth, p.frames.at_host,
                       p.frames.complete) +
         tally_cells(p.tally) + "\n";
}

std::string phase_table(const Report& r) {
  std::string out = "per phase type (all cameras):\n";
  out += printf_string("  %-6s %7s %7s %8s", "phase", "frames", "at_host", "complete") +
         kTallyHeader + "\n";
  for (const std::string& type : r.phase_types) out += phase_row(type, r.phases.at(type));
  return out + phase_row("all", r.overall);
}

// Only when the truth has masks (person phases).
std::string silhouette_table(const Report& r) {
  if (r.overall.silhouettes.expected == 0) return "";
  std::string out =
      "silhouettes (frames with a true mask; IoU against it; area: the silhouette's over the "
      "true mask's, mean):\n";
  out += printf_string("  %-6s %8s %8s %8s %8s %8s %8s\n", "camera", "masks", "received",
                       "iou_mean", "iou_min", "iou_max", "area");
  auto row = [](const std::string& name, const SilhouetteTally& s) {
    return printf_string("  %-6s %8ld %8ld", name.c_str(), s.expected, s.received) +
           cell(s.iou.mean(), 8, 4) + cell(s.iou.min(), 8, 4) + cell(s.iou.max(), 8, 4) +
           cell(s.area_ratio.mean(), 8, 4) + "\n";
  };
  for (const auto& [id, c] : r.cameras) out += row(std::to_string(id), c.silhouettes);
  return out + row("all", r.overall.silhouettes);
}

std::string frames_line(const Report& r) {
  const FrameCounts& f = r.overall.frames;
  return printf_string("frames: %ld/%ld truth frames at the host, %ld complete (%.1f%%)", f.at_host,
                       f.truth, f.complete, 100.0 * f.complete_share()) +
         (r.groups_outside_truth
              ? printf_string("; %ld groups for frames outside the truth", r.groups_outside_truth)
              : std::string()) +
         "\n";
}

std::string thresholds_line(const Thresholds& t) {
  return printf_string(
      "limits: RMS <= %.3f px and detection >= %.1f%% per camera, complete frames >= %.1f%%, "
      "match radius %.2f px, silhouette IoU >= %.3f%s\n",
      t.max_rms_px, 100.0 * t.min_detection, 100.0 * t.min_frames, t.match_radius_px, t.min_iou,
      t.require_silhouettes ? " (silhouettes required)" : "");
}

ordered_json optional_json(std::optional<double> value) {
  return value ? ordered_json(*value) : ordered_json(nullptr);
}

ordered_json detection_json(const Detection& d) {
  const auto bias = d.errors.bias();
  return {{"targets", d.targets},
          {"matched", d.matched},
          {"detection", optional_json(d.rate())},
          {"rms_px", optional_json(d.errors.rms())},
          {"max_px", optional_json(d.errors.max())},
          {"bias_x_px", bias ? ordered_json(bias->x()) : ordered_json(nullptr)},
          {"bias_y_px", bias ? ordered_json(bias->y()) : ordered_json(nullptr)}};
}

ordered_json tally_json(const Tally& t) {
  return {{"counted", detection_json(t.counted)},
          {"border", detection_json(t.border)},
          {"hidden", t.hidden},
          {"blobs", t.blobs},
          {"false_blobs", t.false_blobs}};
}

ordered_json frames_json(const FrameCounts& f) {
  return {{"truth", f.truth}, {"at_host", f.at_host}, {"complete", f.complete}};
}

ordered_json silhouettes_json(const SilhouetteTally& s) {
  return {{"expected", s.expected},
          {"received", s.received},
          {"iou_mean", optional_json(s.iou.mean())},
          {"iou_min", optional_json(s.iou.min())},
          {"iou_max", optional_json(s.iou.max())},
          {"area_ratio_mean", optional_json(s.area_ratio.mean())}};
}

ordered_json camera_json(int id, const CameraReport& c) {
  ordered_json j{{"id", id},
                 {"groups_with", c.groups_with},
                 {"groups_without", c.groups_without},
                 {"processing_us_mean", optional_json(c.processing_us.mean())},
                 {"processing_us_max", optional_json(c.processing_us.max())}};
  j.update(tally_json(c.tally));
  j["silhouettes"] = silhouettes_json(c.silhouettes);
  return j;
}

ordered_json phase_json(const std::string& type, const PhaseReport& p) {
  ordered_json j{{"type", type}, {"frames", frames_json(p.frames)}};
  j.update(tally_json(p.tally));
  j["silhouettes"] = silhouettes_json(p.silhouettes);
  return j;
}

}  // namespace

std::string verdict_line(const Report& report) {
  if (report.pass()) return "PASS";
  std::string line = "FAIL: ";
  for (std::size_t i = 0; i < report.failures.size(); ++i) {
    line += (i ? "; " : "") + report.failures[i];
  }
  return line;
}

std::string format_summary(const Report& report, const std::string& heading) {
  return heading + "\n" + thresholds_line(report.thresholds) + frames_line(report) +
         camera_table(report) + phase_table(report) + silhouette_table(report) +
         verdict_line(report) + "\n";
}

ordered_json report_json(const Report& r) {
  const Thresholds& t = r.thresholds;
  ordered_json j{{"pass", r.pass()},
                 {"failures", r.failures},
                 {"thresholds",
                  {{"max_rms_px", t.max_rms_px},
                   {"min_detection", t.min_detection},
                   {"match_radius_px", t.match_radius_px},
                   {"min_frames", t.min_frames},
                   {"min_iou", t.min_iou},
                   {"require_silhouettes", t.require_silhouettes}}},
                 {"frames", frames_json(r.overall.frames)},
                 {"groups_outside_truth", r.groups_outside_truth}};
  j["cameras"] = ordered_json::array();
  for (const auto& [id, c] : r.cameras) j["cameras"].push_back(camera_json(id, c));
  j["phases"] = ordered_json::array();
  for (const std::string& type : r.phase_types) {
    j["phases"].push_back(phase_json(type, r.phases.at(type)));
  }
  j["overall"] = tally_json(r.overall.tally);
  j["overall"]["silhouettes"] = silhouettes_json(r.overall.silhouettes);
  return j;
}

}  // namespace syncap::compare
