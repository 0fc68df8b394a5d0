#include "pipeline/recent_values.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::pipeline {

double quantile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  const auto rank =
      static_cast<std::size_t>(std::clamp(std::ceil(p * static_cast<double>(values.size())) - 1,
                                          0.0, static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                   values.end());
  return values[rank];
}

}  // namespace syncap::pipeline
