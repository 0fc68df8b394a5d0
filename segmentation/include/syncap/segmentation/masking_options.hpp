// The medi-picture options as command-line values, shared by syncap-edge (--mask-k 3, also in
// its config file) and `syncap segment-eval` (--k 3), so both check them alike.
#pragma once

#include <array>
#include <charconv>
#include <stdexcept>
#include <string>
#include <string_view>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {

// A value an option cannot take; what() is "'TEXT': expected ...", the caller names the option.
class BadValue : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The whole of `text` as a number in low..high (NaN, "2xyz", "" and out-of-range refused).
template <class T>
T parse_number(const std::string& text, T low, T high) {
  T value{};
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !(value >= low && value <= high)) {
    throw BadValue("'" + text + "': expected a number in " + std::to_string(low) + ".." +
                   std::to_string(high));
  }
  return value;
}

// A medi-picture option as a program's --help shows it: its name (syncap-edge prefixes "mask-"),
// its value's name, and its meaning with the unit. The default is each program's own: the value
// in the options it starts from (masking_option_value).
struct MaskingOptionHelp {
  const char* name;
  const char* metavar;
  const char* meaning;
  // The name before the option grammar put the unit in it (docs/reference/cli.md, "Old names"),
  // still taken with a notice; nullptr for none.
  const char* old_name = nullptr;
};

inline constexpr std::array<MaskingOptionHelp, 10> kMaskingOptions{{
    {"k", "K", "interval width in units of d"},
    {"min-difference-dn", "D", "floor of d, DN", "min-difference"},
    {"ncc", "L", "shadow threshold L_NCC (correlation test)"},
    {"shadow-test", "T", "correlation (eqs 5.6-5.11) or common-ratio"},
    {"shadow-sigmas", "S", "common-ratio tolerance in training sigmas"},
    {"fill-holes-px", "A", "fill holes of the mask up to A pixels", "fill-holes"},
    {"closing-px", "D", "elliptical closing diameter, pixels, 0 = none", "closing"},
    {"min-area-px", "A", "smallest component kept, pixels", "min-area"},
    {"update-rate", "R", "slow model update where background, per frame, 0 = frozen"},
    {"illumination", "M", "lsm (correct each frame's illumination, eqs 5.12-5.20) or off"},
}};

// The value the option `name` (of kMaskingOptions) has in `m`, as the option takes it ("3",
// "0.98", "common-ratio"): a program's default in its help.
std::string masking_option_value(const MediPictureOptions& m, std::string_view name);

// One medi-picture option by its name without dashes or prefix ("k", "min-difference-dn",
// "shadow-test", "shadow-sigmas", "ncc", "fill-holes-px", "closing-px", "min-area-px",
// "update-rate", "illumination"):
// false for another name; throws BadValue for a value out of range.
bool apply_masking_option(MediPictureOptions& m, std::string_view name, const std::string& value);

}  // namespace syncap::segmentation
