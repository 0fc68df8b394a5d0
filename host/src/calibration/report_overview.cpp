#include "calibration/report_overview.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "util/html_escape.hpp"
#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

using util::printf_string;

struct Cell {
  long rays = 0;
  double sum_u = 0.0, sum_v = 0.0;
};

// The accepted rays of one camera by cell, row-major.
std::vector<Cell> cells_of(const ReportCamera& c, const std::vector<ReportResidual>& residuals) {
  std::vector<Cell> cells(kGridColumns * kGridRows);
  const double w = std::max(1, c.camera.sensor.width_px),
               h = std::max(1, c.camera.sensor.height_px);
  for (const ReportResidual& r : residuals) {
    if (r.camera != c.camera.id || r.rejected) continue;
    const int i = std::clamp(static_cast<int>(r.u / w * kGridColumns), 0, kGridColumns - 1);
    const int j = std::clamp(static_cast<int>(r.v / h * kGridRows), 0, kGridRows - 1);
    Cell& cell = cells[static_cast<std::size_t>(j * kGridColumns + i)];
    ++cell.rays;
    cell.sum_u += r.vu;
    cell.sum_v += r.vv;
  }
  return cells;
}

double parameter_sigma(const ReportCamera& c, const std::string& name, double* value = nullptr) {
  for (const ReportParameter& p : c.parameters) {
    if (p.name != name) continue;
    if (value != nullptr) *value = p.value;
    return p.sigma;
  }
  return 0.0;
}

// Indices of the three largest (or smallest) of `values`, where there are more than three.
std::vector<std::size_t> worst_three(const std::vector<double>& values, bool largest) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (values.size() <= 3) return {};
  std::ranges::sort(order, [&](std::size_t a, std::size_t b) {
    return largest ? values[a] > values[b] : values[a] < values[b];
  });
  order.resize(3);
  return order;
}

}  // namespace

std::vector<CameraOverview> camera_overview(const CalibrationReport& report) {
  std::vector<CameraOverview> out;
  for (const ReportCamera& c : report.cameras) {
    CameraOverview o;
    o.id = c.camera.id;
    o.rays = c.observations - c.rejected;
    o.rms_px = c.rms_px;
    const std::vector<Cell> cells = cells_of(c, report.residuals);
    o.coverage = static_cast<double>(
                     std::ranges::count_if(cells, [](const Cell& x) { return x.rays > 0; })) /
                 static_cast<double>(cells.size());
    double focal = 0.0;
    const double c_sigma = parameter_sigma(c, "c", &focal);
    o.c_sigma_share = focal > 0.0 ? c_sigma / focal : 0.0;
    o.centre_sigma =
        std::hypot(parameter_sigma(c, "X0"), parameter_sigma(c, "Y0"), parameter_sigma(c, "Z0"));
    out.push_back(o);
  }
  return out;
}

