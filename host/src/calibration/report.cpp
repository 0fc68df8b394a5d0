#include "calibration/report.hpp"
#include "calibration/report_overview.hpp"
#include "util/html_escape.hpp"
#include "util/printf_string.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace syncap::calibration {
namespace {

using util::printf_string;

struct MeanSd {
  double mean = 0, sd = 0;
};

MeanSd mean_sd(const std::vector<double>& values) {
  MeanSd m;
  if (values.empty()) return m;
  m.mean = std::accumulate(values.begin(), values.end(), 0.0) / values.size();
  double sum = 0;
  for (double v : values) sum += (v - m.mean) * (v - m.mean);
  m.sd = values.size() > 1 ? std::sqrt(sum / (values.size() - 1)) : 0.0;
  return m;
}

// ---- text ------------------------------------------------------------------------------------

// "verdict: weak" and its reasons, the first thing a reader sees.
std::string text_verdict(const CalibrationReport& r) {
  if (r.verdict.empty()) return "";
  std::string out = "verdict: " + r.verdict + "\n";
  for (const std::string& reason : r.verdict_reasons) out += "  " + reason + "\n";
  return out;
}

std::string text_summary(const CalibrationReport& r) {
  std::string out = r.title + "\n" + std::string(r.title.size(), '=') + "\n";
  out += text_verdict(r);
  if (!r.input.empty()) out += "input: " + r.input + "\n";
  out += printf_string("observations %ld, unknowns %ld, redundancy %ld\n", r.observations,
                       r.unknowns, r.redundancy);
  out +=
      printf_string("sigma0 %.4f, iterations %d (%s), outliers removed %ld\n", r.sigma0,
                    r.iterations, r.converged ? "converged" : "NOT converged", r.outliers_removed);
  if (r.wand_length_mm > 0 && !r.wand_lengths_mm.empty()) {
    const MeanSd w = mean_sd(r.wand_lengths_mm);
    out += printf_string(
        "wand length: nominal %.3f mm, adjusted mean %.4f mm, sd %.4f mm (%zu frames)\n",
        r.wand_length_mm, w.mean, w.sd, r.wand_lengths_mm.size());
  }
  if (!r.check_points.empty()) out += "check points: " + r.check_points + "\n";
  if (!r.halves.empty()) out += "halves: " + r.halves + "\n";
  for (const std::string& line : r.model_selection) out += "model: " + line + "\n";
  for (const std::string& line : r.start_search) out += "start search: " + line + "\n";
  return out;
}

std::string text_camera(const ReportCamera& c) {
  std::string out = printf_string("\ncamera %d: %ld observations, %ld rejected, RMS %.4f px\n",
                                  c.camera.id, c.observations, c.rejected, c.rms_px);
  for (const ReportParameter& p : c.parameters) {
    out += printf_string("  %-6s %+.10e  +- %.3e %-6s %s", p.name.c_str(), p.value, p.sigma,
                         p.unit.c_str(), p.mode.c_str());
    if (p.bootstrap_sigma > 0) out += printf_string("  (bootstrap +- %.3e)", p.bootstrap_sigma);
    out += "\n";
  }
  if (c.correlation.rows() > 0) {
    out += "  correlations:\n        ";
    for (const std::string& n : c.correlation_names) out += printf_string(" %6s", n.c_str());
    out += "\n";
    for (Eigen::Index i = 0; i < c.correlation.rows(); ++i) {
      out += printf_string("  %-6s", c.correlation_names[static_cast<std::size_t>(i)].c_str());
      for (Eigen::Index j = 0; j <= i; ++j) out += printf_string(" %+6.2f", c.correlation(i, j));
      out += "\n";
    }
  }
  return out;
}

std::string text_tests(const CalibrationReport& r) {
  std::string out = "\ntests:\n";
  for (const ReportTest& t : r.tests) {
    out += printf_string("  %-48s %s  statistic %.4f in [%.4f, %.4f]\n", t.name.c_str(),
                         t.passed ? "pass" : "FAIL", t.statistic, t.lower, t.upper);
    if (!t.detail.empty()) out += "    " + t.detail + "\n";
  }
  return out;
}

// ---- html / svg ------------------------------------------------------------------------------

const char* kStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:2px 6px;"
    "text-align:right;font-size:13px}th{background:#f0f0f0}.fail{color:#b00;font-weight:bold}"
    ".pass{color:#070}svg{border:1px solid #ddd;margin:4px;background:#fff}"
    "figure{display:inline-block;margin:4px}figcaption{font-size:12px;text-align:center}"
    ".verdict{font-size:20px;font-weight:bold}.good{color:#070}.weak{color:#a60}"
    ".failed{color:#b00}";

std::string html_summary(const CalibrationReport& r) {
  std::string out = "<h1>" + util::html_escaped(r.title) + "</h1>";
  if (!r.verdict.empty()) {
    out += "<p class='verdict " + util::html_escaped(r.verdict) +
           "'>verdict: " + util::html_escaped(r.verdict) + "</p>";
    if (!r.verdict_reasons.empty()) {
      out += "<ul>";
      for (const std::string& reason : r.verdict_reasons)
        out += "<li>" + util::html_escaped(reason) + "</li>";
      out += "</ul>";
    }
  }
  out += "<table>";
  auto row = [&](const std::string& k, const std::string& v) {
    out += "<tr><th>" + k + "</th><td>" + v + "</td></tr>";
  };
  if (!r.input.empty()) row("input", util::html_escaped(r.input));
  row("observations / unknowns / redundancy",
      printf_string("%ld / %ld / %ld", r.observations, r.unknowns, r.redundancy));
  row("sigma0 (a posteriori)", printf_string("%.4f", r.sigma0));
  row("iterations",
      printf_string("%d, %s", r.iterations, r.converged ? "converged" : "NOT converged"));
  row("outliers removed", std::to_string(r.outliers_removed));
  if (r.wand_length_mm > 0 && !r.wand_lengths_mm.empty()) {
    const MeanSd w = mean_sd(r.wand_lengths_mm);
    row("wand length mean / sd",
        printf_string("%.4f mm / %.4f mm (nominal %.3f mm)", w.mean, w.sd, r.wand_length_mm));
  }
  if (!r.check_points.empty()) row("check points", util::html_escaped(r.check_points));
  if (!r.halves.empty()) row("two halves", util::html_escaped(r.halves));
  for (const std::string& line : r.model_selection) row("model", util::html_escaped(line));
  for (const std::string& line : r.start_search) row("start search", util::html_escaped(line));
  for (const std::string& m : r.messages) row("note", util::html_escaped(m));
  return out + "</table>";
}

std::string html_parameters(const ReportCamera& c) {
  std::string out =
      printf_string("<h3>camera %d</h3><p>%ld observations, %ld rejected, RMS %.4f px</p>",
                    c.camera.id, c.observations, c.rejected, c.rms_px);
  out +=
      "<table><tr><th>parameter</th><th>value</th><th>std. dev.</th><th>bootstrap std. "
      "dev.</th><th>unit</th><th>mode</th></tr>";
  for (const ReportParameter& p : c.parameters) {
    const std::string bootstrap =
        p.bootstrap_sigma > 0 ? printf_string("%.3g", p.bootstrap_sigma) : std::string("-");
    out += printf_string(
        "<tr><td>%s</td><td>%.8g</td><td>%.3g</td><td>%s</td><td>%s</td><td>%s</td></tr>",
        p.name.c_str(), p.value, p.sigma, bootstrap.c_str(), p.unit.c_str(), p.mode.c_str());
  }
  return out + "</table>";
}

// Red for positive, blue for negative correlation, saturation by magnitude.
std::string html_correlation(const ReportCamera& c) {
  if (c.correlation.rows() == 0) return "";
  std::string out = "<table><tr><th></th>";
  for (const std::string& n : c.correlation_names) out += "<th>" + n + "</th>";
  out += "</tr>";
  for (Eigen::Index i = 0; i < c.correlation.rows(); ++i) {
    out += "<tr><th>" + c.correlation_names[static_cast<std::size_t>(i)] + "</th>";
    for (Eigen::Index j = 0; j < c.correlation.cols(); ++j) {
      const double r = c.correlation(i, j);
      const int fade = static_cast<int>(255 - 155 * std::min(1.0, std::abs(r)));
      out += r >= 0
                 ? printf_string("<td style='background:rgb(255,%d,%d)'>%.2f</td>", fade, fade, r)
                 : printf_string("<td style='background:rgb(%d,%d,255)'>%.2f</td>", fade, fade, r);
    }
    out += "</tr>";
  }
  return out + "</table>";
}

// Histogram of the standardised residuals (or of the residual components when w is not
// computed), bins of 0.5 from -5 to 5, with the N(0,1) density for comparison.
std::string svg_histogram(const CalibrationReport& r) {
  constexpr int kBins = 20;
  std::vector<int> bins(kBins, 0);
  long n = 0;
  for (const ReportResidual& res : r.residuals) {
    if (res.rejected) continue;
    const int bin = static_cast<int>(std::floor((res.w + 5.0) / 0.5));
    if (bin >= 0 && bin < kBins) ++bins[static_cast<std::size_t>(bin)];
    ++n;
  }
  const int peak = std::max(1, *std::max_element(bins.begin(), bins.end()));
  std::string out = "<svg width='420' height='220' viewBox='0 0 420 220'>";
  for (int b = 0; b < kBins; ++b) {
    const double h = 180.0 * bins[static_cast<std::size_t>(b)] / peak;
    out += printf_string("<rect x='%d' y='%.1f' width='18' height='%.1f' fill='#69c'/>",
                         10 + 20 * b, 190 - h, h);
  }
  std::string curve;
  for (int i = 0; i <= 100; ++i) {
    const double w = -5.0 + i * 0.1;
    const double expected = n * 0.5 * std::exp(-0.5 * w * w) / std::sqrt(2 * M_PI);
    curve += printf_string("%.1f,%.1f ", 10 + (w + 5.0) * 40, 190 - 180.0 * expected / peak);
  }
  out += "<polyline fill='none' stroke='#c33' points='" + curve + "'/>";
  out +=
      "<text x='10' y='210' font-size='11'>-5</text><text x='205' y='210' font-size='11'>0"
      "</text><text x='395' y='210' font-size='11'>5</text></svg>";
  return "<figure>" + out +
         "<figcaption>standardised residuals w (bars) and N(0,1) (line)</figcaption></figure>";
}

// The image of one camera scaled to `width` px: every measurement as a dot (coverage) and, when
// `scale` > 0, its residual vector magnified by `scale`.
std::string svg_image(const ReportCamera& c, const std::vector<ReportResidual>& residuals,
                      double scale, const char* caption) {
  const double w = c.camera.sensor.width_px, h = c.camera.sensor.height_px;
  const double k = 300.0 / std::max(1.0, w);
  std::string out = printf_string("<svg width='%.0f' height='%.0f'>", w * k, h * k);
  for (const ReportResidual& r : residuals) {
    if (r.camera != c.camera.id) continue;
    const char* colour = r.rejected ? "#c00" : "#369";
    if (scale <= 0) {
      out +=
          printf_string("<circle cx='%.1f' cy='%.1f' r='1' fill='%s'/>", r.u * k, r.v * k, colour);
    } else {
      out += printf_string("<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s'/>", r.u * k,
                           r.v * k, (r.u + scale * r.vu) * k, (r.v + scale * r.vv) * k, colour);
    }
  }
  return "<figure>" + out + "</svg><figcaption>" +
         printf_string("camera %d: %s", c.camera.id, caption) + "</figcaption></figure>";
}

// Plan (X, Y) or elevation (X, Z) of the cameras (triangles pointing along the viewing
// direction) and the object points (dots).
std::string svg_network(const CalibrationReport& r, int vertical_axis, const char* caption) {
  std::vector<Eigen::Vector3d> all = r.points;
  for (const ReportCamera& c : r.cameras) all.push_back(c.camera.projection_centre());
  if (all.empty()) return "";
  Eigen::Vector3d lo = all.front(), hi = all.front();
  for (const auto& p : all) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double span = std::max({hi.x() - lo.x(), hi(vertical_axis) - lo(vertical_axis), 1.0});
  const double k = 380.0 / span;
  auto x = [&](const Eigen::Vector3d& p) { return 10 + (p.x() - lo.x()) * k; };
  auto y = [&](const Eigen::Vector3d& p) {
    return 390 - (p(vertical_axis) - lo(vertical_axis)) * k;
  };
  std::string out = "<svg width='400' height='400'>";
  const std::size_t step = std::max<std::size_t>(1, r.points.size() / 3000);
  for (std::size_t i = 0; i < r.points.size(); i += step) {
    out += printf_string("<circle cx='%.1f' cy='%.1f' r='1' fill='#999'/>", x(r.points[i]),
                         y(r.points[i]));
  }
  for (const ReportCamera& c : r.cameras) {
    const Eigen::Vector3d o = c.camera.projection_centre();
    // the camera looks along -z' of its sensor axes (docs/reference/camera-model.md)
    const Eigen::Vector3d view = -c.camera.rotation().col(2) * (0.08 * span);
    out += printf_string(
        "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#c33' "
        "stroke-width='2'/><circle cx='%.1f' cy='%.1f' r='4' fill='#c33'/>"
        "<text x='%.1f' y='%.1f' font-size='11'>%d</text>",
        x(o), y(o), x(o + view), y(o + view), x(o), y(o), x(o) + 6, y(o) - 6, c.camera.id);
  }
  return "<figure>" + out + "</svg><figcaption>" + caption + "</figcaption></figure>";
}

std::string html_tests(const CalibrationReport& r) {
  std::string out =
      "<table><tr><th>test</th><th>outcome</th><th>statistic</th><th>accepted "
      "interval</th><th>detail</th></tr>";
  for (const ReportTest& t : r.tests) {
    out += "<tr><td>" + util::html_escaped(t.name) + "</td><td class='" +
           (t.passed ? "pass" : "fail") + "'>" + (t.passed ? "pass" : "FAIL") + "</td>" +
           printf_string("<td>%.4f</td><td>[%.4f, %.4f]</td>", t.statistic, t.lower, t.upper) +
           "<td>" + util::html_escaped(t.detail) + "</td></tr>";
  }
  return out + "</table>";
}

// Residual vectors magnified so that the RMS residual draws as ~10 px of the 300-px image.
double residual_scale(const CalibrationReport& r) {
  double sum = 0;
  long n = 0;
  for (const ReportResidual& res : r.residuals) {
    if (!res.rejected) sum += res.vu * res.vu + res.vv * res.vv, ++n;
  }
  const double rms = n ? std::sqrt(sum / n) : 0;
  return rms > 0 ? 10.0 / (rms * 300.0 / 1280.0) : 0;
}

std::string network_figures(const CalibrationReport& report) {
  return "<h2>Network</h2>" + svg_network(report, 1, "plan (X right, Y up)") +
         svg_network(report, 2, "elevation (X right, Z up)") + "</body></html>\n";
}

// A big rig's images as cells, one small figure a camera: where its rays are and the mean
// residual of each cell, at one magnification for all.
std::string html_cells(const CalibrationReport& report) {
  constexpr double kWidth = 200.0;
  const double scale = cell_residual_scale(report, kWidth);
  std::string out = printf_string(
      "<h2>Coverage and residuals by cell</h2><p>Each image in %d x %d cells: grey by the number "
      "of rays kept, red the cell's mean residual x %.0f (a systematic error shows as a "
      "pattern).</p>",
      kGridColumns, kGridRows, scale);
  for (const ReportCamera& c : report.cameras)
    out += svg_cells(c, report.residuals, scale, kWidth, "rays and mean residuals");
  return out;
}

}  // namespace

