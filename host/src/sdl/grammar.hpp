// What the parser and the writer share: the parameter names and the design-block tags
// (docs/reference/sdl.md). Internal to host/src/sdl.
#pragma once

#include <array>
#include <string_view>

#include "scene/network.hpp"

namespace syncap::sdl::detail {

// In sensor::InteriorBlock / ExteriorBlock order, as estimators name them.
inline constexpr std::array<std::string_view, 10> kInteriorNames{"c",  "xp", "yp", "k1", "k2",
                                                                 "k3", "p1", "p2", "sc", "sh"};
inline constexpr std::array<std::string_view, 6> kExteriorNames{"X0",    "Y0",  "Z0",
                                                                "omega", "phi", "kappa"};
inline constexpr std::array<std::string_view, 3> kPointNames{"X", "Y", "Z"};

enum class TagKind {
  kFlag,                  // switches a DesignOptions bool; NO switches it off
  kOutputIterations,      // OUTPUT ITERATIONS [INLINE]
  kExactIterations,       // EXACT ITERATIONS n; NO EXACT ITERATIONS
  kMaxIterations,         // MAX ITERATIONS n
  kConvergenceTolerance,  // CONVERGENCE TOLERANCE x
  kSeed,                  // SEED n (SIMULATE's noise)
  kCount,                 // COVARIANCE STRETCHES n, COVARIANCE CELLS n: a DesignOptions int
};

struct DesignTag {
  std::string_view words;  // upper case, separated by one space
  TagKind kind = TagKind::kFlag;
  bool scene::DesignOptions::*flag = nullptr;  // kFlag
  int scene::DesignOptions::*count = nullptr;  // kCount
};

using Design = scene::DesignOptions;
inline const std::array<DesignTag, 21> kDesignTags{{
    {"SIMULATE", TagKind::kFlag, &Design::simulate},
    {"SEED", TagKind::kSeed, nullptr},
    {"UNIFIED LEAST SQUARES", TagKind::kFlag, &Design::unified_least_squares},
    {"RESIDUALS", TagKind::kFlag, &Design::residuals},
    {"CALCULATE COVARIANCE", TagKind::kFlag, &Design::calculate_covariance},
    {"STATISTICAL TESTS", TagKind::kFlag, &Design::statistical_tests},
    {"FORCE COMPLETE", TagKind::kFlag, &Design::force_complete},
    {"EXACT ITERATIONS", TagKind::kExactIterations, nullptr},
    {"MAX ITERATIONS", TagKind::kMaxIterations, nullptr},
    {"CONVERGENCE TOLERANCE", TagKind::kConvergenceTolerance, nullptr},
    {"COVARIANCE STRETCHES", TagKind::kCount, nullptr, &Design::covariance_stretches},
    {"COVARIANCE CELLS", TagKind::kCount, nullptr, &Design::covariance_cells},
    {"IGNORE APPROXIMATES", TagKind::kFlag, &Design::ignore_approximates},
    {"SORT", TagKind::kFlag, &Design::sort},
    {"OUTPUT COEFFICIENT MATRIX", TagKind::kFlag, &Design::output_coefficient_matrix},
    {"OUTPUT MISCLOSURES", TagKind::kFlag, &Design::output_misclosures},
    {"OUTPUT CORRECTIONS", TagKind::kFlag, &Design::output_corrections},
    {"OUTPUT MESSAGES", TagKind::kFlag, &Design::output_messages},
    {"OUTPUT ITERATIONS", TagKind::kOutputIterations, nullptr},
    {"DEBUG", TagKind::kFlag, &Design::debug},
    {"WAIT", TagKind::kFlag, &Design::wait},
}};

}  // namespace syncap::sdl::detail
