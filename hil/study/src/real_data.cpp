#include "real_data.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "calibration/calibrate.hpp"
#include "calibration/observations.hpp"

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
         "--input mcsc:DIR --led` with its defaults (calibration/calibrate.hpp: start from the "
         "image size alone, two-stage adjustment, data snooping). No truth: the figures are the "
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
  out << "\n";
  return out.str();
}

}  // namespace syncap::study
