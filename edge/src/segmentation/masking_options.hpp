// The medi-picture options as command-line values, shared by syncap-edge (--mask-k 3, also in
// its config file) and `syncap segment-eval` (--k 3), so both check them alike.
#pragma once

#include <charconv>
#include <stdexcept>
#include <string>
#include <string_view>

#include "segmentation/medi_picture.hpp"

namespace syncap::edge {

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

// One medi-picture option by its name without dashes or prefix ("k", "min-difference",
// "shadow-test", "shadow-sigmas", "ncc", "fill-holes", "closing", "min-area", "update-rate"):
// false for another name; throws BadValue for a value out of range.
bool apply_masking_option(MediPictureOptions& m, std::string_view name, const std::string& value);

}  // namespace syncap::edge
