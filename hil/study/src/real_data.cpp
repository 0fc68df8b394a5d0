#include "real_data.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "calibration/calibrate.hpp"
#include "calibration/observations.hpp"
#include "util/printf_string.hpp"

namespace syncap::study {

std::vector<RealDataRun> calibrate_real_data(const std::filesystem::path& calibration_dir) {
  std::vector<std::filesystem::path> folders;
  if (std::filesystem::is_directory(calibration_dir)) {
    for (const auto& entry : std::filesystem::directory_iterator(calibration_dir)) {
      if (entry.is_directory() && entry.path().filename().string().rfind("strawlab-", 0) == 0) {
        folders.push_back(entry.path());
      }
    }
  }
  std::sort(folders.begin(), folders.end());
  std::vector<RealDataRun> runs;
  for (const auto& folder : folders) {
    const auto start = std::chrono::steady_clock::now();
    RealDataRun run;
    run.dataset = folder.filename().string();
    try {
      const calibration::Observations observations = calibration::read_mcsc_observations(folder);
      run.cameras = static_cast<int>(observations.cameras().size());
      run.frames = static_cast<long>(observations.frames.size());
      calibration::CalibrationOptions options;  // as `syncap calibrate --led` with its defaults
      options.wand.led = true;
      const calibration::CalibrationResult result = calibration::calibrate(observations, options);
      run.observations = result.quality.observations;
      run.outliers = result.quality.outliers_removed;
      run.sigma0_px = result.quality.sigma0_px;
      run.rms_px = result.quality.rms_px;
      run.converged = result.adjustment.converged;
      if (!result.quality.per_camera_rms_px.empty()) {
        run.min_camera_rms_px = run.max_camera_rms_px =
            result.quality.per_camera_rms_px.begin()->second;
        for (const auto& [camera, rms] : result.quality.per_camera_rms_px) {
          run.min_camera_rms_px = std::min(run.min_camera_rms_px, rms);
          run.max_camera_rms_px = std::max(run.max_camera_rms_px, rms);
        }
      }
      run.verdict = calibration::verdict_name(result.verdict);
      for (const calibration::Finding& f : result.findings) run.reasons.push_back(f.text);
      for (const sensor::CameraModel& c : result.cameras) {
        run.focal_px += (run.focal_px.empty() ? "" : ", ") +
                        std::to_string(std::lround(c.interior.c / c.sensor.pixel_width_mm));
      }
      run.check_median_px = result.check_points.median_px;
      run.fit_median_px = result.check_points.fit_median_px;
      run.halves_compared = result.halves.compared;
      run.halves_worst_z = result.halves.worst_z;
      if (result.halves.centres_spread_mm > 0) {
        run.halves_centres_percent =
            100.0 * result.halves.centres_rms_mm / result.halves.centres_spread_mm;
      }
      run.ok = true;
    } catch (const std::exception& e) {
      run.failure = e.what();
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    runs.push_back(run);
  }
  return runs;
}

std::string format_real_data(const std::vector<RealDataRun>& runs,
                             const std::filesystem::path& calibration_dir) {
  std::ostringstream out;
  if (runs.empty()) {
    out << "No strawlab-* recordings under `" << calibration_dir.string()
        << "` (set SYNCAP_DATA or --data): this section is left out.\n";
    return out.str();
  }
  out << "The real recordings of strawlab's MultiCamSelfCal test data (flydra, one moved LED, "
         "`$SYNCAP_DATA/calibration/strawlab-*`), calibrated by the code of `syncap calibrate "
         "--input mcsc:DIR --led` with its defaults (calibration/calibrate.hpp: start searched "
         "from the image size and seven fields of view, staged adjustment with model selection, "
         "data snooping). No truth: the figures are the "
         "adjustment's own. An LED gives no scale, and the interior orientation is weakly "
         "determined by a single moved point (thesis Table 4.8).\n\n"
      << "| recording | cameras | frames | accepted observations | outliers removed | "
         "converged | sigma0 x sigma_px [px] | residual RMS [px] | per camera [px] | wall time |\n"
      << "|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const RealDataRun& r : runs) {
    if (!r.ok) {
      out << "| " << r.dataset << " | " << r.cameras << " | " << r.frames
          << " | failed: " << r.failure << " | | | | | | |\n";
      continue;
    }
    std::snprintf(line, sizeof line,
                  "| %s | %d | %ld | %ld | %ld | %s | %.3f | %.3f | %.3f-%.3f | %.1f s |\n",
                  r.dataset.c_str(), r.cameras, r.frames, r.observations, r.outliers,
                  r.converged ? "yes" : "no", r.sigma0_px, r.rms_px, r.min_camera_rms_px,
                  r.max_camera_rms_px, r.seconds);
    out << line;
  }
  out << "\nThe calibration's own checks (docs/design/calibration.md, \"Is it right?\"): its "
         "verdict, "
         "the focal lengths c / pixel size (nominal pixel 0.005 mm), the held-out frames' median "
         "image distance beside the fit's, and the two halves (the first and the second half of "
         "the frames) calibrated "
         "alone: the largest difference of a camera constant in their combined sigmas and the "
         "centres' distance after a similarity fit.\n\n"
      << "| recording | verdict | focal [px] | check points: median / fit's [px] | halves: "
         "worst c difference [sigma] | halves: centres apart [% of spread] |\n"
      << "|---|---|---|---|---|---|\n";
  for (const RealDataRun& r : runs) {
    if (!r.ok) continue;
    const auto halves = [&](double value) {
      return r.halves_compared ? util::printf_string("%.2f", value) : std::string("-");
    };
    out << util::printf_string("| %s | %s | %s | %.3f / %.3f | %s | %s |\n", r.dataset.c_str(),
                               r.verdict.c_str(), r.focal_px.c_str(), r.check_median_px,
                               r.fit_median_px, halves(r.halves_worst_z).c_str(),
                               halves(r.halves_centres_percent).c_str());
  }
  out << "\n";
  for (const RealDataRun& r : runs) {
    for (const std::string& reason : r.reasons) out << "- " << r.dataset << ": " << reason << "\n";
  }
  out << "\n";
  return out.str();
}

}  // namespace syncap::study
