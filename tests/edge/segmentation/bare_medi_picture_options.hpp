// Medi-picture options with every step after classification off (no shadow test, no closing, no
// component filter), so that a test sees the classification itself.
#pragma once

#include "segmentation/medi_picture.hpp"

namespace syncap::edge::testing {

inline MediPictureOptions bare_options() {
  MediPictureOptions options;
  options.remove_shadows = false;
  options.closing_diameter = 0;
  options.min_component_area = 0;
  return options;
}

}  // namespace syncap::edge::testing