std::string html_camera_overview(const CalibrationReport& report) {
  const std::vector<CameraOverview> cameras = camera_overview(report);
  if (cameras.empty()) return "";
  std::vector<double> rays, rms, coverage, c_sigma, centre;
  for (const CameraOverview& o : cameras) {
    rays.push_back(static_cast<double>(o.rays));
    rms.push_back(o.rms_px);
    coverage.push_back(o.coverage);
    c_sigma.push_back(o.c_sigma_share);
    centre.push_back(o.centre_sigma);
  }
  // Few rays, little coverage: the smallest are worst; the others the largest.
  const std::vector<std::vector<std::size_t>> worst{
      worst_three(rays, false), worst_three(rms, true), worst_three(coverage, false),
      worst_three(c_sigma, true), worst_three(centre, true)};
  std::map<std::size_t, int> marks;  // how many columns name a camera among their worst
  for (const auto& column : worst) {
    for (const std::size_t i : column) ++marks[i];
  }
  const auto cell = [&](std::size_t column, std::size_t i, const std::string& text) {
    const bool bad = std::ranges::find(worst[column], i) != worst[column].end();
    return std::string("<td>") + (bad ? "<b>" + text + "</b>" : text) + "</td>";
  };
  std::string out =
      "<table><tr><th>camera</th><th>rays kept</th><th>RMS [px]</th><th>image covered "
      "(16 x 10 cells)</th><th>sigma c / c</th><th>sigma of the centre</th></tr>";
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const CameraOverview& o = cameras[i];
    out += printf_string("<tr><td>%d</td>", o.id) + cell(0, i, std::to_string(o.rays)) +
           cell(1, i, printf_string("%.3f", o.rms_px)) +
           cell(2, i, printf_string("%.0f %%", 100.0 * o.coverage)) +
           cell(3, i, printf_string("%.3f %%", 100.0 * o.c_sigma_share)) +
           cell(4, i, printf_string("%.3g", o.centre_sigma)) + "</tr>";
  }
  out += "</table>";
  const auto most = std::ranges::max_element(
      marks, [](const auto& a, const auto& b) { return a.second < b.second; });
  if (most != marks.end() && most->second >= 2) {
    out += printf_string(
        "<p>Camera %d is among the three worst in %d of the five columns (bold): it limits the "
        "result most; more rays over more of its image help it.</p>",
        cameras[most->first].id, most->second);
  }
  return out;
}

bool draws_cells(const CalibrationReport& report) {
  if (report.cameras.size() > 6) return true;
  return std::ranges::any_of(report.cameras,
                             [](const ReportCamera& c) { return c.observations > 2000; });
}

double cell_residual_scale(const CalibrationReport& report, double width) {
  double largest = 0.0, k = 1.0;
  for (const ReportCamera& c : report.cameras) {
    k = width / std::max(1, c.camera.sensor.width_px);
    for (const Cell& cell : cells_of(c, report.residuals)) {
      if (cell.rays == 0) continue;
      largest =
          std::max(largest, std::hypot(cell.sum_u, cell.sum_v) / static_cast<double>(cell.rays));
    }
  }
  const double cell_px = width / kGridColumns;
  return largest > 0.0 ? 0.8 * cell_px / (largest * k) : 0.0;
}

std::string svg_cells(const ReportCamera& camera, const std::vector<ReportResidual>& residuals,
                      double scale, double width, const std::string& caption) {
  const std::vector<Cell> cells = cells_of(camera, residuals);
  const double w = std::max(1, camera.camera.sensor.width_px);
  const double h = std::max(1, camera.camera.sensor.height_px);
  const double k = width / w;
  const double cw = w * k / kGridColumns, ch = h * k / kGridRows;
  long most = 1;
  for (const Cell& c : cells) most = std::max(most, c.rays);
  std::string out = printf_string("<svg width='%.0f' height='%.0f'>", w * k, h * k);
  for (int j = 0; j < kGridRows; ++j) {
    for (int i = 0; i < kGridColumns; ++i) {
      const Cell& c = cells[static_cast<std::size_t>(j * kGridColumns + i)];
      if (c.rays == 0) continue;
      const int grey =
          235 -
          static_cast<int>(std::lround(150.0 * std::sqrt(static_cast<double>(c.rays) / most)));
      out +=
          printf_string("<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='rgb(%d,%d,%d)'/>",
                        i * cw, j * ch, cw, ch, grey, grey, grey + 15);
      if (scale <= 0.0) continue;
      const double x = (i + 0.5) * cw, y = (j + 0.5) * ch;
      const double mu = c.sum_u / static_cast<double>(c.rays),
                   mv = c.sum_v / static_cast<double>(c.rays);
      out += printf_string(
          "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#c33' stroke-width='1.5'/>", x, y,
          x + scale * mu * k, y + scale * mv * k);
    }
  }
  return "<figure>" + out + "</svg><figcaption>" +
         util::html_escaped(printf_string("camera %d: %s", camera.camera.id, caption.c_str())) +
         "</figcaption></figure>";
}

}  // namespace syncap::calibration
