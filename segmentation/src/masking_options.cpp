#include "syncap/segmentation/masking_options.hpp"

namespace syncap::segmentation {
namespace {

// The shortest text that reads back as `v` (0.98f is "0.98", not 0.9800000190734863).
template <class T>
std::string shortest(T v) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return std::string(text, ec == std::errc() ? end : text);
}

}  // namespace

std::string masking_option_value(const MediPictureOptions& m, std::string_view name) {
  if (name == "k") return shortest(m.k);
  if (name == "min-difference-dn") return shortest(m.min_difference);
  if (name == "ncc") return shortest(m.ncc_threshold);
  if (name == "shadow-test")
    return m.shadow_test == ShadowTest::kCorrelation ? "correlation" : "common-ratio";
  if (name == "shadow-sigmas") return shortest(m.shadow_ratio_sigmas);
  if (name == "fill-holes-px") return shortest(m.max_hole_area);
  if (name == "closing-px") return shortest(m.closing_diameter);
  if (name == "min-area-px") return shortest(m.min_component_area);
  if (name == "update-rate") return shortest(m.update_rate);
  if (name == "illumination") return m.correct_illumination ? "lsm" : "off";
  return {};
}

bool apply_masking_option(MediPictureOptions& m, std::string_view name, const std::string& v) {
  if (name == "k") {
    m.k = parse_number<float>(v, 0.1f, 100.0f);
  } else if (name == "min-difference-dn") {
    m.min_difference = parse_number<float>(v, 0.0f, 255.0f);
  } else if (name == "shadow-test") {
    if (v != "correlation" && v != "common-ratio") {
      throw BadValue("'" + v + "': expected correlation or common-ratio");
    }
    m.shadow_test = v == "correlation" ? ShadowTest::kCorrelation : ShadowTest::kCommonRatio;
  } else if (name == "shadow-sigmas") {
    m.shadow_ratio_sigmas = parse_number<float>(v, 0.1f, 100.0f);
  } else if (name == "ncc") {
    m.ncc_threshold = parse_number<float>(v, -1.0f, 1.0f);
  } else if (name == "fill-holes-px") {
    m.max_hole_area = parse_number<int>(v, 0, 1 << 24);
  } else if (name == "closing-px") {
    m.closing_diameter = parse_number<int>(v, 0, 255);
  } else if (name == "min-area-px") {
    m.min_component_area = parse_number<int>(v, 0, 1 << 24);
  } else if (name == "update-rate") {
    m.update_rate = parse_number<float>(v, 0.0f, 1.0f);
  } else if (name == "illumination") {
    if (v != "lsm" && v != "off") throw BadValue("'" + v + "': expected lsm or off");
    m.correct_illumination = v == "lsm";
  } else {
    return false;
  }
  return true;
}

}  // namespace syncap::segmentation
