#include "segmentation/masking_options.hpp"

namespace syncap::edge {

bool apply_masking_option(MediPictureOptions& m, std::string_view name, const std::string& v) {
  if (name == "k") {
    m.k = parse_number<float>(v, 0.1f, 100.0f);
  } else if (name == "min-difference") {
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
  } else if (name == "fill-holes") {
    m.max_hole_area = parse_number<int>(v, 0, 1 << 24);
  } else if (name == "closing") {
    m.closing_diameter = parse_number<int>(v, 0, 255);
  } else if (name == "min-area") {
    m.min_component_area = parse_number<int>(v, 0, 1 << 24);
  } else if (name == "update-rate") {
    m.update_rate = parse_number<float>(v, 0.0f, 1.0f);
  } else {
    return false;
  }
  return true;
}

}  // namespace syncap::edge
