#include "surface_limits.hpp"

#include "util/printf_string.hpp"

namespace syncap::compare {

std::vector<std::string> surface_failures(const SurfaceErrors& e, const SurfaceLimits& l) {
  std::vector<std::string> failed;
  if (l.max_rms_mm && !(e.rms_normal_mm <= *l.max_rms_mm))
    failed.push_back(
        util::printf_string("RMS on the normal %.3f mm > %g mm", e.rms_normal_mm, *l.max_rms_mm));
  if (l.min_points && e.points < *l.min_points)
    failed.push_back(util::printf_string("%.0f points < %.0f", static_cast<double>(e.points),
                                         static_cast<double>(*l.min_points)));
  const double blunders = e.points ? static_cast<double>(e.blunders) / e.points : 0.0;
  if (l.max_blunder_fraction && blunders > *l.max_blunder_fraction)
    failed.push_back(util::printf_string("blunders %.2f %% > %.2f %%", 100 * blunders,
                                         100 * *l.max_blunder_fraction));
  if (l.max_rms_error_over_sigma && !(e.rms_normalised <= *l.max_rms_error_over_sigma))
    failed.push_back(
        util::printf_string("RMS error/sigma %.2f > %.2f (the sigmas are far from honest)",
                            e.rms_normalised, *l.max_rms_error_over_sigma));
  if (l.min_within_3_sigma && e.within_3_sigma < *l.min_within_3_sigma)
    failed.push_back(util::printf_string("%.1f %% within 3 sigma < %.1f %%", 100 * e.within_3_sigma,
                                         100 * *l.min_within_3_sigma));
  if (l.min_gain_over_gc3) {
    const double gain = e.rms_normal_mm > 0 ? e.sweep_rms_normal_mm / e.rms_normal_mm : 0.0;
    if (!(gain >= *l.min_gain_over_gc3))
      failed.push_back(util::printf_string("least squares %.1fx more precise than GC3 < %.1fx",
                                           gain, *l.min_gain_over_gc3));
  }
  return failed;
}

}  // namespace syncap::compare
