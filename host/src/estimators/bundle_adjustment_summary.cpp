// format_summary of bundle_adjustment.hpp: the result as text a person reads.
#include <string>

#include "estimators/bundle_adjustment.hpp"
#include "estimators/data_snooping.hpp"
#include "util/printf_string.hpp"

namespace syncap::estimators {
namespace {

using util::printf_string;

const auto& kInteriorNames = sensor::InteriorBlock::kNames;

}  // namespace

std::string format_summary(const BundleAdjustmentResult& r) {
  std::string out;
  out += printf_string("adjustments %d, last %d iterations, %s\n", r.adjustments, r.iterations,
                       r.converged ? "converged" : "NOT converged");
  out += printf_string("observations %ld, unknowns %ld, redundancy %ld, sigma0 %.4f\n",
                       r.observations, r.unknowns, r.redundancy, r.sigma0);
  if (r.tests_computed) {
    const auto& v = r.variance_test;
    out +=
        printf_string("variance factor %.4f in [%.4f, %.4f] (chi-square, alpha %.3g): %s\n",
                      v.variance_factor, v.lower, v.upper, v.alpha, v.passed ? "passed" : "FAILED");
    const auto& g = r.goodness_of_fit;
    out += printf_string(
        "goodness of fit y %.2f <= %.2f (%d classes, %ld residuals): %s; KS D %.4f p %.3f\n",
        g.statistic, g.critical, g.bins, g.samples, g.passed ? "passed" : "FAILED", g.ks_distance,
        g.ks_p_value);
    out += printf_string("data snooping |w| > %.2f: %zu removed%s\n", r.critical_w,
                         r.rejected.size(), ambiguous_note(r.rejected).c_str());
  }
  for (const auto& m : r.models) {
    out += "camera model " + m.name + ":";
    const auto values = sensor::interior_block(m.interior);
    for (int i = 0; i < kInteriorSize; ++i) {
      out += printf_string(" %s %.6g +- %.2g", kInteriorNames[i], values[i], m.interior_sigma[i]);
    }
    out += "\n";
  }
  for (const auto& s : r.stations) {
    out += printf_string("station %s: rms %.3f px, %ld measurements, %ld removed\n", s.name.c_str(),
                         s.rms_px, s.measurements, s.rejected);
  }
  for (const auto& m : r.models) {
    const int n = static_cast<int>(m.estimated_interior.size());
    if (n == 0) continue;
    out += "Camera " + m.name;
    for (int i : m.estimated_interior) out += printf_string(" %6s", kInteriorNames[i]);
    out += "\n";
    for (int a = 0; a < n; ++a) {
      out += printf_string("%-6s", kInteriorNames[m.estimated_interior[a]]);
      for (int b = 0; b < n; ++b) {
        out += b < a ? std::string(7, ' ') : printf_string(" %6.3f", m.interior_correlation(a, b));
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace syncap::estimators
