// What a surface check must meet to pass (syncap-hil-surface-check --max-* / --min-*): the
// limits live here, not in the scripts that run the check (hil/run, tests/hil).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "surface_check.hpp"

namespace syncap::compare {

struct SurfaceLimits {
  std::optional<double> max_rms_mm;  // RMS on the true normal, without blunders
  std::optional<std::size_t> min_points;
  std::optional<double> max_blunder_fraction;  // of the points
  std::optional<double> max_rms_error_over_sigma;
  std::optional<double> min_within_3_sigma;  // share of the points
  std::optional<double> min_gain_over_gc3;   // the GC3 peaks' RMS over least squares'
  bool any() const {
    return max_rms_mm || min_points || max_blunder_fraction || max_rms_error_over_sigma ||
           min_within_3_sigma || min_gain_over_gc3;
  }
};

// Each limit `e` misses, in words ("RMS on the normal 1.62 mm > 1.5 mm"); empty: it passes.
std::vector<std::string> surface_failures(const SurfaceErrors& e, const SurfaceLimits& limits);

}  // namespace syncap::compare
