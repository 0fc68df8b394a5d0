// Millimetres per unit of a length unit as motion files write it ("mm", "cm", "m"; any case).
#pragma once

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>

namespace syncap::io {

inline std::optional<double> millimetres_per(std::string unit) {
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "m") return 1000.0;
  return std::nullopt;
}

}  // namespace syncap::io
