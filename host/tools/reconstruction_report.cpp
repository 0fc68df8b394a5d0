#include "reconstruction_report.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hull/reprojection.hpp"
#include "util/html_escape.hpp"
#include "util/printf_string.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;
using util::printf_string;

// A view whose mask agrees with the others' hull below this (median over the frames) has a false
// or missing region the others do not share (a shadow, a moved chair, a limb cut), or a camera
// the calibration has wrong; on a studio recording with good masks views reach 0.97-0.99.
constexpr double kMinViewIou = 0.9;
// A person's hull, standing or seated, is this tall (mm); outside it the calibration's scale or
// the masks are wrong.
constexpr double kMinHeightMm = 800, kMaxHeightMm = 2300;
// A hull clipped to the capture volume stands on its floor within this (mm): more is a hull
// floating (feet lost in every view), less cannot be (the clip).
constexpr double kMaxFloorGapMm = 50;
// Below these shares of the frames the run did not reconstruct the recording.
constexpr double kMinHullShare = 0.9, kMinBodyShare = 0.5;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

std::vector<ViewAgreement> view_agreements(const std::vector<FrameFigures>& frames) {
  std::map<int, std::vector<double>> by_camera;
  for (const FrameFigures& f : frames)
    for (const auto& [id, iou] : f.view_iou) by_camera[id].push_back(iou);
  std::vector<ViewAgreement> views;
  for (const auto& [id, ious] : by_camera)
    views.push_back({id, median(ious), *std::min_element(ious.begin(), ious.end()),
                     static_cast<int>(ious.size())});
  return views;
}

void add_warnings(const ReportInputs& in, ReportFigures& f) {
  const double fed = static_cast<double>(std::max<int64_t>(in.frames_fed, 1));
  if (in.quality && !in.quality->verdict.empty() && in.quality->verdict != "good")
    f.warnings.push_back("the calibration's verdict is " + in.quality->verdict +
                         (in.quality->verdict_reasons.empty()
                              ? std::string()
                              : ": " + in.quality->verdict_reasons.front()));
  if (static_cast<double>(f.hulls) < kMinHullShare * fed)
    f.warnings.push_back(printf_string("hulls for %ld of %lld frames", f.hulls,
                                       static_cast<long long>(in.frames_fed)));
  for (const ViewAgreement& v : f.views)
    if (v.median_iou < kMinViewIou)
      f.warnings.push_back(printf_string(
          "camera %d's masks agree with the other views' hull at a median IoU of %.3f (%.2f "
          "wanted): false regions in its masks (shadows, moved objects) or its camera is off",
          v.camera_id, v.median_iou, kMinViewIou));
  if (f.hulls > 0 && (f.median_height_mm < kMinHeightMm || f.median_height_mm > kMaxHeightMm))
    f.warnings.push_back(printf_string(
        "the hull is %.2f m tall (median): no person stands or sits so (the calibration's "
        "units? the masks?)",
        f.median_height_mm * 1e-3));
  if (!in.floor_z_mm && f.hulls > 0)
    f.warnings.push_back(
        "no floor given (--volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX, ZMIN the floor): hulls reach "
        "below the floor where the cameras cannot see between the feet and the ground");
  if (f.median_floor_gap_mm && *f.median_floor_gap_mm > kMaxFloorGapMm)
    f.warnings.push_back(printf_string(
        "the hulls' lowest point is %.0f mm above the floor (median): the feet are missing "
        "from the masks, or the floor is not at ZMIN",
        *f.median_floor_gap_mm));
  if (in.body_fitted && f.hulls > 0 &&
      static_cast<double>(f.bodies) < kMinBodyShare * static_cast<double>(f.hulls))
    f.warnings.push_back(
        printf_string("the body was fitted on %ld of %ld hulls", f.bodies, f.hulls));
}

// The frame with its mask's outline (green) and the hull's reprojection's (red).
cv::Mat overlay(const ViewPicture& p, const std::optional<hull::Mesh>& mesh,
                const std::vector<sensor::CameraModel>& cameras) {
  cv::Mat picture;
  if (p.image.channels() == 1)
    cv::cvtColor(p.image, picture, cv::COLOR_GRAY2BGR);
  else
    picture = p.image.clone();
  const auto draw = [&picture](const cv::Mat& mask, const cv::Scalar& colour, int thickness) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask.clone(), contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
    cv::drawContours(picture, contours, -1, colour, thickness, cv::LINE_8);
  };
  // The mask's outline wider, so that it shows beside the hull's where the two agree.
  draw(p.mask, {0, 220, 0}, 3);
  const auto camera =
      std::find_if(cameras.begin(), cameras.end(),
                   [&p](const sensor::CameraModel& c) { return c.id == p.camera_id; });
  if (mesh && camera != cameras.end()) draw(hull::render_mask(*mesh, *camera), {0, 0, 255}, 1);
  return picture;
}

void write_calibration(std::ostream& html, const ReportInputs& in) {
  html << "<h2>Calibration</h2>\n<p>" << util::html_escaped(in.calibration_file) << ": "
       << in.cameras.size() << " cameras";
  if (in.quality) {
    html << printf_string(", RMS %.3f px", in.quality->rms_px);
    if (!in.quality->verdict.empty()) html << ", verdict <b>" << in.quality->verdict << "</b>";
  }
  html << "</p>\n";
  if (in.quality) {
    html << "<ul>\n";
    for (const std::string& r : in.quality->verdict_reasons)
      html << "<li>" << util::html_escaped(r) << "</li>\n";
    for (const auto& [id, rms] : in.quality->per_camera_rms_px)
      html << printf_string("<li>camera %d: RMS %.3f px</li>\n", id, rms);
    html << "</ul>\n";
  }
}

