#include "calibration/report.hpp"

#include <cmath>

#include "calibration/report_overview.hpp"

#include <gtest/gtest.h>

namespace syncap::calibration {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

CalibrationReport two_camera_report() {
  CalibrationReport r;
  r.input = "csv:<wand>.csv";
  r.observations = 400;
  r.unknowns = 120;
  r.redundancy = 280;
  r.sigma0 = 1.02;
  r.iterations = 7;
  r.converged = true;
  r.outliers_removed = 1;
  r.wand_length_mm = 1000;
  r.wand_lengths_mm = {999.9, 1000.1, 1000.0};
  for (int id = 0; id < 2; ++id) {
    ReportCamera c;
    c.camera.id = id;
    c.camera.sensor = {1280, 1024, 0.0067, 0.0067};
    c.camera.interior.c = 6.0;
    c.camera.exterior = {2000.0 * id, -4000, 2000, 1.3, 0, 0.2 * id};
    c.parameters = {{"c", 6.0012, 0.0009, "mm", "free"}, {"k1", 5.6e-3, 1e-5, "mm^-2", "free"}};
    c.correlation_names = {"c", "k1"};
    c.correlation = Eigen::Matrix2d{{1.0, -0.42}, {-0.42, 1.0}};
    c.rms_px = 0.21;
    c.observations = 200;
    r.cameras.push_back(c);
  }
  for (int i = 0; i < 100; ++i) {
    r.residuals.push_back({i % 2, i, 10.0 * i, 5.0 * i, 0.1, -0.2, 0.03 * (i - 50), i == 7});
    r.points.emplace_back(10.0 * i, 5.0 * i, 1000 + i);
  }
  r.tests = {{"variance factor (chi-square, two-tailed)", 285.6, 235.4, 328.4, true, "ok"},
             {"goodness of fit", 0.31, 0.0, 0.05, false, "residuals are not normal"}};
  return r;
}

TEST(CalibrationReportText, ListsFiguresParametersCorrelationsAndTests) {
  const std::string text = format_report_text(two_camera_report());
  EXPECT_NE(text.find("observations 400, unknowns 120, redundancy 280"), std::string::npos);
  EXPECT_NE(text.find("sigma0 1.0200, iterations 7 (converged), outliers removed 1"),
            std::string::npos);
  EXPECT_NE(text.find("adjusted mean 1000.0000 mm, sd 0.1000 mm (3 frames)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("camera 1: 200 observations, 0 rejected, RMS 0.2100 px"), std::string::npos);
  EXPECT_NE(text.find("  k1      -0.42  +1.00"), std::string::npos) << text;
  EXPECT_NE(text.find("goodness of fit"), std::string::npos);
  EXPECT_EQ(count(text, "FAIL"), 1u);
}

TEST(CalibrationReportHtml, IsSelfContainedWithEveryFigure) {
  const std::string html = format_report_html(two_camera_report());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  // histogram + residual vectors and coverage per camera + plan and elevation
  EXPECT_EQ(count(html, "<svg"), 1u + 2u * 2u + 2u);
  EXPECT_EQ(count(html, "<svg"), count(html, "</svg>"));
  EXPECT_EQ(count(html, "<table"), count(html, "</table>"));
  EXPECT_EQ(count(html, "<script"), 0u);
  EXPECT_EQ(count(html, "src="), 0u);                               // nothing to fetch
  EXPECT_NE(html.find("csv:&lt;wand&gt;.csv"), std::string::npos);  // escaped
  EXPECT_EQ(count(html, "class='fail'"), 1u);
  EXPECT_EQ(count(html, "stroke='#c00'"), 1u);  // the rejected residual drawn in red
  EXPECT_NE(html.find("rgb(189,189,255)"), std::string::npos);  // -0.42 in blue
}

TEST(CalibrationReportTables, HoldEveryResidualAndPointWithAHeader) {
  const CalibrationReport r = two_camera_report();
  const std::string residuals = format_residuals_csv(r);
  EXPECT_EQ(residuals.rfind("camera,frame,u_px,v_px,vu_px,vv_px,w,rejected\n", 0), 0u);
  EXPECT_EQ(count(residuals, "\n"), r.residuals.size() + 1);
  // the eighth measurement: camera 1, frame 7, rejected
  EXPECT_NE(residuals.find("\n1,7,70.0000,35.0000,0.10000,-0.20000,-1.2900,1\n"), std::string::npos)
      << residuals;
  const std::string points = format_points_csv(r);
  EXPECT_EQ(points.rfind("x_mm,y_mm,z_mm\n0.0000,0.0000,1000.0000\n", 0), 0u) << points;
  EXPECT_EQ(count(points, "\n"), r.points.size() + 1);
  EXPECT_NE(points.find("\n10.0000,5.0000,1001.0000\n"), std::string::npos) << points;
}

// Issue 37: a rig of 8 cameras, one of them (id 5) with few rays in one corner of its image and a
// large sigma of c, each ray's residual pointing outwards (a systematic error).
CalibrationReport eight_camera_report() {
  CalibrationReport r;
  for (int id = 0; id < 8; ++id) {
    ReportCamera c;
    c.camera.id = id;
    c.camera.sensor = {1920, 1200, 0.00586, 0.00586};
    c.camera.exterior = {1000.0 * id, -4000, 2000, 1.3, 0, 0};
    const bool weak = id == 5;
    c.parameters = {{"c", 15.2, weak ? 0.3 : 0.01, "mm", "free"},
                    {"X0", 1000.0 * id, weak ? 9.0 : 1.0, "mm", "free"},
                    {"Y0", -4000, 1.0, "mm", "free"},
                    {"Z0", 2000, 1.0, "mm", "free"}};
    c.rms_px = weak ? 0.4 : 0.1 + 0.01 * id;
    const int rays = weak ? 300 : 3000;
    c.observations = rays;
    for (int i = 0; i < rays; ++i) {
      const double u = weak ? 200.0 * (i % 10) / 10.0 : 1920.0 * (i % 60) / 60.0;
      const double v = weak ? 150.0 * (i / 10 % 10) / 10.0 : 1200.0 * (i / 60 % 50) / 50.0;
      r.residuals.push_back({id, i, u, v, 1e-4 * (u - 960), 1e-4 * (v - 600), 0.0, false});
    }
    r.cameras.push_back(c);
  }
  return r;
}

TEST(CalibrationReportHtml, ABigRigGetsOneTableAndOneSmallFigureACamera) {
  const CalibrationReport r = eight_camera_report();
  const std::vector<CameraOverview> overview = camera_overview(r);
  ASSERT_EQ(overview.size(), 8u);
  EXPECT_EQ(overview[5].rays, 300);
  EXPECT_LT(overview[5].coverage, 0.05);  // one corner of 160 cells
  EXPECT_GT(overview[0].coverage, 0.99);
  EXPECT_NEAR(overview[5].c_sigma_share, 0.3 / 15.2, 1e-9);
  EXPECT_NEAR(overview[5].centre_sigma, std::sqrt(81.0 + 2.0), 1e-9);
  const std::string html = format_report_html(r);
  EXPECT_TRUE(draws_cells(r));
  // The histogram, one cell figure a camera, plan and elevation: not 2 x 8 figures of every ray.
  EXPECT_EQ(count(html, "<svg"), 1u + 8u + 2u);
  EXPECT_EQ(count(html, "<circle"), 16u);  // the cameras in plan and elevation, no dot per ray
  EXPECT_NE(html.find("Camera 5 is among the three worst in 5 of the five columns"),
            std::string::npos)
      << html;
  EXPECT_LT(html.size(), 200000u);          // 22 800 rays
  EXPECT_EQ(count(html, "<details>"), 8u);  // each camera's parameters folded
  EXPECT_EQ(count(html, "<table"), count(html, "</table>"));
}

TEST(CalibrationReportHtml, CopesWithAnEmptyReport) {
  const std::string html = format_report_html(CalibrationReport{});
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_EQ(count(html, "<svg"), 1u);  // the (empty) histogram only
}

}  // namespace
}  // namespace syncap::calibration