std::string format_report_text(const CalibrationReport& report) {
  std::string out = text_summary(report);
  for (const ReportCamera& c : report.cameras) out += text_camera(c);
  out += text_tests(report);
  for (const std::string& m : report.messages) out += "note: " + m + "\n";
  return out;
}

std::string format_report_html(const CalibrationReport& report) {
  std::string out = "<!DOCTYPE html><html><head><meta charset='utf-8'><title>" +
                    util::html_escaped(report.title) + "</title><style>" + kStyle +
                    "</style></head><body>";
  out += html_summary(report);
  out += "<h2>Cameras</h2>" + html_camera_overview(report);
  out += "<h2>Tests</h2>" + html_tests(report);
  out += "<h2>Parameters</h2>";
  // A big rig's cameras folded (the table above says which to open), each a click away, and its
  // images drawn as cells.
  const bool fold = draws_cells(report);
  for (const ReportCamera& c : report.cameras) {
    if (fold) out += printf_string("<details><summary>camera %d</summary>", c.camera.id);
    out += html_parameters(c);
    if (c.correlation.rows() > 0) out += "<p>correlations of the interior parameters</p>";
    out += html_correlation(c);
    if (fold) out += "</details>";
  }
  out += "<h2>Residuals</h2>" + svg_histogram(report);
  if (fold) return out + html_cells(report) + network_figures(report);
  const double scale = residual_scale(report);
  out += "<h2>Residual vectors</h2>";
  for (const ReportCamera& c : report.cameras) {
    out += svg_image(c, report.residuals, scale,
                     printf_string("residuals x %.0f (red: rejected)", scale).c_str());
  }
  out += "<h2>Coverage</h2>";
  for (const ReportCamera& c : report.cameras) {
    out += svg_image(c, report.residuals, 0, "measurements over the image");
  }
  return out + network_figures(report);
}

std::string format_residuals_csv(const CalibrationReport& report) {
  std::string out = "camera,frame,u_px,v_px,vu_px,vv_px,w,rejected\n";
  for (const ReportResidual& r : report.residuals)
    out += printf_string("%d,%lld,%.4f,%.4f,%.5f,%.5f,%.4f,%d\n", r.camera,
                         static_cast<long long>(r.frame), r.u, r.v, r.vu, r.vv, r.w,
                         r.rejected ? 1 : 0);
  return out;
}

std::string format_points_csv(const CalibrationReport& report) {
  std::string out = "x_mm,y_mm,z_mm\n";
  for (const Eigen::Vector3d& p : report.points)
    out += printf_string("%.4f,%.4f,%.4f\n", p.x(), p.y(), p.z());
  return out;
}

}  // namespace syncap::calibration