void write_views(std::ostream& html, const ReportInputs& in, const ReportFigures& f) {
  html << "<h2>Views</h2>\n<p>Each view's mask against the hull of all views reprojected into "
          "it (IoU; a false region in one view is carved away by the others).</p>\n"
          "<table border=1 cellpadding=4><tr><th>camera</th><th>IoU median</th><th>min</th>"
          "<th>frames</th></tr>\n";
  for (const ViewAgreement& v : f.views)
    html << printf_string("<tr><td>%d</td><td>%.3f</td><td>%.3f</td><td>%d</td></tr>\n",
                          v.camera_id, v.median_iou, v.min_iou, v.frames);
  html << "</table>\n<ul>\n";
  for (const std::string& a : in.alignments) html << "<li>" << util::html_escaped(a) << "</li>\n";
  for (const std::string& n : in.notes) html << "<li>" << util::html_escaped(n) << "</li>\n";
  html << "</ul>\n";
  if (in.picture_frame >= 0) {
    html << "<p>Frame " << in.picture_frame
         << ": the mask's outline in green, the hull's reprojection in red.</p>\n<p>";
    for (const ViewPicture& p : in.pictures)
      html << "<img src=\"report/cam" << p.camera_id << ".png\" alt=\"camera " << p.camera_id
           << "\" width=\"45%\"> ";
    html << "</p>\n";
  }
}

}  // namespace

void FrameFiguresStage::process(pipeline::FrameWork& work) {
  FrameFigures f;
  f.frame = work.group.frame_number;
  if (work.hull && work.hull->faces > 0) {
    f.hull = true;
    f.view_iou = work.hull->view_iou;
    f.min_mm = work.hull->min_mm;
    f.max_mm = work.hull->max_mm;
  }
  if (work.body && !work.body->parameters.empty()) {
    f.body = true;
    f.body_rms_mm = work.body->rms_mm;
  }
  frames_.push_back(std::move(f));
}

ReportFigures summarise(const ReportInputs& in) {
  ReportFigures f;
  std::vector<double> heights, gaps;
  for (const FrameFigures& frame : in.frames) {
    if (frame.body) ++f.bodies;
    if (!frame.hull) continue;
    ++f.hulls;
    heights.push_back(frame.max_mm.z() - frame.min_mm.z());
    if (in.floor_z_mm) gaps.push_back(frame.min_mm.z() - *in.floor_z_mm);
  }
  f.views = view_agreements(in.frames);
  f.median_height_mm = median(heights);
  if (!gaps.empty()) f.median_floor_gap_mm = median(gaps);
  add_warnings(in, f);
  return f;
}

std::string summary_lines(const ReportFigures& f) {
  std::string text = printf_string("hulls %ld, bodies %ld; hull height %.3f m (median)", f.hulls,
                                   f.bodies, f.median_height_mm * 1e-3);
  if (f.median_floor_gap_mm)
    text += printf_string(", lowest point %.0f mm above the floor", *f.median_floor_gap_mm);
  text += "\nviews (mask against the others' hull, IoU):";
  for (const ViewAgreement& v : f.views)
    text +=
        printf_string(" camera %d median %.3f (min %.3f)", v.camera_id, v.median_iou, v.min_iou);
  text += '\n';
  for (const std::string& w : f.warnings) text += "warning: " + w + '\n';
  return text;
}

void write_report(const fs::path& dir, const ReportInputs& in, const ReportFigures& f) {
  fs::create_directories(dir / "report");
  for (const ViewPicture& p : in.pictures) {
    const fs::path file = dir / "report" / ("cam" + std::to_string(p.camera_id) + ".png");
    if (!cv::imwrite(file.string(), overlay(p, in.picture_hull, in.cameras)))
      throw std::runtime_error("cannot write " + file.string());
  }
  const fs::path file = dir / "report.html";
  std::ofstream html(file);
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>syncap reconstruct"
          "</title></head><body>\n<h1>syncap reconstruct</h1>\n<p><code>"
       << util::html_escaped(in.command_line) << "</code></p>\n<h2>Verdict</h2>\n";
  if (f.warnings.empty()) html << "<p>Nothing implausible found.</p>\n";
  html << "<ul>\n";
  for (const std::string& w : f.warnings)
    html << "<li><b>warning</b>: " << util::html_escaped(w) << "</li>\n";
  html << "</ul>\n";
  write_calibration(html, in);
  write_views(html, in, f);
  html << printf_string(
      "<h2>Hull and body</h2>\n<p>%lld frames, %ld hulls, %ld bodies; hull height %.3f m "
      "(median)",
      static_cast<long long>(in.frames_fed), f.hulls, f.bodies, f.median_height_mm * 1e-3);
  if (f.median_floor_gap_mm)
    html << printf_string(", lowest point %.0f mm above the floor (median)",
                          *f.median_floor_gap_mm);
  html << "</p>\n<pre>" << util::html_escaped(in.hull_summary + in.body_summary) << "</pre>\n"
       << printf_string(
              "<h2>Time</h2>\n<p>%.1f s in all, %.1f ms a frame; masking %.1f ms a "
              "camera and frame</p>\n",
              in.wall_s, 1e3 * in.wall_s / static_cast<double>(std::max<int64_t>(in.frames_fed, 1)),
              in.mask_ms_per_frame)
       << "<h2>Files</h2>\n<ul>\n";
  for (const std::string& name : in.files)
    html << "<li><a href=\"" << util::html_escaped(name) << "\">" << util::html_escaped(name)
         << "</a></li>\n";
  html << "</ul>\n</body></html>\n";
  if (!html) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace syncap::tools
