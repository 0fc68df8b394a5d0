// The report of syncap reconstruct: what a researcher needs to decide whether to trust a
// reconstruction of a recording. Per camera the masking's alignment and each view's agreement
// with the others (its mask against the hull's reprojection from all views: a false region in one
// view is carved away by the others, so a view well below the rest has a bad mask or camera), the
// hull's size and where it stands, the body fit, the calibration's verdict, and warnings where a
// figure is implausible for a person. Written as DIR/report.html with one picture per camera
// (DIR/report/camN.png: the frame with its mask's outline in green and the hull's in red).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "hull/mesh.hpp"
#include "pipeline/frame_work.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::tools {

// What the report keeps of a frame.
struct FrameFigures {
  int64_t frame = 0;
  bool hull = false;  // a hull was built
  std::map<int, double> view_iou;
  Eigen::Vector3d min_mm = Eigen::Vector3d::Zero(), max_mm = Eigen::Vector3d::Zero();
  bool body = false;  // a body was fitted
  double body_rms_mm = 0;
};

// The last stage of the chain: keeps every frame's figures.
class FrameFiguresStage : public pipeline::Stage {
 public:
  const char* name() const override { return "report"; }
  void process(pipeline::FrameWork& work) override;
  const std::vector<FrameFigures>& frames() const { return frames_; }

 private:
  std::vector<FrameFigures> frames_;
};

// One camera's picture for the report: the frame as recorded and its mask.
struct ViewPicture {
  int camera_id = 0;
  cv::Mat image, mask;
};

struct ReportInputs {
  std::string command_line;
  std::string calibration_file;
  std::vector<sensor::CameraModel> cameras;
  std::optional<sensor::CalibrationQuality> quality;
  std::vector<std::string> alignments, notes;
  std::vector<FrameFigures> frames;
  int64_t frames_fed = 0;
  std::optional<double> floor_z_mm;  // the capture volume's bottom (--volume)
  bool body_fitted = true;           // the body stage ran (not --no-body)
  int64_t picture_frame = -1;
  std::vector<ViewPicture> pictures;
  std::optional<hull::Mesh> picture_hull;
  std::string hull_summary, body_summary;
  double mask_ms_per_frame = 0, wall_s = 0;
  std::vector<std::string> files;  // written, relative to the output folder
};

struct ViewAgreement {
  int camera_id = 0;
  double median_iou = 0, min_iou = 0;
  int frames = 0;
};

// The figures the report and the command's summary give, and what is implausible in them.
struct ReportFigures {
  long hulls = 0, bodies = 0;
  std::vector<ViewAgreement> views;
  double median_height_mm = 0;                // the hulls' extent in z
  std::optional<double> median_floor_gap_mm;  // the hulls' lowest point above the floor
  std::vector<std::string> warnings;          // empty: nothing implausible
};
ReportFigures summarise(const ReportInputs& in);

// The figures as lines for the terminal ("views: camera 1 IoU median 0.95 (min 0.90) ...").
std::string summary_lines(const ReportFigures& figures);

// DIR/report.html and DIR/report/camN.png; throws std::runtime_error naming a file that cannot be
// written.
void write_report(const std::filesystem::path& dir, const ReportInputs& in,
                  const ReportFigures& figures);

}  // namespace syncap::tools
